// SPDX-License-Identifier: Apache-2.0
// view_calc_tb: view_calc in every configuration tb/view_calc checks, side by side in one build:
// g_case[i] holds view_calc with the parameters of row i of the table below and its own copy of
// the unit's ports (named as the ports), so the cocotb test drives and checks each through the
// hierarchy (dut.g_case[i].valid_i, ...), with its own reset; only the clock is shared.  An
// instance at the package's float-unit depths is built with no ADD_LAT / MUL_LAT parameter (so
// that the unit's defaults are checked too).  The table is the test's CASES, then (LONG = 1)
// LONG_CASES (the test reads the parameters back and stops if they differ).
module view_calc_tb
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter bit LONG = 1'b0  // 1: also the make test-long configuration (the paper's depths)
) (
  input logic clk_i
);

  // make test: the design's unit at its defaults, a 1-bit tag; make test-long adds the first at
  // the paper's depths (2, 1)
  localparam int unsigned NCASE = LONG ? 3 : 2;
  localparam int unsigned ADD_LAT_OF [3] = '{F24_ADD_LAT, F24_ADD_LAT, 2};  // f24_add latency
  localparam int unsigned MUL_LAT_OF [3] = '{F24_MUL_LAT, F24_MUL_LAT, 1};  // f24_mul latency
  localparam int unsigned TAG_W_OF   [3] = '{8, 1, 8};                      // side-band bits

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned ADD_LAT = ADD_LAT_OF[i];
    localparam int unsigned MUL_LAT = MUL_LAT_OF[i];
    localparam int unsigned TAG_W   = TAG_W_OF[i];

    // the unit's ports
    logic             rst_ni, en_i;
    f24_t             cfg_depth_i;
    logic             valid_i;
    logic [TAG_W-1:0] tag_i;
    f24_t             tx_i, ty_i, tz_i, bx_i, by_i, bz_i, nx_i, ny_i, nz_i, vx_i, vy_i, vz_i;
    logic             valid_o;
    logic [TAG_W-1:0] tag_o;
    f24_t             du_o, dv_o, seg_o;

    if (ADD_LAT == F24_ADD_LAT && MUL_LAT == F24_MUL_LAT) begin : g_unit
      view_calc #(.TAG_W(TAG_W)) u_dut (.*);
    end else begin : g_unit
      view_calc #(.TAG_W(TAG_W), .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT)) u_dut (.*);
    end
  end

endmodule
