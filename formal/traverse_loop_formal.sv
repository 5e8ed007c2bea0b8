// SPDX-License-Identifier: Apache-2.0
// traverse_loop_formal: the traverse ring (traverse_loop) under SymbiYosys
// (formal/traverse_loop.sby), for its ray ids: the properties are the bound traverse_loop_assert's
// id checks (ring_ids_distinct, id_enter_free, id_leave_once, id_in_ring: over the ring and the
// park queue) and its control checks (new_ray_only_in_bubble, no_spurious_response, and the park
// queue's park_no_overflow, park_no_underflow, park_in_range, park_only_not_done,
// park_old_leaves, park_old_flag, park_wait_bound, rays_conserved), with PARK = 1 (the ring's
// default is 0) and a park queue of PARK_DEPTH = 2.
//
// The float datapath is cut: the .sby script replaces the register done19_q (the ray at the tail,
// S18 at MUL_LAT 1, has finished: the only way the datapath reaches the ring's control) by a free
// value each clock, so the proof holds for every finishing decision of every ray, whatever the
// arithmetic computes;
// the datapath's own checks (plane_operand_in_range, nk0_is_n_minus_k, bits16_copy,
// live_ray_has_no_result, descent_not_admitted, bdiff_operand_in_range) and the slot counters'
// slot_counter are removed from this model (they are about the arithmetic, the static
// configuration and the tables; simulation checks them).  Everything else is free: the new rays (id, fields,
// whether setup finished them), the result FIFO's full flag, the configuration.  Assumed: the
// height cache answers only a lookup made LOOKUP_LAT clocks earlier (no_spurious_response, the
// cache's side), a new ray's id is not in the ring (id_enter_free: dm_pipeline's slot ids are
// unique, the free list proof), and reset in the first clock; resets may come again at any time
// (in the prove and cover tasks; the BMC task, TRAVERSE_LOOP_ONE_RESET, resets only first).
module traverse_loop_formal
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W       = 5,  // 32 ids for the ring's LOOP_DEPTH (19 or 22) slots
  // park queue entries: 2 (the queue's logic is the same for any depth; the default 12 makes
  // the induction step take the solver more than 10 minutes)
  parameter int unsigned PARK_DEPTH = 2
) (
  input logic              clk_i,
  input logic              rst_ni,
  input cfg_t              cfg_i,
  input logic              new_valid_i,
  input logic [ID_W-1:0]   new_id_i,
  input ray_t              new_ray_i,
  input logic              res_full_i,
  input logic              rs_valid_i,
  input logic              rs_hit_i,
  input logic              rs_err_i,
  input logic [CODE_W-1:0] rs_data_i
);

  logic              new_pop, res_push, lk_valid, lk_wide;
  logic [ID_W-1:0]   res_id;
  result_t           res;
  logic [ADDR_W-1:0] lk_addr;
  logic              st_iter, st_down, st_cross, st_up;
  logic [LOOP_BUSY_W-1:0] busy;

  traverse_loop #(.ID_W(ID_W), .PARK(1'b1), .PARK_DEPTH(PARK_DEPTH)) u_dut (
    .clk_i, .rst_ni, .cfg_i, .hlt_we_i(1'b0), .hlt_waddr_i('0), .hlt_wdata_i('0),
    .new_valid_i, .new_id_i, .new_ray_i, .new_pop_o(new_pop),
    .res_full_i, .res_push_o(res_push), .res_id_o(res_id), .res_o(res),
    .lk_valid_o(lk_valid), .lk_addr_o(lk_addr), .lk_wide_o(lk_wide),
    .rs_valid_i, .rs_hit_i, .rs_err_i, .rs_data_i,
    .st_iter_o(st_iter), .st_down_o(st_down), .st_cross_o(st_cross), .st_up_o(st_up),
    .busy_o(busy));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  always_comb begin
    // (formal_reset: a reset may come again at any time ...)
`ifdef TRAVERSE_LOOP_ONE_RESET
    if (started_q) assume (rst_ni);    // (... but in the BMC task: 24 steps with free resets
                                        // took minutes)
`endif
    assume (!rs_valid_i || u_dut.u_assert.lk_d_q[LOOKUP_LAT-1]);  // the checker's history
    assume (!new_valid_i || !u_dut.u_assert.g_ids.in_ring_q[new_id_i]);
  end

  // What a result carries: a retiring ray's id is the ring's last slot's, a bypassing ray's the
  // new one's (the ring's own wiring, checked here as the results' id).
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      res_id_source: assert (!res_push || res_id == (u_dut.retire ? u_dut.id_q[LOOP_DEPTH-1]
                                                                   : new_id_i));
      res_once:      assert (!res_push || (u_dut.retire != u_dut.bypass));
      c_full_ring:   cover (busy == LOOP_BUSY_W'(LOOP_DEPTH));
      c_retire_admit: cover (u_dut.retire && u_dut.admit);
      c_bypass:      cover (u_dut.bypass && busy != '0);
    end
  end

endmodule
