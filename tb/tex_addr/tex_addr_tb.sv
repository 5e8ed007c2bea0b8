// SPDX-License-Identifier: Apache-2.0
// tex_addr_tb: tex_addr in every configuration tb/tex_addr checks, side by side in one build:
// g_case[i] holds tex_addr with the parameters of row i of the table below and its own copy of
// the unit's ports (named as the ports), so the cocotb test drives and checks each through the
// hierarchy (dut.g_case[i].valid_i, ...), with its own reset; only the clock is shared.  An
// instance at the package's float-unit depths is built with no ADD_LAT / MUL_LAT parameter (so
// that the unit's defaults are checked too).  The table is the test's CASES, then (LONG = 1)
// LONG_CASES (the test reads the parameters back and stops if they differ).
module tex_addr_tb
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter bit LONG = 1'b0  // 1: also the make test-long configurations
) (
  input logic clk_i
);

  // make test: the design's unit at its defaults, a 1-bit tag with 40-bit addresses, two textures
  // (as in dm_pipeline); make test-long adds both first at the paper's depths (2, 1) and three
  // textures
  localparam int unsigned NCASE = LONG ? 6 : 3;
  localparam int unsigned ADD_LAT_OF [6] =  // f24_add latency
    '{F24_ADD_LAT, F24_ADD_LAT, F24_ADD_LAT, 2, 2, F24_ADD_LAT};
  localparam int unsigned MUL_LAT_OF [6] =  // f24_mul latency
    '{F24_MUL_LAT, F24_MUL_LAT, F24_MUL_LAT, 1, 1, F24_MUL_LAT};
  localparam int unsigned TAG_W_OF   [6] = '{8, 1, 9, 8, 9, 8};  // side-band bits
  localparam int unsigned ADDR_W_OF  [6] =  // byte address width
    '{TEX_ADDR_W, 40, TEX_ADDR_W, TEX_ADDR_W, TEX_ADDR_W, TEX_ADDR_W};
  localparam int unsigned NTEX_OF    [6] = '{1, 1, 2, 1, 2, 3};  // textures sharing the unit

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned ADD_LAT = ADD_LAT_OF[i];
    localparam int unsigned MUL_LAT = MUL_LAT_OF[i];
    localparam int unsigned TAG_W   = TAG_W_OF[i];
    localparam int unsigned ADDR_W  = ADDR_W_OF[i];
    localparam int unsigned NTEX    = NTEX_OF[i];
    localparam int unsigned SEL_W   = (NTEX > 1) ? $clog2(NTEX) : 1;  // as tex_addr's
    localparam int unsigned LVT_W   = 1 + SEL_W + TEX_LVL_W;          // as tex_addr's
    localparam int unsigned LVT_DW  = (ADDR_W > 2 * TEX_DIM_W) ? ADDR_W : 2 * TEX_DIM_W;

    // the unit's ports
    logic                        rst_ni, en_i;
    f24_t [NTEX-1:0]             cfg_su_i, cfg_sv_i;
    logic [NTEX-1:0][ADDR_W-1:0] cfg_base_i;
    logic                        lvt_we_i;
    logic [LVT_W-1:0]            lvt_waddr_i;
    logic [LVT_DW-1:0]           lvt_wdata_i;
    logic                        valid_i;
    logic [TAG_W-1:0]            tag_i;
    logic [SEL_W-1:0]            tex_i;
    f24_t                        u_i, v_i;
    logic [MIP_LEVEL_W-1:0]      level_i;
    logic                        valid_o;
    logic [TAG_W-1:0]            tag_o;
    logic [ADDR_W-1:0]           addr00_o, addr01_o, addr10_o, addr11_o;
    f24_t                        fx_o, fy_o;

    if (ADD_LAT == F24_ADD_LAT && MUL_LAT == F24_MUL_LAT) begin : g_unit
      tex_addr #(.TAG_W(TAG_W), .ADDR_W(ADDR_W), .NTEX(NTEX)) u_dut (.*);
    end else begin : g_unit
      tex_addr #(
        .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT), .TAG_W(TAG_W), .ADDR_W(ADDR_W), .NTEX(NTEX)
      ) u_dut (.*);
    end
  end

endmodule
