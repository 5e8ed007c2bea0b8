// SPDX-License-Identifier: Apache-2.0
// traverse_unit_tb: traverse_unit in every configuration tb/traverse_unit checks, side by side in
// one build, each with height_rom (fixed latency 3, random misses from an LFSR) on its lookup
// port.  g_case[i] holds the unit with XOR_PATH = XOR_PATH_OF[i], MUL_LAT = MUL_LAT_OF[i], its
// own ROM and its own copy of the arrangement's ports (signals named as ports), so the cocotb
// test drives and checks each through the hierarchy (dut.g_case[i].ray_valid_i, ...), with its
// own reset; only the clock is shared.  The table is the test's CASES (the test reads XOR_PATH
// and MUL_LAT back and stops if they differ).
module traverse_unit_tb
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter bit LONG = 1'b0  // 1: also the make test-long configurations (the paper's depths)
) (
  input logic clk_i
);

  localparam int unsigned ID_W  = 16;  // ray id bits
  localparam int unsigned AW    = 18;  // height_rom's byte address bits
  // XOR descent path and the package's multipliers; without the XOR path; (make test-long) the
  // XOR path at the paper's one-clock multipliers (the 19-stage ring)
  localparam int unsigned NCASE = LONG ? 3 : 2;
  localparam bit          XOR_PATH_OF [3] = '{1'b1, 1'b0, 1'b1};  // traverse_loop's XOR path
  localparam int unsigned MUL_LAT_OF  [3] =                       // traverse_loop's f24_mul LAT
    '{pipe_pkg::F24_MUL_LAT, pipe_pkg::F24_MUL_LAT, 1};

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam bit          XOR_PATH = XOR_PATH_OF[i];
    localparam int unsigned MUL_LAT  = MUL_LAT_OF[i];

    // the arrangement's ports
    logic                 rst_ni;
    logic [3:0]           cfg_method_i;
    logic [DIM_W-1:0]     cfg_width_i, cfg_height_i;
    logic [LVL_W-1:0]     cfg_root_level_i;
    logic                 cfg_bits16_i;
    logic [ADDR_W-1:0]    cfg_base_i;
    logic [CODE_W-1:0]    cfg_root_code_i;
    logic [ITER_W-1:0]    cfg_iter_cap_i;
    logic                 hlt_we_i;
    logic [LVL_W-1:0]     hlt_waddr_i;
    logic [ADDR_W-1:0]    hlt_wdata_i;
    logic                 ray_valid_i, ray_ready_o;
    logic [ID_W-1:0]      ray_id_i;
    f24_t                 ray_u0_i, ray_v0_i, ray_du_i, ray_dv_i;
    logic                 res_valid_o, res_ready_i;
    logic [ID_W-1:0]      res_id_o;
    f24_t                 res_t_o, res_u_o, res_v_o;
    logic                 res_hit_o, res_invalid_o, res_capped_o, res_err_o;
    logic [ITER_W-1:0]    res_iters_o;
    logic [31:0]          stat_cycles_o, stat_rays_in_o, stat_rays_out_o, stat_iters_o;
    logic [31:0]          stat_lookups_o, stat_crossings_o, stat_level_ups_o, stat_descents_o;
    logic                 idle_o;
    // the memory's
    logic [31:0]          rom_base_i;
    logic [15:0]          miss_thresh_i;
    logic                 wr_en_i;
    logic [AW-3:0]        wr_addr_i;
    logic [31:0]          wr_data_i;

    logic        lk_valid, lk_wide, rs_valid, rs_hit, rs_err;
    logic [31:0] lk_addr;
    logic [15:0] rs_data;

    traverse_unit #(.ID_W(ID_W), .XOR_PATH(XOR_PATH), .MUL_LAT(MUL_LAT)) u_dut (
      .clk_i, .rst_ni,
      .cfg_method_i, .cfg_width_i, .cfg_height_i, .cfg_root_level_i, .cfg_bits16_i, .cfg_base_i,
      .cfg_root_code_i, .cfg_iter_cap_i, .hlt_we_i, .hlt_waddr_i, .hlt_wdata_i,
      .ray_valid_i, .ray_ready_o, .ray_id_i, .ray_u0_i, .ray_v0_i, .ray_du_i, .ray_dv_i,
      .res_valid_o, .res_ready_i, .res_id_o, .res_t_o, .res_u_o, .res_v_o, .res_hit_o,
      .res_invalid_o, .res_capped_o, .res_err_o, .res_iters_o,
      .lk_valid_o(lk_valid), .lk_addr_o(lk_addr), .lk_wide_o(lk_wide),
      .rs_valid_i(rs_valid), .rs_hit_i(rs_hit), .rs_err_i(rs_err), .rs_data_i(rs_data),
      .stat_cycles_o, .stat_rays_in_o, .stat_rays_out_o, .stat_iters_o, .stat_lookups_o,
      .stat_crossings_o, .stat_level_ups_o, .stat_descents_o, .idle_o
    );

    height_rom #(.AW(AW)) u_rom (
      .clk_i, .rst_ni, .base_i(rom_base_i), .miss_thresh_i,
      .wr_en_i, .wr_addr_i, .wr_data_i,
      .lk_valid_i(lk_valid), .lk_addr_i(lk_addr), .lk_wide_i(lk_wide),
      .rs_valid_o(rs_valid), .rs_hit_o(rs_hit), .rs_err_o(rs_err), .rs_data_o(rs_data)
    );
  end

endmodule
