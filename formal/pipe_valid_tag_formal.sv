// SPDX-License-Identifier: Apache-2.0
// pipe_valid_tag_formal: pipe_valid_tag alone under SymbiYosys (formal/pipe_valid_tag.sby), its
// inputs free (the clock enable too: the units with stalls use it), reset in the first clock.
// The properties are the bound pipe_valid_tag_assert's.
module pipe_valid_tag_formal #(
  parameter int unsigned TAG_W = 4,  // tag bits (the properties do not depend on it)
  parameter int unsigned DEPTH = 3   // latency in enabled clocks
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             en_i,
  input logic             valid_i,
  input logic [TAG_W-1:0] tag_i
);

  logic             valid;
  logic [TAG_W-1:0] tag;
  logic [DEPTH:1]   stage_valid;

  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(DEPTH)) u_dut (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o(valid), .tag_o(tag),
    .stage_valid_o(stage_valid));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  logic unused;
  assign unused = ^{valid, tag, stage_valid};

endmodule
