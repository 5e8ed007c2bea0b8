// SPDX-License-Identifier: Apache-2.0
// traverse_fifo_tb: traverse_fifo in every configuration tb/traverse_fifo checks, side by side
// in one build: g_case[i] holds traverse_fifo with W = W_OF[i], DEPTH = DEPTH_OF[i], OUT_REG =
// OUT_REG_OF[i] and its own copy of the unit's ports (named as the ports), so the cocotb test
// drives and checks each through the hierarchy (dut.g_case[i].wr_i, ...), with its own reset;
// only the clock is shared.  The table is the test's CASES (the test reads W, DEPTH and OUT_REG
// back and stops if they differ).
module traverse_fifo_tb (
  input logic clk_i
);

  localparam int unsigned NCASE = 6;
  // three sizes, each without and with the head in a register (OUT_REG 1: the default of the
  // block-RAM FIFOs; the ports must behave clock for clock as without it)
  localparam int unsigned W_OF       [NCASE] = '{16, 7, 33, 16, 7, 33};
  localparam int unsigned DEPTH_OF   [NCASE] = '{16, 2, 4, 16, 2, 4};
  localparam bit          OUT_REG_OF [NCASE] = '{0, 0, 0, 1, 1, 1};

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned W       = W_OF[i];
    localparam int unsigned DEPTH   = DEPTH_OF[i];
    localparam bit          OUT_REG = OUT_REG_OF[i];

    logic                   rst_ni, wr_i, rd_i, full_o, empty_o;
    logic [W-1:0]           wr_data_i, rd_data_o;
    logic [$clog2(DEPTH):0] count_o;

    traverse_fifo #(.W(W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_dut (
      .clk_i, .rst_ni, .wr_i, .wr_data_i, .rd_i, .rd_data_o, .full_o, .empty_o, .count_o);
  end

endmodule
