// SPDX-License-Identifier: Apache-2.0
// view_calc_assert: the simulation check of view_calc, bound into every instance (the `bind` at
// the end of this file; not in synthesis).  Immediate assertions in a clocked block, in the form
// the formal flow's front end (Yosys read_slang) accepts.
//
//   frag_spacing  x and y share lane TB and the scale multiplier: no fragment on the enabled
//                 clock after one.
`ifndef SYNTHESIS
module view_calc_assert (
  input logic clk_i,
  input logic rst_ni,
  input logic en_i,
  input logic valid_i,
  input logic stage_v1_i   // view_calc's stage_v[1]: the last enabled clock took a fragment
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      frag_spacing: assert (!(en_i && valid_i) || !stage_v1_i)
        else $error("view_calc: fragments on two consecutive enabled clocks");
    end
  end

endmodule

bind view_calc view_calc_assert u_assert (.clk_i, .rst_ni, .en_i, .valid_i,
  .stage_v1_i(stage_v[1]));
`endif
