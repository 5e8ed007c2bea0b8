// SPDX-License-Identifier: Apache-2.0
// formal_reset: the reset a formal harness opens with.  started_o is 0 in the first clock only,
// and rst_ni is assumed low in that clock, so every trace starts from reset; a reset may come
// again at any later clock unless the harness assumes otherwise.
module formal_reset (
  input  logic clk_i,
  input  logic rst_ni,
  output logic started_o   // 0 in the first clock only
);

  logic started_q = 1'b0;
  always_ff @(posedge clk_i) started_q <= 1'b1;
  assign started_o = started_q;

  always_comb begin
    if (!started_q) assume (!rst_ni);
  end

endmodule
