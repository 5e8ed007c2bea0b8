// SPDX-License-Identifier: Apache-2.0
// traverse_rings: N_RINGS traverse_systems (each a traverse unit with its own height cache) behind
// one ray stream, one result stream and one AXI4 read port; the ports are traverse_system's.
//
//   rays -> deal -> traverse_system [0 .. N_RINGS-1] -> round-robin -> results
//                          |  AXI4 read masters (ids AXI_ID_W - log2 N_RINGS bits)
//                   axi_read_mux -> m_axi_ar* / m_axi_r*  (arid = {ring, the ring's id})
//
// N_RINGS = 1 is traverse_system itself (same clocks, same port).
// Dealing: a ray goes to the ready ring with the fewest rays inside (rays dealt minus results
//   taken; ties to the lower index), so a ring busy with long rays receives fewer.  Ray ids pass
//   through; results leave in completion order with their ids, as from one ring.
// Results: round-robin among the rings' result streams; a ring granted while its result is not
//   taken keeps the grant (the payload does not change under a waiting consumer).
// Statistics: each counter is the sum over the rings (stat_cycles_o counts ring-clocks with a ray
//   inside, so it may exceed the clocks); idle_o when every ring is idle.
module traverse_rings
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned N_RINGS          = 2,   // traverse rings (>= 1)
  // each ring (traverse_system's parameters)
  parameter int unsigned RAY_ID_W         = 16,  // ray id of the ray / result streams
  parameter int unsigned SETUP_FIFO_DEPTH = 32,  // power of two, > setup latency for full rate
  parameter int unsigned RES_FIFO_DEPTH   = 16,  // power of two
  parameter int unsigned UNIT_CNT_W       = 48,  // width of the units' statistics counters
  parameter bit          PARK             = 1'b0, // 1: park queue for missed rays (traverse_loop)
  parameter int unsigned PARK_DEPTH       = traverse_pkg::PARK_DEPTH_DEF,  // park queue entries (traverse_loop)
  parameter int unsigned PARK_WAIT        = 16,  // clocks before a parked ray beats new rays (traverse_loop)
  parameter int unsigned PARK_MAX         = 4 * traverse_pkg::LOOP_DEPTH, // bound on a parked ray's wait
  parameter int unsigned LINE_BYTES       = 32,  // height-cache line (one AXI burst per fill)
  parameter int unsigned SETS             = 256, // height-cache sets per ring (power of two)
  parameter int unsigned WAYS             = 4,   // height-cache ways (power of two)
  parameter int unsigned MSHRS            = 4,   // line fills in flight per ring
  // AXI4 read port (shared by the rings)
  parameter int unsigned AXI_ID_W         = 4,   // > log2(N_RINGS) + log2(MSHRS)
  parameter int unsigned AXI_DATA_W       = 64
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  // configuration (every ring's; see traverse_system)
  input  logic [3:0]                        cfg_method_i,
  input  logic [DIM_W-1:0]                  cfg_width_i,
  input  logic [DIM_W-1:0]                  cfg_height_i,
  input  logic [LVL_W-1:0]                  cfg_root_level_i,
  input  logic                              cfg_bits16_i,
  input  logic [ADDR_W-1:0]                 cfg_base_i,
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
  // AXI4 read master
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
  // statistics: traverse units (sums; since reset, wrapping)
  output logic [UNIT_CNT_W-1:0]             stat_cycles_o,
  output logic [UNIT_CNT_W-1:0]             stat_rays_in_o,
  output logic [UNIT_CNT_W-1:0]             stat_rays_out_o,
  output logic [UNIT_CNT_W-1:0]             stat_iters_o,
  output logic [UNIT_CNT_W-1:0]             stat_lookups_o,
  output logic [UNIT_CNT_W-1:0]             stat_crossings_o,
  output logic [UNIT_CNT_W-1:0]             stat_level_ups_o,
  output logic [UNIT_CNT_W-1:0]             stat_descents_o,
  // statistics: height caches (sums; cleared by clr_stats_i)
  input  logic                              clr_stats_i,
  output logic [47:0]                       stat_cache_hits_o,
  output logic [47:0]                       stat_cache_misses_o,
  output logic [47:0]                       stat_mem_bytes_o,
  output logic [47:0]                       stat_mem_lines_o,
  output logic                              idle_o
);

  localparam int unsigned R      = N_RINGS;
  localparam int unsigned SEL_W  = (R > 1) ? $clog2(R) : 1;
  localparam int unsigned RID_W  = AXI_ID_W - ((R > 1) ? $clog2(R) : 0);  // each ring's AXI id
  localparam int unsigned CNT_W  = RAY_ID_W + 1;                          // rays inside a ring

  if (R < 1) begin : g_check_rings
    $error("traverse_rings: N_RINGS must be >= 1");
  end
  if (RID_W <= ((MSHRS > 1) ? $clog2(MSHRS) : 0)) begin : g_check_id
    $error("traverse_rings: AXI_ID_W too small for N_RINGS rings of MSHRS line fills");
  end

  // ---- the rings -------------------------------------------------------------------------------
  logic [R-1:0]                 r_ray_valid, r_ray_ready;
  logic [R-1:0]                 r_res_valid, r_res_ready, r_hit, r_inv, r_capped, r_err;
  logic [R-1:0][RAY_ID_W-1:0]   r_id;
  f24_t [R-1:0]                 r_t, r_u, r_v;
  logic [R-1:0][ITER_W-1:0]     r_iters;
  logic [R-1:0][RID_W-1:0]      r_arid, r_rid;
  logic [R-1:0][ADDR_W-1:0]     r_araddr;
  logic [R-1:0][7:0]            r_arlen;
  logic [R-1:0][2:0]            r_arsize;
  logic [R-1:0][1:0]            r_arburst, r_rresp;
  logic [R-1:0]                 r_arvalid, r_arready, r_rlast, r_rvalid, r_rready, r_idle;
  logic [R-1:0][AXI_DATA_W-1:0] r_rdata;
  logic [R-1:0][7:0][UNIT_CNT_W-1:0] r_ustat;   // the unit's eight counters
  logic [R-1:0][3:0][47:0]           r_cstat;   // the cache's four counters

  for (genvar r = 0; r < R; r++) begin : g_ring
    traverse_system #(
      .RAY_ID_W(RAY_ID_W), .SETUP_FIFO_DEPTH(SETUP_FIFO_DEPTH), .RES_FIFO_DEPTH(RES_FIFO_DEPTH),
      .UNIT_CNT_W(UNIT_CNT_W), .PARK(PARK), .PARK_DEPTH(PARK_DEPTH),
      .PARK_WAIT(PARK_WAIT), .PARK_MAX(PARK_MAX),
      .LINE_BYTES(LINE_BYTES), .SETS(SETS), .WAYS(WAYS), .MSHRS(MSHRS),
      .AXI_ID_W(RID_W), .AXI_DATA_W(AXI_DATA_W)
    ) u_sys (
      .clk_i, .rst_ni,
      .cfg_method_i, .cfg_width_i, .cfg_height_i, .cfg_root_level_i, .cfg_bits16_i, .cfg_base_i,
      .cfg_root_code_i, .cfg_iter_cap_i, .hlt_we_i, .hlt_waddr_i, .hlt_wdata_i,
      .ray_valid_i(r_ray_valid[r]), .ray_ready_o(r_ray_ready[r]), .ray_id_i,
      .ray_u0_i, .ray_v0_i, .ray_du_i, .ray_dv_i,
      .res_valid_o(r_res_valid[r]), .res_ready_i(r_res_ready[r]), .res_id_o(r_id[r]),
      .res_t_o(r_t[r]), .res_u_o(r_u[r]), .res_v_o(r_v[r]), .res_hit_o(r_hit[r]),
      .res_invalid_o(r_inv[r]), .res_capped_o(r_capped[r]), .res_err_o(r_err[r]),
      .res_iters_o(r_iters[r]),
      .m_axi_arid(r_arid[r]), .m_axi_araddr(r_araddr[r]), .m_axi_arlen(r_arlen[r]),
      .m_axi_arsize(r_arsize[r]), .m_axi_arburst(r_arburst[r]), .m_axi_arvalid(r_arvalid[r]),
      .m_axi_arready(r_arready[r]), .m_axi_rid(r_rid[r]), .m_axi_rdata(r_rdata[r]),
      .m_axi_rresp(r_rresp[r]), .m_axi_rlast(r_rlast[r]), .m_axi_rvalid(r_rvalid[r]),
      .m_axi_rready(r_rready[r]),
      .stat_cycles_o(r_ustat[r][0]), .stat_rays_in_o(r_ustat[r][1]),
      .stat_rays_out_o(r_ustat[r][2]), .stat_iters_o(r_ustat[r][3]),
      .stat_lookups_o(r_ustat[r][4]), .stat_crossings_o(r_ustat[r][5]),
      .stat_level_ups_o(r_ustat[r][6]), .stat_descents_o(r_ustat[r][7]),
      .clr_stats_i,
      .stat_cache_hits_o(r_cstat[r][0]), .stat_cache_misses_o(r_cstat[r][1]),
      .stat_mem_bytes_o(r_cstat[r][2]), .stat_mem_lines_o(r_cstat[r][3]),
      .idle_o(r_idle[r])
    );
  end

  // ---- dealing: the ready ring with the fewest rays inside ---------------------------------------
  logic [R-1:0][CNT_W-1:0] inside_q;
  logic [SEL_W-1:0]        deal;
  logic                    any_ready;

  always_comb begin
    deal      = '0;
    any_ready = 1'b0;
    for (int r = 0; r < R; r++) begin
      if (r_ray_ready[r] && (!any_ready || inside_q[r] < inside_q[deal])) begin
        deal      = SEL_W'(r);
        any_ready = 1'b1;
      end
    end
  end

  assign ray_ready_o = any_ready;
  always_comb begin
    r_ray_valid       = '0;
    r_ray_valid[deal] = ray_valid_i && any_ready;
  end

  // ---- results: round-robin, the grant held while its result waits ------------------------------
  logic [SEL_W-1:0] gnt;
  rr_hold_arb #(.N(R)) u_res_arb (
    .clk_i, .rst_ni, .req_i(r_res_valid), .ready_i(res_ready_i), .gnt_o(gnt),
    .valid_o(res_valid_o));

  assign res_id_o      = r_id[gnt];
  assign res_t_o       = r_t[gnt];
  assign res_u_o       = r_u[gnt];
  assign res_v_o       = r_v[gnt];
  assign res_hit_o     = r_hit[gnt];
  assign res_invalid_o = r_inv[gnt];
  assign res_capped_o  = r_capped[gnt];
  assign res_err_o     = r_err[gnt];
  assign res_iters_o   = r_iters[gnt];
  always_comb begin
    r_res_ready      = '0;
    r_res_ready[gnt] = res_ready_i;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      inside_q   <= '0;
    end else begin
      for (int r = 0; r < R; r++) begin
        inside_q[r] <= inside_q[r] + CNT_W'(r_ray_valid[r] && r_ray_ready[r])
                                   - CNT_W'(r_res_valid[r] && r_res_ready[r]);
      end
    end
  end

  // ---- AXI: one port for the rings' height caches ------------------------------------------------
  axi_read_mux #(.N(R), .ADDR_W(ADDR_W), .DATA_W(AXI_DATA_W), .ID_W(RID_W)) u_axi (
    .clk_i, .rst_ni,
    .s_arid_i(r_arid), .s_araddr_i(r_araddr), .s_arlen_i(r_arlen), .s_arsize_i(r_arsize),
    .s_arburst_i(r_arburst), .s_arvalid_i(r_arvalid), .s_arready_o(r_arready),
    .s_rid_o(r_rid), .s_rdata_o(r_rdata), .s_rresp_o(r_rresp), .s_rlast_o(r_rlast),
    .s_rvalid_o(r_rvalid), .s_rready_i(r_rready),
    .m_arid_o(m_axi_arid), .m_araddr_o(m_axi_araddr), .m_arlen_o(m_axi_arlen),
    .m_arsize_o(m_axi_arsize), .m_arburst_o(m_axi_arburst), .m_arvalid_o(m_axi_arvalid),
    .m_arready_i(m_axi_arready), .m_rid_i(m_axi_rid), .m_rdata_i(m_axi_rdata),
    .m_rresp_i(m_axi_rresp), .m_rlast_i(m_axi_rlast), .m_rvalid_i(m_axi_rvalid),
    .m_rready_o(m_axi_rready));

  // ---- statistics: sums over the rings -------------------------------------------------------------
  logic [7:0][UNIT_CNT_W-1:0] ustat;
  logic [3:0][47:0]           cstat;
  always_comb begin
    ustat  = '0;
    cstat  = '0;
    idle_o = 1'b1;
    for (int r = 0; r < R; r++) begin
      for (int k = 0; k < 8; k++) ustat[k] = ustat[k] + r_ustat[r][k];
      for (int k = 0; k < 4; k++) cstat[k] = cstat[k] + r_cstat[r][k];
      idle_o = idle_o && r_idle[r];
    end
  end
  assign stat_cycles_o       = ustat[0];
  assign stat_rays_in_o      = ustat[1];
  assign stat_rays_out_o     = ustat[2];
  assign stat_iters_o        = ustat[3];
  assign stat_lookups_o      = ustat[4];
  assign stat_crossings_o    = ustat[5];
  assign stat_level_ups_o    = ustat[6];
  assign stat_descents_o     = ustat[7];
  assign stat_cache_hits_o   = cstat[0];
  assign stat_cache_misses_o = cstat[1];
  assign stat_mem_bytes_o    = cstat[2];
  assign stat_mem_lines_o    = cstat[3];

endmodule
