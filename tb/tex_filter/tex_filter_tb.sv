// SPDX-License-Identifier: Apache-2.0
// tex_filter_tb: tex_filter in every configuration tb/tex_filter checks, side by side in one
// build: g_case[i] holds tex_filter with the parameters of row i of the table below and its own
// copy of the unit's ports (named as the ports), so the cocotb test drives and checks each
// through the hierarchy (dut.g_case[i].valid_i, ...), with its own reset; only the clock is
// shared.  An instance at the package's float-unit depths is built with no ADD_LAT / MUL_LAT
// parameter (so that the unit's defaults are checked too).  The table is the test's CASES, then
// (LONG = 1) LONG_CASES (the test reads the parameters back and stops if they differ).
module tex_filter_tb
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter bit LONG = 1'b0  // 1: also the make test-long configurations (other depths)
) (
  input logic clk_i
);

  // make test: all four channels, dm_pipeline's build (R, G, B) with a 1-bit tag; make test-long
  // adds the first at the paper's depths (2, 1) and at (2, 2) (no parity delay for m), and the
  // second at (2, 1)
  localparam int unsigned NCASE = LONG ? 5 : 2;
  localparam int unsigned ADD_LAT_OF [5] =  // f24_add latency
    '{F24_ADD_LAT, F24_ADD_LAT, 2, 2, 2};
  localparam int unsigned MUL_LAT_OF [5] =  // f24_mul latency
    '{F24_MUL_LAT, F24_MUL_LAT, 1, 2, 1};
  localparam int unsigned TAG_W_OF   [5] = '{8, 1, 8, 8, 1};  // side-band bits
  localparam bit          ALPHA_OF   [5] = '{1, 0, 1, 1, 0};  // 1: filter A too

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned ADD_LAT = ADD_LAT_OF[i];
    localparam int unsigned MUL_LAT = MUL_LAT_OF[i];
    localparam int unsigned TAG_W   = TAG_W_OF[i];
    localparam bit          ALPHA   = ALPHA_OF[i];

    // the unit's ports
    logic               rst_ni, en_i;
    logic               valid_i, ready_o;
    logic [TAG_W-1:0]   tag_i;
    logic [TEXEL_W-1:0] t00_i, t01_i, t10_i, t11_i;
    f24_t               fx_i, fy_i;
    logic               valid_o;
    logic [TAG_W-1:0]   tag_o;
    f24_t               r_o, g_o, b_o, a_o;

    if (ADD_LAT == F24_ADD_LAT && MUL_LAT == F24_MUL_LAT) begin : g_unit
      tex_filter #(.TAG_W(TAG_W), .ALPHA(ALPHA)) u_dut (.*);
    end else begin : g_unit
      tex_filter #(.ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT), .TAG_W(TAG_W), .ALPHA(ALPHA)) u_dut (.*);
    end
  end

endmodule
