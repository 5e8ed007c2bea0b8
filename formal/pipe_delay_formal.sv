// SPDX-License-Identifier: Apache-2.0
// pipe_delay_formal: pipe_delay's RAM line alone under SymbiYosys (formal/pipe_delay.sby), its
// inputs free (the clock enable too: stalls of any length), reset in the first clock.  The
// properties are the bound pipe_delay_assert's (the line against a reference of N registers).
module pipe_delay_formal #(
  parameter int unsigned W = 2,  // value bits (the properties do not depend on it)
  parameter int unsigned N = 3   // delay in enabled clocks (a RAM line: RAM_MIN = 2)
) (
  input logic         clk_i,
  input logic         rst_ni,
  input logic         en_i,
  input logic [W-1:0] d_i
);

  logic [W-1:0] q;

  pipe_delay #(.W(W), .N(N), .RAM_MIN(2)) u_dut (.clk_i, .rst_ni, .en_i, .d_i, .q_o(q));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  logic unused;
  assign unused = ^q;

endmodule
