// SPDX-License-Identifier: Apache-2.0
// traverse_rings_formal: traverse_rings' dealing and result return for the ray ids under
// SymbiYosys (formal/traverse_rings.sby), N_RINGS rings, each the abstract traverse_system of
// formal/traverse_system_abs.sv (holds up to CAP rays, returns each once, in any order, at any
// time).  The properties are the bound traverse_rings_assert's (deal_one, take_one, inside_wrap,
// and the id checks rid_enter_free, rid_leave_once, rid_ring, rid_count) and the wrapper's
// induction invariants:
//   inv_held   an id is inside (the checker's in_q) exactly when the ring it was dealt to holds
//              it, and no other ring does; no ring holds one id twice;
//   inv_show   a ring's result shown is one of the rays it holds;
//   inv_hold   the arbiter's held grant is a ring whose result is still shown.
// Free: the ray stream (valid, id), the result stream's ready, the rings' choices.  Assumed: a
// ray's id is not inside when the stream offers it (rid_enter_free: dm_pipeline's slot ids are
// unique, the free list proof), reset in the first clock and at any time after.
module traverse_rings_formal
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned N_RINGS = 2,
  parameter int unsigned ID_W    = 3,
  parameter int unsigned CAP     = 2    // formal/traverse_system_abs.sv's
) (
  input logic            clk_i,
  input logic            rst_ni,
  input logic            ray_valid_i,
  input logic [ID_W-1:0] ray_id_i,
  input logic            res_ready_i
);

  localparam int unsigned NID   = 1 << ID_W;
  localparam int unsigned SEL_W = (N_RINGS > 1) ? $clog2(N_RINGS) : 1;

  logic            ray_ready, res_valid;
  logic [ID_W-1:0] res_id;

  /* verilator lint_off PINCONNECTEMPTY */
  traverse_rings #(.N_RINGS(N_RINGS), .RAY_ID_W(ID_W), .AXI_ID_W(4)) u_dut (
    .clk_i, .rst_ni,
    .cfg_method_i('0), .cfg_width_i('0), .cfg_height_i('0), .cfg_root_level_i('0),
    .cfg_bits16_i(1'b0), .cfg_base_i('0), .cfg_root_code_i('0),
    .cfg_iter_cap_i('0), .hlt_we_i(1'b0), .hlt_waddr_i('0), .hlt_wdata_i('0),
    .ray_valid_i, .ray_ready_o(ray_ready), .ray_id_i, .ray_u0_i('0), .ray_v0_i('0),
    .ray_du_i('0), .ray_dv_i('0),
    .res_valid_o(res_valid), .res_ready_i, .res_id_o(res_id), .res_t_o(), .res_u_o(),
    .res_v_o(), .res_hit_o(), .res_invalid_o(), .res_capped_o(), .res_err_o(), .res_iters_o(),
    .m_axi_arid(), .m_axi_araddr(), .m_axi_arlen(), .m_axi_arsize(), .m_axi_arburst(),
    .m_axi_arvalid(), .m_axi_arready(1'b1), .m_axi_rid('0), .m_axi_rdata('0), .m_axi_rresp('0),
    .m_axi_rlast(1'b0), .m_axi_rvalid(1'b0), .m_axi_rready(),
    .stat_cycles_o(), .stat_rays_in_o(), .stat_rays_out_o(), .stat_iters_o(), .stat_lookups_o(),
    .stat_crossings_o(), .stat_level_ups_o(), .stat_descents_o(), .clr_stats_i(1'b0),
    .stat_cache_hits_o(), .stat_cache_misses_o(), .stat_mem_bytes_o(), .stat_mem_lines_o(),
    .idle_o());
  /* verilator lint_on PINCONNECTEMPTY */

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // Each ring's held rays, through hierarchy: copies[r][x] = how often ring r holds id x.
  logic [N_RINGS-1:0][NID-1:0][1:0] copies;
  logic [N_RINGS-1:0]               show_ok;
  logic [N_RINGS-1:0]               shown;
  for (genvar r = 0; r < N_RINGS; r++) begin : g_r
    always_comb begin
      copies[r] = '0;
      for (int k = 0; k < CAP; k++) begin
        if (u_dut.g_ring[r].u_sys.h_v_q[k]) begin
          copies[r][u_dut.g_ring[r].u_sys.h_id_q[k]] =
            copies[r][u_dut.g_ring[r].u_sys.h_id_q[k]] + 2'd1;
        end
      end
      show_ok[r] = !u_dut.g_ring[r].u_sys.o_v_q
                   || u_dut.g_ring[r].u_sys.h_v_q[u_dut.g_ring[r].u_sys.o_k_q];
      shown[r]   = u_dut.g_ring[r].u_sys.o_v_q;
    end
  end

  logic held_ok;
  always_comb begin
    held_ok = 1'b1;
    for (int x = 0; x < NID; x++) begin
      for (int r = 0; r < N_RINGS; r++) begin
        if (copies[r][x] != ((u_dut.u_assert.g_ids.in_q[x]
                              && u_dut.u_assert.g_ids.ring_q[x] == SEL_W'(r)) ? 2'd1 : 2'd0)) begin
          held_ok = 1'b0;
        end
      end
      if (u_dut.u_assert.g_ids.in_q[x] && 32'(u_dut.u_assert.g_ids.ring_q[x]) >= N_RINGS) begin
        held_ok = 1'b0;
      end
    end
  end

  always_comb begin
    assume (!ray_valid_i || !u_dut.u_assert.g_ids.in_q[ray_id_i]);
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      inv_held: assert (held_ok);
      inv_show: assert (&show_ok);
      inv_hold: assert (!u_dut.u_res_arb.hold_q || shown[u_dut.u_res_arb.hold_sel_q]);
      c_both_busy:  cover (u_dut.inside_q[0] == 2 && u_dut.inside_q[N_RINGS-1] == 2);
      c_out_of_order: cover (res_valid && res_ready_i && res_id == ID_W'(1)
                             && u_dut.u_assert.g_ids.in_q[0]);
      c_wait:       cover (res_valid && !res_ready_i && u_dut.inside_q[0] != 0
                           && u_dut.inside_q[N_RINGS-1] != 0);
    end
  end

endmodule
