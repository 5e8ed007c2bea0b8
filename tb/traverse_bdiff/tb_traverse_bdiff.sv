// SPDX-License-Identifier: Apache-2.0
// tb_traverse_bdiff: traverse_bdiff with two boundaries (the ring's descent form, NB = 2) on
// packed ports for cocotb.
module tb_traverse_bdiff
  import f24_pkg::*;
#(
  parameter int unsigned W = 20  // width of each boundary (two's complement)
) (
  input  logic                clk_i,
  input  logic                en_i,
  input  logic signed [W-1:0] b0_i,
  input  logic signed [W-1:0] b1_i,
  input  f24_t                u_i,
  output f24_t                y0_o,
  output f24_t                y1_o
);

  f24_t y [2];
  traverse_bdiff #(.W(W), .NB(2)) u_dut (.clk_i, .en_i, .b_i('{b0_i, b1_i}), .u_i, .y_o(y));
  assign y0_o = y[0];
  assign y1_o = y[1];

endmodule
