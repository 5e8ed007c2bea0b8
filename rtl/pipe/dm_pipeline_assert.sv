// SPDX-License-Identifier: Apache-2.0
// dm_pipeline_assert: the simulation checks of dm_pipeline, bound into every instance (the
// `bind` at the end of this file; not in synthesis).  Immediate assertions in a clocked block, in
// the form the formal flow's front end (Yosys read_slang) accepts: "disable iff (!rst_ni)" is a
// guard on rst_ni, "a |=> b" a guard on a registered copy of a, $stable a comparison with a
// registered copy.
//
//   slots_conserved  free + live = SLOTS once the free list is filled;
//   fifo0_credit     the credits hold: FIFO #0 never sees a write while full;
//   req_credit       ... nor the texture-request FIFO a lookup's address while full;
//   frag_spacing     view_calc shares its float units over 4 clocks: a fragment accepted every
//                    4th clock at most (counted here apart from acc_q);
//   hit_spacing      one address unit serves both textures: a hit every 4th clock at most
//                    (counted here apart from the admission's grid, hit_ph_q);
//   nl_tag_held      the held normal-map lookup reads mip_level's tag a clock after its result:
//                    still the hit's;
//   addr_pairs       a hit's two lookups come out of tex_addr 2 clocks apart, colour first, for
//                    the same slot;
//   out_credit       the shaded-pixel FIFO never sees a write while full;
//   px_stable        the pixel stream's payload holds while stalled;
//   tc_req_held      the texture request stays valid while stalled;
//   tf_pairs         the filter's results alternate colour, normal map, and a normal-map result
//                    belongs to the pixel of the colour result before it (what the pairing into
//                    shade_unit relies on).
// Slot ids, each leaving once: a shadow of the slots in use (use_q: set when a fragment takes
// the free list's head, cleared when its pixel leaves) and of those in the traversal (trav_q:
// set with use_q, cleared when traverse_rings' result for the slot is taken):
//   slot_enter_free  a fragment takes a slot not in use (the free list gives no id twice);
//   slot_trav_once   a traversal result is for a slot in the traversal (each slot's ray comes
//                    back once, and only for a fragment inside);
//   slot_out_once    a pixel leaves for a slot in use whose traversal is over (one pixel per
//                    fragment, after its ray);
//   slot_count       the slots in use = live_q (none lost: with slots_conserved, every slot is
//                    in the free list or in use).
// The merge into the output register (mg_q: the slots between the miss FIFO or the out FIFO and
// the pixel out): merge_enter_free, merge_leave_once, merge_count (below).
// The pieces of this path are proven in formal (docs/formal.md): the free list, FIFO #0's
// admission and order, traverse_rings' dealing and return, the traverse ring's ids, the merge
// (formal/dm_pipeline.sby: merge_leave_once, merge_count, px_stable; merge_enter_free and
// out_credit assumed there); their composition with view_calc, traverse_rings and the back end
// abstracted (formal/dm_pipeline_slots.sby: slot_*, slots_conserved, merge_*, out_credit,
// fifo0_credit, frag_spacing, hit_spacing).
`ifndef SYNTHESIS
module dm_pipeline_assert #(
  parameter int unsigned PIX_W = 20,   // dm_pipeline's PIX_W
  parameter int unsigned SLOTS = 128   // dm_pipeline's SLOTS
) (
  input logic                           clk_i,
  input logic                           rst_ni,
  input logic                           init_i,        // init_q: filling the free list
  input logic [$clog2(SLOTS):0]         free_count_i,
  input logic [$clog2(SLOTS):0]         live_i,        // live_q
  input logic                           f0_wr_i,
  input logic                           f0_full_i,
  input logic                           ta_valid_i,
  input logic                           ta_tex_i,
  input logic [$clog2(SLOTS)-1:0]       ta_slot_i,
  input logic                           rq_c_full_i,
  input logic                           rq_n_full_i,
  input logic                           hit_adm_i,
  input logic                           nl_valid_i,    // nl_valid_q
  input logic [$clog2(SLOTS)+48-1:0]    mip_tag_i,     // mip_tag (MIP_TAG_W bits)
  input logic                           sh_valid_i,
  input logic                           out_full_i,
  input logic                           px_valid_i,    // px_valid_o
  input logic                           px_ready_i,
  input logic [PIX_W-1:0]               px_id_i,       // px_id_o
  input logic [2:0][7:0]                px_rgb_i,      // px_rgb_o
  input logic                           tc_req_valid_i,
  input logic                           tc_req_ready_i,
  input logic                           tf_valid_i,
  input logic                           tf_nmap_i,     // tf_tag[1]: a normal-map result
  input logic [$clog2(SLOTS)-1:0]       sh_in_slot_i,
  input logic                           acc_i,         // acc: a fragment takes a slot
  input logic [$clog2(SLOTS)-1:0]       free_head_i,   // free_head: the slot it takes
  input logic                           res_take_i,    // res_valid && res_ready
  input logic [$clog2(SLOTS)-1:0]       res_id_i,      // res_id: the slot of the result
  input logic [$clog2(SLOTS)-1:0]       o_slot_i,      // o_slot_q: the slot of the pixel out
  input logic                           miss_wr_i,     // miss_wr: a result into the miss FIFO
  input logic [$clog2(SLOTS)-1:0]       sh_slot_i,     // the slot of shade_unit's pixel (sh_tag)
  input logic [31:0]                    miss_count_i,  // the miss FIFO's count
  input logic [31:0]                    out_count_i    // the shaded-pixel FIFO's count
);

  localparam int unsigned SLOT_W    = $clog2(SLOTS);
  localparam int unsigned MIP_TAG_W = SLOT_W + 48;

  // Clocks since the last fragment accepted, saturating at 3.
  logic [1:0] frag_age_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni)                 frag_age_q <= 2'd3;
    else if (acc_i)              frag_age_q <= 2'd0;
    else if (frag_age_q != 2'd3) frag_age_q <= frag_age_q + 2'd1;
  end

  // Clocks since the last hit admitted, saturating at 3.
  logic [1:0] hit_age_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni)        hit_age_q <= 2'd3;
    else if (hit_adm_i) hit_age_q <= 2'd0;
    else if (hit_age_q != 2'd3) hit_age_q <= hit_age_q + 2'd1;
  end

  // [k]: a colour lookup came out of tex_addr k + 1 clocks ago, and its slot.
  logic [1:0]        ta_col_q;
  logic [SLOT_W-1:0] ta_col_slot_q [2];
  always_ff @(posedge clk_i) begin
    if (!rst_ni) ta_col_q <= '0;
    else         ta_col_q <= {ta_col_q[0], ta_valid_i && !ta_tex_i};
    ta_col_slot_q[0] <= ta_slot_i;
    ta_col_slot_q[1] <= ta_col_slot_q[0];
  end

  // A colour result of the filter waits for its normal-map result, and its slot.
  logic              tf_col_pend_q;
  logic [SLOT_W-1:0] tf_col_slot_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) tf_col_pend_q <= 1'b0;
    else if (tf_valid_i) tf_col_pend_q <= !tf_nmap_i;
    if (tf_valid_i && !tf_nmap_i) tf_col_slot_q <= sh_in_slot_i;
  end

  // The clock before: the guards of "|=>" (cleared in reset) and the values $stable compares.
  logic                 px_wait_q, tc_wait_q;
  logic [PIX_W-1:0]     px_id_q;
  logic [2:0][7:0]      px_rgb_q;
  logic [MIP_TAG_W-1:0] mip_tag_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      px_wait_q <= 1'b0;
      tc_wait_q <= 1'b0;
    end else begin
      px_wait_q <= px_valid_i && !px_ready_i;
      tc_wait_q <= tc_req_valid_i && !tc_req_ready_i;
    end
    px_id_q   <= px_id_i;
    px_rgb_q  <= px_rgb_i;
    mip_tag_q <= mip_tag_i;
  end

  // The number of slots set in a slot mask.
  function automatic logic [SLOT_W:0] ones(input logic [SLOTS-1:0] m);
    logic [SLOT_W:0] n;
    n = '0;
    for (int i = 0; i < SLOTS; i++) n = n + (SLOT_W+1)'(m[i]);
    return n;
  endfunction

  // The slots in use and in the traversal.
  logic [SLOTS-1:0] use_q, trav_q;
  logic             px_done;
  logic [SLOT_W:0]  n_use;
  assign px_done = px_valid_i && px_ready_i;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      use_q  <= '0;
      trav_q <= '0;
    end else begin
      if (px_done)    use_q[o_slot_i]   <= 1'b0;
      if (res_take_i) trav_q[res_id_i]  <= 1'b0;
      if (acc_i) begin
        use_q[free_head_i]  <= 1'b1;
        trav_q[free_head_i] <= 1'b1;
      end
    end
  end
  assign n_use = ones(use_q);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      slot_enter_free: assert (!acc_i || !use_q[free_head_i])
        else $error("dm_pipeline: slot %0d taken while in use", free_head_i);
      slot_trav_once:  assert (!res_take_i || (trav_q[res_id_i] && use_q[res_id_i]))
        else $error("dm_pipeline: traversal result for slot %0d, not in the traversal", res_id_i);
      slot_out_once:   assert (!px_done || (use_q[o_slot_i] && !trav_q[o_slot_i]))
        else $error("dm_pipeline: pixel out for slot %0d, not in use or still traversing",
                    o_slot_i);
      slot_count:      assert (n_use == live_i)
        else $error("dm_pipeline: %0d slots in use, live_q %0d", n_use, live_i);
    end
  end

  // The merge into the output register: a slot is in it (mg_q) from its result's entry into the
  // miss FIFO or its shaded pixel's into the out FIFO until its pixel leaves.
  //   merge_enter_free  a slot enters the merge only when not in it, and not from both sides in
  //                     one clock (what the traversal and the back end guarantee);
  //   merge_leave_once  a pixel leaves for a slot in the merge (so once per entry);
  //   merge_count       the slots in the merge = the miss FIFO's + the out FIFO's entries + the
  //                     output register's pixel (none lost inside).
  logic [SLOTS-1:0] mg_q;
  logic [SLOT_W:0]  n_mg;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      mg_q <= '0;
    end else begin
      if (px_done)    mg_q[o_slot_i]  <= 1'b0;
      if (miss_wr_i)  mg_q[res_id_i]  <= 1'b1;
      if (sh_valid_i) mg_q[sh_slot_i] <= 1'b1;
    end
  end
  assign n_mg = ones(mg_q);
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      merge_enter_free: assert ((!miss_wr_i || !mg_q[res_id_i]) && (!sh_valid_i || !mg_q[sh_slot_i])
                                && !(miss_wr_i && sh_valid_i && res_id_i == sh_slot_i))
        else $error("dm_pipeline: slot %0d / %0d enters the merge twice", res_id_i, sh_slot_i);
      merge_leave_once: assert (!px_done || mg_q[o_slot_i])
        else $error("dm_pipeline: pixel out for slot %0d, not in the merge", o_slot_i);
      merge_count:      assert (32'(n_mg) == miss_count_i + out_count_i + 32'(px_valid_i))
        else $error("dm_pipeline: %0d slots in the merge, %0d + %0d + %0d held", n_mg,
                    miss_count_i, out_count_i, px_valid_i);
    end
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni && !init_i) begin
      slots_conserved: assert (free_count_i + live_i == (SLOT_W+1)'(SLOTS))
        else $error("dm_pipeline: free %0d + live %0d != SLOTS", free_count_i, live_i);
    end
    if (rst_ni) begin
      fifo0_credit: assert (!f0_wr_i || !f0_full_i)
        else $error("dm_pipeline: FIFO #0 written while full");
      req_credit:   assert (!ta_valid_i || (ta_tex_i ? !rq_n_full_i : !rq_c_full_i))
        else $error("dm_pipeline: texture-request FIFO written while full");
      frag_spacing: assert (!acc_i || frag_age_q == 2'd3)
        else $error("dm_pipeline: fragments %0d clocks apart (4 at least)", frag_age_q + 2'd1);
      hit_spacing:  assert (!hit_adm_i || hit_age_q == 2'd3)
        else $error("dm_pipeline: hits %0d clocks apart (4 at least)", hit_age_q + 2'd1);
      nl_tag_held:  assert (!nl_valid_i || mip_tag_i == mip_tag_q)
        else $error("dm_pipeline: mip_level's tag changed under the held normal-map lookup");
      addr_pairs:   assert ((ta_valid_i && ta_tex_i) == ta_col_q[1]
                            && (!ta_col_q[1] || ta_slot_i == ta_col_slot_q[1]))
        else $error("dm_pipeline: tex_addr's lookups not in colour, normal-map pairs 2 clocks apart");
      out_credit:   assert (!sh_valid_i || !out_full_i)
        else $error("dm_pipeline: shaded-pixel FIFO written while full");
      px_stable:    assert (!px_wait_q || (px_valid_i && px_id_i == px_id_q
                                           && px_rgb_i == px_rgb_q))
        else $error("dm_pipeline: pixel stream changed while waiting for px_ready_i");
      tc_req_held:  assert (!tc_wait_q || tc_req_valid_i)
        else $error("dm_pipeline: texture request withdrawn while waiting");
      tf_pairs:     assert (!tf_valid_i || (tf_nmap_i ? tf_col_pend_q && tf_col_slot_q == sh_in_slot_i
                                                      : !tf_col_pend_q))
        else $error("dm_pipeline: tex_filter's results not in colour, normal-map pairs");
    end
  end

endmodule

bind dm_pipeline dm_pipeline_assert #(.PIX_W(PIX_W), .SLOTS(SLOTS)) u_assert (
  .clk_i, .rst_ni, .init_i(init_q), .free_count_i(free_count), .live_i(live_q), .f0_wr_i(f0_wr),
  .f0_full_i(f0_full), .ta_valid_i(ta_valid), .ta_tex_i(ta_tex), .ta_slot_i(ta_slot),
  .rq_c_full_i(rq_c_full), .rq_n_full_i(rq_n_full), .hit_adm_i(hit_adm),
  .nl_valid_i(nl_valid_q), .mip_tag_i(mip_tag), .sh_valid_i(sh_valid), .out_full_i(out_full),
  .px_valid_i(px_valid_o), .px_ready_i, .px_id_i(px_id_o), .px_rgb_i(px_rgb_o),
  .tc_req_valid_i(tc_req_valid), .tc_req_ready_i(tc_req_ready), .tf_valid_i(tf_valid),
  .tf_nmap_i(tf_tag[1]), .sh_in_slot_i(sh_in_slot), .acc_i(acc), .free_head_i(free_head),
  .res_take_i(res_valid && res_ready), .res_id_i(res_id), .o_slot_i(o_slot_q),
  .miss_wr_i(miss_wr), .sh_slot_i(sh_tag[$clog2(SLOTS):1]),
  .miss_count_i(32'(miss_count)), .out_count_i(32'(out_count)));
`endif
