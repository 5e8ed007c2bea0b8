// SPDX-License-Identifier: Apache-2.0
// pipe_valid_tag_assert: the properties of pipe_valid_tag, bound into every instance (the `bind`
// at the end of this file), checked by simulation (Verilator --assert) and proven by
// `make formal` (formal/pipe_f0.sby; docs/formal.md).  Immediate assertions only, in the form
// the formal flow's front end (Yosys read_slang) accepts.
//
//   in_flight   the valid bits inside (stage_valid_o) number the items entered minus the items
//               out since reset (counted on enabled clocks);
//   tag_order   a tracked item (one picked freely in formal, every item entering while none is
//               tracked in simulation) comes out exactly DEPTH enabled clocks after it entered,
//               valid and with its own tag; trk_stage: while inside it is valid at its stage and
//               its tag there is unchanged (the invariant that makes the induction step hold).
// Covers: an item out, and the tracked item out.
`ifndef SYNTHESIS
module pipe_valid_tag_assert #(
  parameter int unsigned TAG_W = 8,  // pipe_valid_tag's TAG_W
  parameter int unsigned DEPTH = 1   // pipe_valid_tag's DEPTH
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             en_i,
  input logic             valid_i,
  input logic [TAG_W-1:0] tag_i,
  input logic             valid_o_i,      // pipe_valid_tag's valid_o
  input logic [TAG_W-1:0] tag_o_i,        // tag_o
  input logic [DEPTH:1]   stage_valid_i   // stage_valid_o
);

  // Wide enough for 0..DEPTH with a bit to spare, so that the range check of the tracked stage
  // is not constant (Verilator's CMPCONST) when DEPTH + 1 is a power of two.
  localparam int unsigned SW = $clog2(DEPTH + 1) + 1;

  // ---- items inside: entered - out -----------------------------------------------------------
  logic [SW:0] n_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni)   n_q <= '0;
    else if (en_i) n_q <= n_q + (SW+1)'(valid_i) - (SW+1)'(valid_o_i);
  end
  logic [SW:0] n_valid;   // valid bits set in stage_valid_i
  always_comb begin
    n_valid = '0;
    for (int s = 1; s <= DEPTH; s++) n_valid = n_valid + (SW+1)'(stage_valid_i[s]);
  end

  // ---- the tracked item ----------------------------------------------------------------------
  // pick: which item to track.  Formal leaves it undriven (SymbiYosys makes an undriven wire a
  // free input); simulation tracks whenever it can.
  logic pick;
`ifndef FORMAL
  assign pick = 1'b1;
`endif
  logic             trk_q;       // an item is tracked
  logic [TAG_W-1:0] trk_tag_q;   // its tag
  logic [SW-1:0]    trk_s_q;     // its stage (1..DEPTH)
  logic             trk_out;     // it leaves in this clock
  assign trk_out = trk_q && en_i && trk_s_q == SW'(DEPTH);
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      trk_q <= 1'b0;
    end else if (en_i) begin
      if (valid_i && pick && (!trk_q || trk_out)) begin
        trk_q     <= 1'b1;
        trk_tag_q <= tag_i;
        trk_s_q   <= SW'(1);
      end else if (trk_out) begin
        trk_q <= 1'b0;
      end else if (trk_q) begin
        trk_s_q <= trk_s_q + SW'(1);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      in_flight: assert (n_q == n_valid)
        else $error("pipe_valid_tag: %0d valid bits inside, %0d items entered and not out",
                    n_valid, n_q);
      trk_stage: assert (!trk_q || (trk_s_q != '0 && trk_s_q <= SW'(DEPTH)
                                    && stage_valid_i[trk_s_q]
                                    && pipe_valid_tag.tag_q[trk_s_q] == trk_tag_q))
        else $error("pipe_valid_tag: the tracked item is lost");
      tag_order: assert (!(trk_q && trk_s_q == SW'(DEPTH)) || (valid_o_i && tag_o_i == trk_tag_q))
        else $error("pipe_valid_tag: tag %0h out, %0h due", tag_o_i, trk_tag_q);
      c_out:     cover (valid_o_i && en_i);
      c_trk_out: cover (trk_out);
    end
  end

endmodule

bind pipe_valid_tag pipe_valid_tag_assert #(.TAG_W(TAG_W), .DEPTH(DEPTH)) u_assert (
  .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o_i(valid_o), .tag_o_i(tag_o),
  .stage_valid_i(stage_valid_o));
`endif
