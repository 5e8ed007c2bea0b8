// SPDX-License-Identifier: Apache-2.0
// dm_pipeline_slots_formal: the slot ids of dm_pipeline as a whole under SymbiYosys
// (formal/dm_pipeline_slots.sby): the free list, FIFO #0, the miss FIFO, the out FIFO, the
// output register, the credits of FIFO #0 and of the out FIFO and dm_pipeline's control are the
// real ones; the units that carry a slot between them are abstracted to what their own proofs
// give (formal/slot_set_abs.sv: every slot taken comes back once, after any delay, in any order):
//   u_vc  view_calc, from a fragment's acceptance (acc, the free list's head) to its output
//         (vc_valid, the tag's slot), never stalled;
//   u_tr  traverse_rings, from FIFO #0's read (its head's slot) to its result (res_valid,
//         res_id), held until res_ready takes it; whether the result is a hit, and when the
//         rings take a ray (ray_ready), are free;
//   u_be  the back end, from a hit's admission (hit_adm, res_id) to shade_unit's output
//         (sh_valid, its tag's slot): mip_level, tex_addr, the request FIFOs, tex_cache,
//         tex_filter, the colour / normal-map pairing, shade_unit.
// dm_pipeline is the top (every input free); the real units are black boxes cut to free outputs
// (the .sby script), and their outputs that carry the ids are assumed equal to the abstract
// units' (the rest, the datapath, stays free).  This checker is bound into dm_pipeline here, for
// formal only.  Assumed too: reset in the first clock; resets may come again at any time.
//
// Proven (with the bound dm_pipeline_assert's slot_enter_free, slot_trav_once, slot_out_once,
// slot_count, slots_conserved, merge_enter_free, merge_leave_once, merge_count, out_credit,
// fifo0_credit, frag_spacing, hit_spacing, the four FIFOs' and the two credits' bound checks,
// the abstract units' abs_enter_free): the induction invariants, for every slot s (the
// shadows use_q, trav_q, mg_q of dm_pipeline_assert; a place's count is how many entries hold
// s):
//   inv_free   while the free list is filled after reset, it holds the slots below init_cnt_q
//              once each and no slot is in use; after that, s is in the free list (once)
//              exactly when not in use;
//   inv_trav   s is in the traversal (trav_q) exactly when it is in one of view_calc, FIFO #0
//              (its head register or RAM) and the rings, once;
//   inv_merge  s is in the merge (mg_q) exactly when it is in one of the miss FIFO, the out FIFO
//              and the output register (holding a pixel), once;
//   inv_use    s is in use (use_q) exactly when it is in one of the traversal, the back end and
//              the merge;
//   inv_init   the fill counter stays below SLOTS while filling;
//   inv_spacing  the admission's spacing registers (acc_q; the hit grid hit_ph_q) agree with the
//              checker's clocks since the last fragment / hit (frag_spacing, hit_spacing: what
//              view_calc's and tex_addr's proofs assume of their input);
//   inv_f0_credit   FIFO #0's credit counts the slots in view_calc;
//   inv_out_credit  the out credit counts the slots in the back end and in the out FIFO.
`ifdef FORMAL
module dm_pipeline_slots_formal #(
  parameter int unsigned SLOTS      = 4,   // dm_pipeline's parameters
  parameter int unsigned F0_DEPTH   = 2,
  parameter int unsigned MISS_DEPTH = 2,
  parameter int unsigned OUT_DEPTH  = 2
) (
  input logic clk_i,
  input logic rst_ni
);

  localparam int unsigned SLOT_W = $clog2(SLOTS);
  localparam int unsigned F0_W   = SLOT_W + 4 * 24;   // FIFO #0's word {slot, u0, v0, du, dv}
  localparam int unsigned OUT_W  = SLOT_W + 1 + 24;   // the out FIFO's word {slot, err, rgb}
  localparam int unsigned FW     = $clog2(F0_DEPTH);
  localparam int unsigned MW     = $clog2(MISS_DEPTH);
  localparam int unsigned OW     = $clog2(OUT_DEPTH);

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // ---- the abstract units ----------------------------------------------------------------------
  logic              vc_v, tr_v, be_v;
  logic [SLOT_W-1:0] vc_s, tr_s, be_s;
  logic [SLOTS-1:0]  vc_held, tr_held, be_held;

  slot_set_abs #(.SLOTS(SLOTS), .HOLD(1'b0)) u_vc (
    .clk_i, .rst_ni, .in_valid_i(dm_pipeline.acc), .in_slot_i(dm_pipeline.free_head),
    .out_valid_o(vc_v), .out_ready_i(1'b1), .out_slot_o(vc_s), .held_o(vc_held));
  slot_set_abs #(.SLOTS(SLOTS), .HOLD(1'b1)) u_tr (
    .clk_i, .rst_ni, .in_valid_i(dm_pipeline.f0_rd),
    .in_slot_i(dm_pipeline.f0_head[F0_W-1 -: SLOT_W]),
    .out_valid_o(tr_v), .out_ready_i(dm_pipeline.res_ready), .out_slot_o(tr_s),
    .held_o(tr_held));
  slot_set_abs #(.SLOTS(SLOTS), .HOLD(1'b0)) u_be (
    .clk_i, .rst_ni, .in_valid_i(dm_pipeline.hit_adm), .in_slot_i(dm_pipeline.res_id),
    .out_valid_o(be_v), .out_ready_i(1'b1), .out_slot_o(be_s), .held_o(be_held));

  // The cut units' id outputs are the abstract units'.
  always_comb begin
    assume (dm_pipeline.vc_valid == vc_v);
    assume (!vc_v || dm_pipeline.vc_slot == vc_s);
    assume (dm_pipeline.res_valid == tr_v);
    assume (!tr_v || dm_pipeline.res_id == tr_s);
    assume (dm_pipeline.sh_valid == be_v);
    assume (!be_v || dm_pipeline.sh_tag[SLOT_W:1] == be_s);
  end

  // ---- each slot's places ----------------------------------------------------------------------
  logic [SLOTS-1:0] use_s, trav_s, mg_s;
  assign use_s  = dm_pipeline.u_assert.use_q;
  assign trav_s = dm_pipeline.u_assert.trav_q;
  assign mg_s   = dm_pipeline.u_assert.mg_q;

  logic [SLOTS-1:0] ok_free, ok_trav, ok_merge, ok_use;
  always_comb begin
    int n_fl, n_f0, n_mg;
    for (int s = 0; s < SLOTS; s++) begin
      // the free list (its head register, then its RAM from the read pointer)
      n_fl = 0;
      if (dm_pipeline.u_free.cnt_q != '0 && dm_pipeline.u_free.g_out_reg.hd_q == SLOT_W'(s))
        n_fl++;
      for (int k = 0; k < SLOTS; k++) begin
        if (32'(k) < 32'(dm_pipeline.u_free.m_cnt)
            && dm_pipeline.u_free.mem_q[dm_pipeline.u_free.rp_q + SLOT_W'(k)] == SLOT_W'(s))
          n_fl++;
      end
      // FIFO #0 (head register, RAM)
      n_f0 = 0;
      if (dm_pipeline.u_fifo0.cnt_q != '0
          && dm_pipeline.u_fifo0.g_out_reg.hd_q[F0_W-1 -: SLOT_W] == SLOT_W'(s))
        n_f0++;
      for (int k = 0; k < F0_DEPTH; k++) begin
        if (32'(k) < 32'(dm_pipeline.u_fifo0.m_cnt)
            && dm_pipeline.u_fifo0.mem_q[dm_pipeline.u_fifo0.rp_q + FW'(k)][F0_W-1 -: SLOT_W]
               == SLOT_W'(s))
          n_f0++;
      end
      // the merge: the miss FIFO, the out FIFO, the output register
      n_mg = 0;
      for (int k = 0; k < MISS_DEPTH; k++) begin
        if (32'(k) < 32'(dm_pipeline.u_miss.cnt_q)
            && dm_pipeline.u_miss.mem_q[dm_pipeline.u_miss.rp_q + MW'(k)] == SLOT_W'(s))
          n_mg++;
      end
      for (int k = 0; k < OUT_DEPTH; k++) begin
        if (32'(k) < 32'(dm_pipeline.u_out.cnt_q)
            && dm_pipeline.u_out.mem_q[dm_pipeline.u_out.rp_q + OW'(k)][OUT_W-1 -: SLOT_W]
               == SLOT_W'(s))
          n_mg++;
      end
      if (dm_pipeline.o_valid_q && dm_pipeline.o_slot_q == SLOT_W'(s)) n_mg++;

      if (dm_pipeline.init_q) begin
        ok_free[s] = !use_s[s] && n_fl == int'(32'(s) < 32'(dm_pipeline.init_cnt_q));
      end else begin
        ok_free[s] = n_fl == int'(!use_s[s]);
      end
      ok_trav[s]  = int'(vc_held[s]) + n_f0 + int'(tr_held[s]) == int'(trav_s[s]);
      ok_merge[s] = n_mg == int'(mg_s[s]);
      ok_use[s]   = int'(trav_s[s]) + int'(be_held[s]) + int'(mg_s[s]) == int'(use_s[s]);
    end
  end

  // The admission's spacing registers agree with the checker's counters of clocks since the last
  // one (saturating at 3): acc_q ([k] a fragment accepted k + 1 clocks ago), and the hit grid
  // hit_ph_q (a hit only where it is 0, so it is age + 1 within 3 clocks of a hit).
  function automatic logic age_ok(input logic [2:0] adm_q, input logic [1:0] age_q);
    return (adm_q == 3'b000 && age_q == 2'd3) || (adm_q == 3'b001 && age_q == 2'd0)
        || (adm_q == 3'b010 && age_q == 2'd1) || (adm_q == 3'b100 && age_q == 2'd2);
  endfunction

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      inv_free:  assert (ok_free == '1);
      inv_trav:  assert (ok_trav == '1);
      inv_merge: assert (ok_merge == '1);
      inv_use:   assert (ok_use == '1);
      inv_init:  assert (!dm_pipeline.init_q || 32'(dm_pipeline.init_cnt_q) < SLOTS);
      inv_spacing: assert (age_ok(dm_pipeline.acc_q, dm_pipeline.u_assert.frag_age_q)
                           && (dm_pipeline.u_assert.hit_age_q == 2'd3
                               || dm_pipeline.hit_ph_q == dm_pipeline.u_assert.hit_age_q + 2'd1));
      inv_f0_credit:  assert (32'(dm_pipeline.vc_cnt) == 32'($countones(vc_held)));
      inv_out_credit: assert (32'(dm_pipeline.hit_cnt)
                              == 32'($countones(be_held)) + 32'(dm_pipeline.out_count));
    end
  end

  // ---- covers ----------------------------------------------------------------------------------
  // A hit's pixel out and a miss's; a slot back in the free list from its pixel while another
  // slot is in use (the loop through the free list closed); three slots in use at once, one each
  // in the traversal, the back end and the merge.  (Every slot in use and a slot taken again by a
  // later fragment were reached in a cover run at depth 24, at steps 19 and 23: a fragment is
  // accepted every 4th clock at most, so the fourth fragment comes 12 clocks after the first;
  // that cover task took 54 s of process time instead of 4.)
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      c_hit_out:    cover (dm_pipeline.px_done && dm_pipeline.o_hit_q);
      c_miss_out:   cover (dm_pipeline.px_done && !dm_pipeline.o_hit_q);
      c_returned:   cover (dm_pipeline.free_push && !dm_pipeline.init_q
                           && dm_pipeline.live_q > (SLOT_W+1)'(1));
      c_spread:     cover (trav_s != '0 && be_held != '0 && mg_s != '0);
    end
  end

endmodule

bind dm_pipeline dm_pipeline_slots_formal #(
  .SLOTS(SLOTS), .F0_DEPTH(F0_DEPTH), .MISS_DEPTH(MISS_DEPTH), .OUT_DEPTH(OUT_DEPTH)
) u_slots (.clk_i, .rst_ni);
`endif
