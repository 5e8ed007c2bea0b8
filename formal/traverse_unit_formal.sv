// SPDX-License-Identifier: Apache-2.0
// traverse_unit_formal: traverse_unit's composition for the ray ids under SymbiYosys
// (formal/traverse_unit.sby): the real credit counter, setup FIFO, result FIFO, occupancy
// counter and configuration register of traverse_unit, with setup and the ring each the
// abstract model of formal/traverse_setup_abs.sv (every ray out LAT clocks after it went in,
// with its id) and formal/traverse_loop_abs.sv (holds up to CAP rays, takes the setup FIFO's
// head, returns each ray once through the result FIFO, or passes the head straight through).
// Those two are the guarantees the real blocks' own proofs give (formal/traverse_setup.sby,
// formal/traverse_loop.sby); this proof composes them.  The properties are the bound
// traverse_unit_assert's (slot_conservation, setup_credits, setup_fifo_never_overflows,
// uid_leave_once, res_out_stable; uid_enter_free and ray_in_stable are the user's obligations,
// assumed here), the bound traverse_fifo_assert's of both FIFOs, and the wrapper's:
//   inv_held_inside   every id held in a place (a setup stage, the setup FIFO's head register
//                     or RAM, a ring slot, the result FIFO's head register or RAM) is inside
//                     the unit (the checker's in_unit_q);
//   inv_distinct      no two places hold the same id;
//   inv_inside_count  the ids inside number inflight_q, which slot_conservation equates with
//                     the rays held: with the two above, every id inside is in exactly one
//                     place, and an id not inside in none.
// Free: the ray stream (valid, id; the ray's fields 0: the datapath is cut), the result
// stream's ready, the abstract blocks' choices.  Assumed: reset in the first clock (and at any
// time after), a ray's id not inside when offered, an offered ray held until taken.
module traverse_unit_formal
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W      = 3,
  parameter int unsigned SF_DEPTH  = 4,   // setup FIFO (> the abstract setup's LAT)
  parameter int unsigned RF_DEPTH  = 2,   // result FIFO
  parameter int unsigned SETUP_LAT = 3,   // formal/traverse_setup_abs.sv's LAT
  parameter int unsigned CAP       = 2    // formal/traverse_loop_abs.sv's CAP
) (
  input logic            clk_i,
  input logic            rst_ni,
  input logic            ray_valid_i,
  input logic [ID_W-1:0] ray_id_i,
  input logic            res_ready_i
);

  localparam int unsigned NID  = 1 << ID_W;
  localparam int unsigned SF_W = ID_W + $bits(ray_t);
  localparam int unsigned RF_W = ID_W + $bits(result_t);

  logic            ray_ready, res_valid;
  logic [ID_W-1:0] res_id;

  /* verilator lint_off PINCONNECTEMPTY */
  traverse_unit #(.ID_W(ID_W), .SETUP_FIFO_DEPTH(SF_DEPTH), .RES_FIFO_DEPTH(RF_DEPTH)) u_dut (
    .clk_i, .rst_ni,
    .cfg_method_i('0), .cfg_width_i('0), .cfg_height_i('0), .cfg_root_level_i('0),
    .cfg_bits16_i(1'b0), .cfg_base_i('0), .cfg_root_code_i('0),
    .cfg_iter_cap_i('0), .hlt_we_i(1'b0), .hlt_waddr_i('0), .hlt_wdata_i('0),
    .ray_valid_i, .ray_ready_o(ray_ready), .ray_id_i, .ray_u0_i('0), .ray_v0_i('0),
    .ray_du_i('0), .ray_dv_i('0),
    .res_valid_o(res_valid), .res_ready_i, .res_id_o(res_id), .res_t_o(), .res_u_o(),
    .res_v_o(), .res_hit_o(), .res_invalid_o(), .res_capped_o(), .res_err_o(), .res_iters_o(),
    .lk_valid_o(), .lk_addr_o(), .lk_wide_o(), .rs_valid_i(1'b0), .rs_hit_i(1'b0),
    .rs_err_i(1'b0), .rs_data_i('0),
    .stat_cycles_o(), .stat_rays_in_o(), .stat_rays_out_o(), .stat_iters_o(), .stat_lookups_o(),
    .stat_crossings_o(), .stat_level_ups_o(), .stat_descents_o(), .idle_o());
  /* verilator lint_on PINCONNECTEMPTY */

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // The places a ray can be in: pv[p] (it holds a ray), pid[p] (its id).  Setup stages, the
  // setup FIFO's head register and RAM entries (in order from the read pointer), the ring's
  // slots, the result FIFO's head register and RAM entries.  The two FIFOs' places are read
  // here, each by its own hierarchical names (a module bound into traverse_fifo that lists its
  // places, read by the RAM's upward reference, gave the same proof at 26 s instead of 8).
  localparam int unsigned P = SETUP_LAT + 1 + SF_DEPTH + CAP + 1 + RF_DEPTH;
  logic [P-1:0]           pv;
  logic [P-1:0][ID_W-1:0] pid;
  always_comb begin
    int p;
    p = 0;
    for (int s = 0; s < SETUP_LAT; s++) begin
      pv[p]  = u_dut.u_setup.v_q[s];
      pid[p] = u_dut.u_setup.id_q[s];
      p++;
    end
    pv[p]  = u_dut.u_setup_fifo.cnt_q != '0;
    pid[p] = u_dut.u_setup_fifo.g_out_reg.hd_q[SF_W-1 -: ID_W];
    p++;
    for (int k = 0; k < SF_DEPTH; k++) begin
      pv[p]  = 32'(k) < 32'(u_dut.u_setup_fifo.m_cnt);
      pid[p] = u_dut.u_setup_fifo.mem_q[u_dut.u_setup_fifo.rp_q + $clog2(SF_DEPTH)'(k)]
                                       [SF_W-1 -: ID_W];
      p++;
    end
    for (int k = 0; k < CAP; k++) begin
      pv[p]  = u_dut.u_loop.h_v_q[k];
      pid[p] = u_dut.u_loop.h_id_q[k];
      p++;
    end
    pv[p]  = u_dut.u_res_fifo.cnt_q != '0;
    pid[p] = u_dut.u_res_fifo.g_out_reg.hd_q[RF_W-1 -: ID_W];
    p++;
    for (int k = 0; k < RF_DEPTH; k++) begin
      pv[p]  = 32'(k) < 32'(u_dut.u_res_fifo.m_cnt);
      pid[p] = u_dut.u_res_fifo.mem_q[u_dut.u_res_fifo.rp_q + $clog2(RF_DEPTH)'(k)]
                                     [RF_W-1 -: ID_W];
      p++;
    end
  end

  // held_inside: every id held is inside; distinct: no two places hold one id.
  logic held_inside, distinct;
  always_comb begin
    held_inside = 1'b1;
    distinct    = 1'b1;
    for (int a = 0; a < P; a++) begin
      if (pv[a] && !u_dut.u_assert.g_ids.in_unit_q[pid[a]]) held_inside = 1'b0;
      for (int b = a + 1; b < P; b++) begin
        if (pv[a] && pv[b] && pid[a] == pid[b]) distinct = 1'b0;
      end
    end
  end

  always_comb begin
    assume (!ray_valid_i || !u_dut.u_assert.g_ids.in_unit_q[ray_id_i]);
    assume (!u_dut.u_assert.ray_wait_q
            || (ray_valid_i && ray_id_i == u_dut.u_assert.ray_q[ID_W+4*24-1 -: ID_W]));
  end

  logic [$clog2(SF_DEPTH):0] sf_count;
  assign sf_count = u_dut.sf_count;
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      inv_held_inside: assert (held_inside);
      inv_distinct: assert (distinct);
      inv_inside_count: assert (32'($countones(u_dut.u_assert.g_ids.in_unit_q))
                                == 32'(u_dut.inflight_q));
      c_every_place: cover (u_dut.su_busy != '0 && sf_count != '0 && u_dut.lp_busy == 5'(CAP)
                            && res_valid);
      c_setup_fifo_full: cover (32'(sf_count) == SF_DEPTH);
      c_credit_stall: cover (ray_valid_i && !ray_ready && u_dut.su_in_ready);
      c_bypass: cover (u_dut.u_loop.bypass && u_dut.lp_busy != '0);
      c_result_wait: cover (res_valid && !res_ready_i && u_dut.rf_full);
    end
  end

endmodule
