// SPDX-License-Identifier: Apache-2.0
// view_calc_assert: the checks of view_calc, bound into every instance (the `bind`s at the end of
// this file; not in synthesis), checked by simulation and proven by `make formal`
// (formal/view_calc.sby; docs/formal.md).  Immediate assertions in a clocked block, in the form
// the formal flow's front end (Yosys read_slang) accepts.
//
//   spacing          z, x and y share the dot-product units and x and y the scale multiplier,
//                    in consecutive stages: no fragment within 3 enabled clocks after one (the
//                    user's obligation);
// The tags (view_calc carries dm_pipeline's slot id in them): a shadow of the tags inside, as a
// multiset of their top KW = min(TAG_W, ID_TRACK_W) bits (the key; tags may repeat, so a count
// per key, not a bit):
//   vtag_leave_once  a tag out was inside: its key's count is not 0 (no tag leaves that did not
//                    enter, none leaves more often than it entered);
//   vtag_inside      every key's count = the valid stages of the tag pipeline (u_valid_tag)
//                    whose tag has that key: the tags inside are exactly those that entered and
//                    did not leave (the invariant that makes the induction step hold).
// With pipe_valid_tag_assert's tag_order (bound into u_valid_tag: every tag comes out
// view_calc_lat(ADD_LAT, MUL_LAT) enabled clocks after it entered, unchanged) every tag that
// enters leaves exactly once, unchanged.
`ifndef SYNTHESIS
module view_calc_assert
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W      = 8,            // view_calc's TAG_W
  parameter int unsigned ADD_LAT    = F24_ADD_LAT,  // view_calc's ADD_LAT
  parameter int unsigned MUL_LAT    = F24_MUL_LAT,  // view_calc's MUL_LAT
  parameter int unsigned ID_TRACK_W = 6   // the shadow's key: the top min(TAG_W, this) tag bits
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             en_i,
  input logic             valid_i,
  input logic [TAG_W-1:0] tag_i,
  input logic             valid_o_i,   // view_calc's valid_o
  input logic [TAG_W-1:0] tag_o_i,     // tag_o
  input logic [3:1]       stage_v_i    // view_calc's stage_v[3:1]: a fragment in S1 .. S3
);

  localparam int unsigned NS = view_calc_lat(ADD_LAT, MUL_LAT);  // view_calc's latency
  localparam int unsigned KW = (TAG_W < ID_TRACK_W) ? TAG_W : ID_TRACK_W;
  localparam int unsigned NK = 1 << KW;
  // A count per key, wide enough for 0..NS with a bit to spare (no constant comparison).
  localparam int unsigned CW = $clog2(NS + 1) + 1;

  logic [KW-1:0] key_in, key_out;
  assign key_in  = tag_i[TAG_W-1 -: KW];
  assign key_out = tag_o_i[TAG_W-1 -: KW];
  if (TAG_W > KW) begin : g_low
    // The tag bits below the key: read nowhere else.
    logic unused_low;
    assign unused_low = ^{tag_i[TAG_W-KW-1:0], tag_o_i[TAG_W-KW-1:0]};
  end

  logic [CW-1:0] cnt_q [NK];   // tags inside per key: entered - left (enabled clocks)
  logic [CW-1:0] occ   [NK];   // valid stages holding a tag with that key
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int k = 0; k < NK; k++) cnt_q[k] <= '0;
    end else if (en_i) begin
      for (int k = 0; k < NK; k++) begin
        cnt_q[k] <= cnt_q[k] + CW'(valid_i && key_in == KW'(k))
                             - CW'(valid_o_i && key_out == KW'(k));
      end
    end
  end
  always_comb begin
    for (int k = 0; k < NK; k++) begin
      occ[k] = '0;
      for (int s = 1; s <= NS; s++) begin
        occ[k] = occ[k] + CW'(view_calc.u_valid_tag.v_q[s]
                              && view_calc.u_valid_tag.tag_q[s][TAG_W-1 -: KW] == KW'(k));
      end
    end
  end
  logic inside_ok;   // occ == cnt_q for every key
  always_comb begin
    inside_ok = 1'b1;
    for (int k = 0; k < NK; k++) inside_ok = inside_ok && occ[k] == cnt_q[k];
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      spacing:         assert (!(en_i && valid_i) || stage_v_i == '0)
        else $error("view_calc: a fragment within 4 enabled clocks of another");
      vtag_leave_once: assert (!(en_i && valid_o_i) || cnt_q[key_out] != '0)
        else $error("view_calc: a tag (key %0h) out that is not inside", key_out);
      vtag_inside:     assert (inside_ok)
        else $error("view_calc: the tags inside differ from the tags that entered");
    end
  end

endmodule

bind view_calc view_calc_assert #(.TAG_W(TAG_W), .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT)) u_assert (
  .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o_i(valid_o), .tag_o_i(tag_o),
  .stage_v_i(stage_v[3:1]));
`endif
