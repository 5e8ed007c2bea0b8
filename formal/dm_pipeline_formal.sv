// SPDX-License-Identifier: Apache-2.0
// dm_pipeline_formal: the output merge of dm_pipeline under SymbiYosys (formal/dm_pipeline.sby):
// the slots of the miss FIFO (results without a hit) and of the shaded-pixel FIFO leave through
// the output register, each once (the bound dm_pipeline_assert's merge_leave_once, merge_count,
// px_stable; the two FIFOs' traverse_fifo_assert).  dm_pipeline is the top (every input free);
// this checker is bound into it here, for formal only.
//
// The units around the merge are cut (the .sby script): view_calc, traverse_rings, mip_level,
// tex_addr, tex_cache, tex_filter and shade_unit are black boxes whose outputs are free values
// each clock, so the traversal's results (slot, hit or not) and the back end's shaded pixels
// (valid, slot) come whenever and however the solver likes, within what the neighbours'
// guarantees allow, assumed here: a slot enters the merge only when not in it, not from both
// sides in one clock (merge_enter_free: the traversal returns each slot once, the back end
// shades each hit once), and the back end writes the out FIFO only with room (out_credit, the
// out credits').  The checks about the cut units and the front (free list, FIFO #0, the
// request FIFOs and credits) are removed from the model after the front end has listed them.
// Assumed too: reset in the first clock; resets may come again at any time.
//
// Induction invariant (inv_place): a slot in the merge (mg_q) is in exactly one place, an entry
// of the miss FIFO, an entry of the out FIFO (its slot field) or the output register while it
// holds a pixel; a slot not in the merge is in none.
`ifdef FORMAL
module dm_pipeline_formal #(
  parameter int unsigned SLOTS      = 4,   // dm_pipeline's parameters
  parameter int unsigned MISS_DEPTH = 2,
  parameter int unsigned OUT_DEPTH  = 2
) (
  input logic clk_i,
  input logic rst_ni
);

  localparam int unsigned SLOT_W = $clog2(SLOTS);
  localparam int unsigned MW     = $clog2(MISS_DEPTH);
  localparam int unsigned OW     = $clog2(OUT_DEPTH);
  localparam int unsigned OUT_W  = SLOT_W + 1 + 24;   // the out FIFO's word {slot, err, rgb}

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));
  // Each slot's places.
  logic [SLOTS-1:0] place_ok;
  always_comb begin
    int n;
    for (int s = 0; s < SLOTS; s++) begin
      n = 0;
      for (int i = 0; i < MISS_DEPTH; i++) begin
        if (i < int'(dm_pipeline.u_miss.cnt_q)
            && dm_pipeline.u_miss.mem_q[MW'(dm_pipeline.u_miss.rp_q + MW'(i))] == SLOT_W'(s))
          n++;
      end
      for (int i = 0; i < OUT_DEPTH; i++) begin
        if (i < int'(dm_pipeline.u_out.cnt_q)
            && dm_pipeline.u_out.mem_q[OW'(dm_pipeline.u_out.rp_q + OW'(i))][OUT_W-1 -: SLOT_W]
               == SLOT_W'(s))
          n++;
      end
      if (dm_pipeline.o_valid_q && dm_pipeline.o_slot_q == SLOT_W'(s)) n++;
      place_ok[s] = (n == int'(dm_pipeline.u_assert.mg_q[s]));
    end
  end

  always_comb begin
    if (rst_ni) begin
      inv_place: assert (place_ok == '1);
    end
  end

  // Covers: a miss and a shaded pixel enter in one clock; the miss FIFO full with the out FIFO
  // holding one (4 slots: the output register holds the fourth); a slot leaves and enters again;
  // the output register waits with both FIFOs holding pixels.
  logic again_q;   // a slot's pixel left, and that slot has entered the merge again
  logic [SLOTS-1:0] left_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      left_q  <= '0;
      again_q <= 1'b0;
    end else begin
      if (dm_pipeline.px_valid_o && dm_pipeline.px_ready_i) left_q[dm_pipeline.o_slot_q] <= 1'b1;
      if (dm_pipeline.miss_wr && left_q[dm_pipeline.res_id]) again_q <= 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      c_both_enter: cover (dm_pipeline.miss_wr && dm_pipeline.sh_valid);
      c_both_full:  cover (dm_pipeline.miss_full && !dm_pipeline.out_empty);
      c_again:      cover (again_q);
      c_wait_both:  cover (dm_pipeline.px_valid_o && !dm_pipeline.px_ready_i
                           && !dm_pipeline.miss_empty && !dm_pipeline.out_empty);
    end
  end

endmodule

bind dm_pipeline dm_pipeline_formal #(
  .SLOTS(SLOTS), .MISS_DEPTH(MISS_DEPTH), .OUT_DEPTH(OUT_DEPTH)
) u_formal (.clk_i, .rst_ni);
`endif
