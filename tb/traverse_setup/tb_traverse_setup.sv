// SPDX-License-Identifier: Apache-2.0
// Test harness: traverse_setup alone, its configuration from flat ports (the method code decoded
// as traverse_unit does) and its ray record out as flat fields.
module tb_traverse_setup
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W    = 16,
  parameter int unsigned ADD_LAT = pipe_pkg::F24_ADD_LAT,  // traverse_setup's ADD_LAT, MUL_LAT
  parameter int unsigned MUL_LAT = pipe_pkg::F24_MUL_LAT
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  input  logic [3:0]              cfg_method_i,
  input  logic [DIM_W-1:0]        cfg_width_i,
  input  logic [DIM_W-1:0]        cfg_height_i,
  input  logic [LVL_W-1:0]        cfg_root_level_i,
  input  logic                    cfg_bits16_i,
  input  logic [CODE_W-1:0]       cfg_root_code_i,
  input  logic                    idle_i,
  output logic                    in_ready_o,
  input  logic                    in_valid_i,
  input  logic [ID_W-1:0]         in_id_i,
  input  f24_t                    in_u0_i,
  input  f24_t                    in_v0_i,
  input  f24_t                    in_du_i,
  input  f24_t                    in_dv_i,
  output logic                    out_valid_o,
  output logic [ID_W-1:0]         out_id_o,
  output f24_t                    out_u0_o,
  output f24_t                    out_v0_o,
  output f24_t                    out_du_o,
  output f24_t                    out_dv_o,
  output f24_t                    out_inv_du_o,
  output f24_t                    out_inv_dv_o,
  output logic [1:0]              out_sx_o,     // {mv, neg}
  output logic [1:0]              out_sy_o,
  output f24_t                    out_t_map_o,
  output logic [LVL_W-1:0]        out_k_o,
  output logic [CELL_W-1:0]       out_cx_o,
  output logic [CELL_W-1:0]       out_cy_o,
  output f24_t                    out_t_o,
  output logic                    out_done_o,
  output logic                    out_invalid_o,
  output logic [5:0]              out_rest_o,   // crossed, prev_cross, hit, capped, err, iters != 0
  output logic [SETUP_BUSY_W-1:0] busy_o
);

  cfg_t cfg;
  ray_t ray;
  always_comb begin
    cfg           = '0;
    cfg.policy    = decode_method(cfg_method_i);
    cfg.width     = cfg_width_i;
    cfg.height    = cfg_height_i;
    cfg.n         = cfg_root_level_i;
    cfg.bits16    = cfg_bits16_i;
    cfg.root_code = cfg_root_code_i;
  end

  traverse_setup #(.ID_W(ID_W), .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT)) u_dut (
    .clk_i, .rst_ni, .cfg_i(cfg), .idle_i, .in_ready_o, .in_valid_i, .in_id_i, .in_u0_i,
    .in_v0_i, .in_du_i, .in_dv_i, .out_valid_o, .out_id_o, .out_ray_o(ray), .busy_o);

  assign out_u0_o      = ray.u0;
  assign out_v0_o      = ray.v0;
  assign out_du_o      = ray.du;
  assign out_dv_o      = ray.dv;
  assign out_inv_du_o  = ray.inv_du;
  assign out_inv_dv_o  = ray.inv_dv;
  assign out_sx_o      = ray.sx;
  assign out_sy_o      = ray.sy;
  assign out_t_map_o   = ray.t_map;
  assign out_k_o       = ray.k;
  assign out_cx_o      = ray.cx;
  assign out_cy_o      = ray.cy;
  assign out_t_o       = ray.t;
  assign out_done_o    = ray.done;
  assign out_invalid_o = ray.invalid;
  assign out_rest_o    = {ray.crossed, ray.prev_cross, ray.hit, ray.capped, ray.err,
                          ray.iters != '0};

endmodule
