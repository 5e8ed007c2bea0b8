// SPDX-License-Identifier: Apache-2.0
// pipe_delay_tb: pipe_delay in every configuration tb/pipe_delay checks, side by side in one
// build: g_case[i] holds pipe_delay with N = N_OF[i], RAM_MIN = RAM_MIN_OF[i] and its own copy of
// the unit's ports (named as the ports), so the cocotb test drives and checks each through the
// hierarchy (dut.g_case[i].d_i, ...), with its own reset; only the clock is shared.  The table
// is the test's CASES (the test reads N and RAM_MIN back and stops if they differ).
module pipe_delay_tb #(
  parameter int unsigned W = 16  // bits of the value, in every instance
) (
  input logic clk_i
);

  localparam int unsigned NCASE = 5;
  // RAM lines (N = 2, the shortest; 16, one LUT RAM deep; 67, the shade unit's longest colour
  // lane) and registers (N = 5 below RAM_MIN; 67 with RAM_MIN = 0)
  localparam int unsigned N_OF       [NCASE] = '{2, 16, 67, 5, 67};
  localparam int unsigned RAM_MIN_OF [NCASE] = '{2, 8, 8, 8, 0};

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned N       = N_OF[i];
    localparam int unsigned RAM_MIN = RAM_MIN_OF[i];

    logic         rst_ni, en_i;
    logic [W-1:0] d_i, q_o;

    pipe_delay #(.W(W), .N(N), .RAM_MIN(RAM_MIN)) u_dut (.clk_i, .rst_ni, .en_i, .d_i, .q_o);
  end

endmodule
