// SPDX-License-Identifier: Apache-2.0
// traverse_system: the traverse unit with its height cache, an AXI4 read master to memory.
//
//   ray stream -> traverse_unit -> result stream
//                     |  lk_* / rs_* (lookup port, fixed latency LOOKUP_LAT = 3)
//                 height_cache -> m_axi_ar* / m_axi_r*  (AXI4 read-only master; no write channels)
//
// The pyramid (model.heightmap.Pyramid.memory_image()) lies in memory at cfg_base_i; the unit
// turns every iteration into one byte-address lookup, the cache answers it two clocks later (hit
// with the code, miss: the ray goes round again while the line is fetched, or err when the line
// came back with an AXI error response).  Flow control: see traverse_unit.sv.
//
// Configuration: cfg_* go through one register stage in traverse_unit (they fan out to the whole
// unit; this also keeps them out of every simulator's input-evaluation path), which loads while
// idle_o = 1: they must be static while idle_o = 0 and stable 7 clocks before the next ray enters.
//
// Statistics: the unit's counters (since reset, wrapping at UNIT_CNT_W bits) and the cache's
// (48 bits, cleared by clr_stats_i).  tb/harness/traverse_harness.cpp runs this module on whole
// ray batches (tb/harness/traverse_system.py).
module traverse_system
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  // traverse unit
  parameter int unsigned RAY_ID_W         = 16,  // ray id of the ray / result streams
  parameter int unsigned SETUP_FIFO_DEPTH = 32,  // power of two, > setup latency for full rate
  parameter int unsigned RES_FIFO_DEPTH   = 16,  // power of two
  parameter int unsigned UNIT_CNT_W       = 48,  // width of the unit's statistics counters
  parameter bit          PARK             = 1'b0, // 1: park queue for missed rays (traverse_loop)
  parameter int unsigned PARK_DEPTH       = PARK_DEPTH_DEF,  // park queue entries (traverse_loop)
  parameter int unsigned PARK_WAIT        = 16,  // clocks before a parked ray beats new rays (traverse_loop)
  parameter int unsigned PARK_MAX         = 4 * LOOP_DEPTH, // bound on a parked ray's wait (traverse_loop)
  // height cache
  parameter int unsigned LINE_BYTES       = 32,  // cache line (one AXI burst per line fill)
  parameter int unsigned SETS             = 256, // sets (power of two); 256 x 4 x 32 B = 32 KiB
  parameter int unsigned WAYS             = 4,   // associativity (power of two)
  parameter int unsigned MSHRS            = 4,   // line fills in flight
  // AXI4 read master
  parameter int unsigned AXI_ID_W         = 4,
  parameter int unsigned AXI_DATA_W       = 64
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  // configuration (traverse_unit; tb/harness/traverse_words.py packs it)
  input  logic [3:0]                        cfg_method_i,      // model.traverse.METHOD_CODES
  input  logic [DIM_W-1:0]                  cfg_width_i,
  input  logic [DIM_W-1:0]                  cfg_height_i,
  input  logic [LVL_W-1:0]                  cfg_root_level_i,
  input  logic                              cfg_bits16_i,
  input  logic [ADDR_W-1:0]                 cfg_base_i,        // byte address of the pyramid
  input  logic [CODE_W-1:0]                 cfg_root_code_i,
  input  logic [ITER_W-1:0]                 cfg_iter_cap_i,
  // the height pyramid's level-offset table (traverse_addr: LUT RAM, not reset, static while
  // busy): write hlt_wdata_i as level hlt_waddr_i's byte offset from cfg_base_i
  input  logic                              hlt_we_i,
  input  logic [LVL_W-1:0]                  hlt_waddr_i,
  input  logic [ADDR_W-1:0]                 hlt_wdata_i,
  // rays in
  input  logic                              ray_valid_i,
  output logic                              ray_ready_o,
  input  logic [RAY_ID_W-1:0]               ray_id_i,
  input  f24_t                              ray_u0_i,
  input  f24_t                              ray_v0_i,
  input  f24_t                              ray_du_i,
  input  f24_t                              ray_dv_i,
  // results out (completion order)
  output logic                              res_valid_o,
  input  logic                              res_ready_i,
  output logic [RAY_ID_W-1:0]               res_id_o,
  output f24_t                              res_t_o,
  output f24_t                              res_u_o,
  output f24_t                              res_v_o,
  output logic                              res_hit_o,
  output logic                              res_invalid_o,
  output logic                              res_capped_o,
  output logic                              res_err_o,
  output logic [ITER_W-1:0]                 res_iters_o,
  // AXI4 read master (read address and read data channels only)
  output logic [AXI_ID_W-1:0]               m_axi_arid,
  output logic [ADDR_W-1:0]                 m_axi_araddr,
  output logic [7:0]                        m_axi_arlen,
  output logic [2:0]                        m_axi_arsize,
  output logic [1:0]                        m_axi_arburst,
  output logic                              m_axi_arvalid,
  input  logic                              m_axi_arready,
  input  logic [AXI_ID_W-1:0]               m_axi_rid,
  input  logic [AXI_DATA_W-1:0]             m_axi_rdata,
  input  logic [1:0]                        m_axi_rresp,
  input  logic                              m_axi_rlast,
  input  logic                              m_axi_rvalid,
  output logic                              m_axi_rready,
  // statistics: traverse unit (since reset, wrapping)
  output logic [UNIT_CNT_W-1:0]             stat_cycles_o,      // clocks with a ray in the unit
  output logic [UNIT_CNT_W-1:0]             stat_rays_in_o,
  output logic [UNIT_CNT_W-1:0]             stat_rays_out_o,
  output logic [UNIT_CNT_W-1:0]             stat_iters_o,       // lookups that returned data
  output logic [UNIT_CNT_W-1:0]             stat_lookups_o,     // all lookups (hits + misses)
  output logic [UNIT_CNT_W-1:0]             stat_crossings_o,
  output logic [UNIT_CNT_W-1:0]             stat_level_ups_o,
  output logic [UNIT_CNT_W-1:0]             stat_descents_o,
  // statistics: height cache (cleared by clr_stats_i)
  input  logic                              clr_stats_i,
  output logic [47:0]                       stat_cache_hits_o,
  output logic [47:0]                       stat_cache_misses_o,
  output logic [47:0]                       stat_mem_bytes_o,   // bytes read over AXI
  output logic [47:0]                       stat_mem_lines_o,   // line fills
  output logic                              idle_o              // no ray in the unit
);

  // The unit and the cache agree on the lookup latency (each package has its own constant).
  if (cache_pkg::LOOKUP_LAT != traverse_pkg::LOOKUP_LAT) begin : g_check_lookup_lat
    $error("traverse_system: cache_pkg::LOOKUP_LAT != traverse_pkg::LOOKUP_LAT");
  end

  // ---- traverse unit and height cache ---------------------------------------------------------
  logic              lk_valid, lk_wide, rs_valid, rs_hit, rs_err;
  logic [ADDR_W-1:0] lk_addr;
  logic [CODE_W-1:0] rs_data;

  traverse_unit #(
    .ID_W(RAY_ID_W), .SETUP_FIFO_DEPTH(SETUP_FIFO_DEPTH), .RES_FIFO_DEPTH(RES_FIFO_DEPTH),
    .CNT_W(UNIT_CNT_W), .PARK(PARK), .PARK_DEPTH(PARK_DEPTH), .PARK_WAIT(PARK_WAIT),
    .PARK_MAX(PARK_MAX)
  ) u_unit (
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

  height_cache #(
    .ADDR_W(ADDR_W), .DATA_W(AXI_DATA_W), .LINE_BYTES(LINE_BYTES), .SETS(SETS), .WAYS(WAYS),
    .MSHRS(MSHRS), .ID_W(AXI_ID_W)
  ) u_cache (
    .clk_i, .rst_ni,
    .lk_valid_i(lk_valid), .lk_addr_i(lk_addr), .lk_wide_i(lk_wide),
    .rs_valid_o(rs_valid), .rs_hit_o(rs_hit), .rs_err_o(rs_err), .rs_data_o(rs_data),
    .m_axi_arid, .m_axi_araddr, .m_axi_arlen, .m_axi_arsize, .m_axi_arburst, .m_axi_arvalid,
    .m_axi_arready, .m_axi_rid, .m_axi_rdata, .m_axi_rresp, .m_axi_rlast, .m_axi_rvalid,
    .m_axi_rready,
    .clr_stats_i,
    .stat_hits_o(stat_cache_hits_o), .stat_misses_o(stat_cache_misses_o),
    .stat_bytes_o(stat_mem_bytes_o), .stat_lines_o(stat_mem_lines_o)
  );

endmodule
