// SPDX-License-Identifier: Apache-2.0
// Test harness: traverse_unit with height_rom (fixed latency 3, random misses) on its lookup port.
module tb_traverse_unit
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W = 16,
  parameter int unsigned AW   = 18,
  parameter bit          XOR_PATH = 1'b1,  // traverse_loop's XOR descent path
  parameter int unsigned MUL_LAT  = pipe_pkg::F24_MUL_LAT  // traverse_loop's f24_mul latency
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic [3:0]                        cfg_method_i,
  input  logic [DIM_W-1:0]                  cfg_width_i,
  input  logic [DIM_W-1:0]                  cfg_height_i,
  input  logic [LVL_W-1:0]                  cfg_root_level_i,
  input  logic                              cfg_bits16_i,
  input  logic [ADDR_W-1:0]                 cfg_base_i,
  input  logic [CODE_W-1:0]                 cfg_root_code_i,
  input  logic [ITER_W-1:0]                 cfg_iter_cap_i,
  input  logic                              hlt_we_i,
  input  logic [LVL_W-1:0]                  hlt_waddr_i,
  input  logic [ADDR_W-1:0]                 hlt_wdata_i,
  input  logic                              ray_valid_i,
  output logic                              ray_ready_o,
  input  logic [ID_W-1:0]                   ray_id_i,
  input  f24_t                              ray_u0_i,
  input  f24_t                              ray_v0_i,
  input  f24_t                              ray_du_i,
  input  f24_t                              ray_dv_i,
  output logic                              res_valid_o,
  input  logic                              res_ready_i,
  output logic [ID_W-1:0]                   res_id_o,
  output f24_t                              res_t_o,
  output f24_t                              res_u_o,
  output f24_t                              res_v_o,
  output logic                              res_hit_o,
  output logic                              res_invalid_o,
  output logic                              res_capped_o,
  output logic                              res_err_o,
  output logic [ITER_W-1:0]                 res_iters_o,
  output logic [31:0]                       stat_cycles_o,
  output logic [31:0]                       stat_rays_in_o,
  output logic [31:0]                       stat_rays_out_o,
  output logic [31:0]                       stat_iters_o,
  output logic [31:0]                       stat_lookups_o,
  output logic [31:0]                       stat_crossings_o,
  output logic [31:0]                       stat_level_ups_o,
  output logic [31:0]                       stat_descents_o,
  output logic                              idle_o,
  // memory
  input  logic [31:0]                       rom_base_i,
  input  logic [15:0]                       miss_thresh_i,
  input  logic                              wr_en_i,
  input  logic [AW-3:0]                     wr_addr_i,
  input  logic [31:0]                       wr_data_i
);

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

endmodule
