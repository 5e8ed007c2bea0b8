// SPDX-License-Identifier: Apache-2.0
// mip_level_tb: mip_level in every configuration tb/mip_level checks, side by side in one build:
// g_case[i] holds mip_level with the parameters of row i of the table below and its own copy of
// the unit's ports (named as the ports), so the cocotb test drives and checks each through the
// hierarchy (dut.g_case[i].valid_i, ...), with its own reset; only the clock is shared.  An
// instance at the package's float-unit depths is built with no ADD_LAT / MUL_LAT parameter (so
// that the unit's defaults are checked too).  The table is the test's CASES, then (LONG = 1)
// LONG_CASES (the test reads the parameters back and stops if they differ).
module mip_level_tb
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter bit LONG = 1'b0  // 1: also the make test-long configuration (the paper's depths)
) (
  input logic clk_i
);

  // make test: the design's unit at its defaults, two triangles with a 3-bit tag; make test-long
  // adds the first at the paper's depths (2, 1)
  localparam int unsigned NCASE = LONG ? 3 : 2;
  localparam int unsigned ADD_LAT_OF [3] = '{F24_ADD_LAT, F24_ADD_LAT, 2};  // f24_add latency
  localparam int unsigned MUL_LAT_OF [3] = '{F24_MUL_LAT, F24_MUL_LAT, 1};  // f24_mul latency
  localparam int unsigned TAG_W_OF   [3] = '{8, 3, 8};                      // side-band bits
  localparam int unsigned TRIS_OF    [3] = '{16, 2, 16};                    // triangle entries

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned ADD_LAT = ADD_LAT_OF[i];
    localparam int unsigned MUL_LAT = MUL_LAT_OF[i];
    localparam int unsigned TAG_W   = TAG_W_OF[i];
    localparam int unsigned TRIS    = TRIS_OF[i];
    localparam int unsigned TRI_W   = (TRIS > 1) ? $clog2(TRIS) : 1;  // as mip_level's

    // the unit's ports
    logic                   rst_ni, en_i;
    logic                   cfg_mip_en_i;
    logic [MIP_LEVEL_W:0]   cfg_levels_colour_i, cfg_levels_normal_i;
    logic                   tt_we_i;
    logic [TRI_W:0]         tt_waddr_i;
    f24_t                   tt_wdata_i;
    logic                   valid_i;
    logic [TAG_W-1:0]       tag_i;
    f24_t                   t_i, seg_i, pl0_i;
    logic [TRI_W-1:0]       tri_i;
    logic                   valid_o;
    logic [TAG_W-1:0]       tag_o;
    logic                   tex_o;
    logic [MIP_LEVEL_W-1:0] level_o;

    if (ADD_LAT == F24_ADD_LAT && MUL_LAT == F24_MUL_LAT) begin : g_unit
      mip_level #(.TAG_W(TAG_W), .TRIS(TRIS)) u_dut (.*);
    end else begin : g_unit
      mip_level #(.TAG_W(TAG_W), .TRIS(TRIS), .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT)) u_dut (.*);
    end
  end

endmodule
