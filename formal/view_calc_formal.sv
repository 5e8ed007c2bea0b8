// SPDX-License-Identifier: Apache-2.0
// view_calc_formal: view_calc under SymbiYosys (formal/view_calc.sby), for its tags: the
// properties are the bound view_calc_assert's (vtag_leave_once, vtag_inside, spacing) and
// pipe_valid_tag_assert's (in_flight, tag_order, trk_stage, bound into its u_valid_tag).  The
// float datapath drives only du_o, dv_o and seg_o, which the wrapper leaves open, so Yosys drops
// it: the tag path is proven whatever the arithmetic.  Free: the fragments (tags, words), the
// configuration, the clock enable.  Assumed: no fragment within 3 enabled clocks after one (the
// unit's spacing; dm_pipeline's admission), reset in the first clock and at any time after.
module view_calc_formal
  import f24_pkg::*;
#(
  parameter int unsigned TAG_W   = 4,                      // tag bits (the shadow keys on all)
  parameter int unsigned ADD_LAT = pipe_pkg::F24_ADD_LAT,  // view_calc's ADD_LAT
  parameter int unsigned MUL_LAT = pipe_pkg::F24_MUL_LAT   // view_calc's MUL_LAT
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             en_i,
  input f24_t             cfg_depth_i,
  input logic             valid_i,
  input logic [TAG_W-1:0] tag_i,
  input f24_t             w_i [12]   // T, B, N, V
);

  logic             valid;
  logic [TAG_W-1:0] tag;
  f24_t             du, dv, seg;

  view_calc #(.TAG_W(TAG_W), .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT)) u_dut (
    .clk_i, .rst_ni, .en_i, .cfg_depth_i, .valid_i, .tag_i,
    .tx_i(w_i[0]), .ty_i(w_i[1]), .tz_i(w_i[2]), .bx_i(w_i[3]), .by_i(w_i[4]), .bz_i(w_i[5]),
    .nx_i(w_i[6]), .ny_i(w_i[7]), .nz_i(w_i[8]), .vx_i(w_i[9]), .vy_i(w_i[10]), .vz_i(w_i[11]),
    .valid_o(valid), .tag_o(tag), .du_o(du), .dv_o(dv), .seg_o(seg));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  always_comb begin
    assume (!(en_i && valid_i) || u_dut.stage_v[3:1] == '0);
`ifdef VIEW_CALC_COVER_EN
    assume (en_i);   // the cover task: every clock enabled (the states it shows need no stall)
`endif
  end

  // Covers: a tag out while the tracked tag is inside; two fragments out with one tag between
  // them in flight (tags may repeat: the multiset shadow); the pipeline full (5 fragments, one
  // every 4th stage).
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      c_out_busy: cover (en_i && valid && u_dut.u_valid_tag.u_assert.trk_q
                         && !u_dut.u_valid_tag.u_assert.trk_out);
      c_repeat:   cover (en_i && valid && u_dut.u_assert.cnt_q[tag] > 1);
      c_full:     cover ($countones(u_dut.stage_v) >= 5);
    end
  end

  logic unused;
  assign unused = ^{du, dv, seg};

endmodule
