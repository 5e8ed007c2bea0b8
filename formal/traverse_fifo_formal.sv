// SPDX-License-Identifier: Apache-2.0
// traverse_fifo_formal: traverse_fifo alone under SymbiYosys (formal/traverse_fifo.sby).  Its
// inputs are free, except what a user of the FIFO promises (assumed here, asserted by
// traverse_fifo_assert in every real use): no write while full, no read while empty, and reset
// in the first clock.  The properties are the bound traverse_fifo_assert's.
module traverse_fifo_formal #(
  parameter int unsigned W       = 4,   // word width (the properties do not depend on it)
  parameter int unsigned DEPTH   = 4,   // entries (power of two)
  parameter bit          OUT_REG = 0    // 1: the head in a register (RAM_STYLE "block")
) (
  input logic         clk_i,
  input logic         rst_ni,
  input logic         wr_i,
  input logic [W-1:0] wr_data_i,
  input logic         rd_i
);

  logic [W-1:0]               rd_data;
  logic                       full, empty;
  logic [$clog2(DEPTH):0]     count;

  traverse_fifo #(.W(W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_dut (
    .clk_i, .rst_ni, .wr_i, .wr_data_i, .rd_i, .rd_data_o(rd_data), .full_o(full),
    .empty_o(empty), .count_o(count));

  logic started_q = 1'b0;   // 0 in the first clock only
  always_ff @(posedge clk_i) started_q <= 1'b1;

  always_comb begin
    if (!started_q) assume (!rst_ni);
    assume (!(wr_i && full));
    assume (!(rd_i && empty));
  end

endmodule
