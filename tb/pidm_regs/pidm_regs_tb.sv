// SPDX-License-Identifier: Apache-2.0
// pidm_regs_tb: the generated register block pidm_regs with pidm_cfg behind it, its hwif structs
// flattened into ports for cocotb: the configuration as dm_pipeline's cfg_* ports, triangle-table
// write port and level table write port (pidm_cfg), the control, error, interrupt and
// frame-descriptor fields, and the hardware inputs (status, error sets, interrupt events,
// progress, statistics, HWCFG).  The interrupt inputs are driven as pidm_top drives them: event |
// INTR_TEST pulse; the external registers' acknowledges (hwif_in.HEIGHT, hwif_in.TEX) come from
// pidm_cfg, as in pidm_top.
module pidm_regs_tb
  import f24_pkg::*;
  import traverse_pkg::*;
  import pipe_pkg::*;
  import shade_pkg::*;
#(
  parameter int unsigned TRIS  = 16,
  parameter int unsigned TRI_W = (TRIS > 1) ? $clog2(TRIS) : 1
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // AXI4-Lite
  output logic                 s_axil_awready,
  input  logic                 s_axil_awvalid,
  input  logic [11:0]          s_axil_awaddr,
  input  logic [2:0]           s_axil_awprot,
  output logic                 s_axil_wready,
  input  logic                 s_axil_wvalid,
  input  logic [31:0]          s_axil_wdata,
  input  logic [3:0]           s_axil_wstrb,
  input  logic                 s_axil_bready,
  output logic                 s_axil_bvalid,
  output logic [1:0]           s_axil_bresp,
  output logic                 s_axil_arready,
  input  logic                 s_axil_arvalid,
  input  logic [11:0]          s_axil_araddr,
  input  logic [2:0]           s_axil_arprot,
  input  logic                 s_axil_rready,
  output logic                 s_axil_rvalid,
  output logic [31:0]          s_axil_rdata,
  output logic [1:0]           s_axil_rresp,
  // configuration (pidm_cfg)
  output logic [3:0]           cfg_method_o,
  output logic [DIM_W-1:0]     cfg_width_o,
  output logic [DIM_W-1:0]     cfg_height_o,
  output logic [LVL_W-1:0]     cfg_root_level_o,
  output logic                 cfg_bits16_o,
  output logic [ADDR_W-1:0]    cfg_base_o,
  output logic [CODE_W-1:0]    cfg_root_code_o,
  output logic [ITER_W-1:0]    cfg_iter_cap_o,
  output f24_t                 cfg_depth_o,
  output logic                 cfg_mip_en_o,
  output logic [MIP_LEVEL_W:0] cfg_levels_colour_o,
  output logic [MIP_LEVEL_W:0] cfg_levels_normal_o,
  output shade_cfg_t           cfg_shade_o,
  output logic [2:0][7:0]      cfg_miss_rgb_o,
  output f24_t [1:0]           cfg_tex_su_o,
  output f24_t [1:0]           cfg_tex_sv_o,
  output logic [1:0][TEX_ADDR_W-1:0] cfg_tex_base_o,
  output logic                 tt_we_o,
  output logic [TRI_W:0]       tt_waddr_o,
  output f24_t                 tt_wdata_o,
  output logic                 lvt_we_o,
  output logic [LVT_ADDR_W-1:0] lvt_waddr_o,
  output logic [31:0]          lvt_wdata_o,
  // control, errors, interrupts, frame descriptor
  output logic                 start_o,
  output logic                 soft_reset_o,
  output logic                 clear_stats_o,
  output logic                 pyr_start_o,
  output logic [8:0]           error_o,       // h_axi, t_axi, frag_dma, fb_write, bad_config,
                                              // pyr_read, pyr_write, pyr_config, start_refused
  output logic                 intr_o,
  output logic [63:0]          frag_base_o,
  output logic [31:0]          frag_count_o,
  output logic [63:0]          fb_base_o,
  output logic [31:0]          fb_pitch_o,
  output logic [63:0]          status_base_o,
  output logic [4:0]           xbits_o,
  output logic                 status_en_o,
  // hardware inputs
  input  logic                 busy_i,
  input  logic                 idle_i,
  input  logic [8:0]           error_set_i,
  input  logic [2:0]           intr_event_i,  // frame_done, axi_error, pyr_done
  input  logic [5:0]           pyr_status_i,  // STATUS pyr_busy, pyr_done, pyr_err_code[3:0]
  input  logic [4:0]           pyr_info_i,    // PYR.INFO present, max_lg[3:0]
  input  logic [31:0]          progress_i,
  input  logic [10:0][47:0]    stats_i,       // [0] cycles .. [10] t_bytes
  input  logic [31:0]          hwcfg_i
);

  pidm_regs_pkg::pidm_regs__in_t  hwif_in;
  pidm_regs_pkg::pidm_regs__out_t hwif_out;
  pidm_regs_pkg::pidm_regs__HEIGHT__in_t hwif_in_height;
  pidm_regs_pkg::pidm_regs__TEXx__in_t   hwif_in_tex [2];

  pidm_regs u_regs (
    .clk(clk_i), .rst_n(rst_ni),
    .s_axil_awready, .s_axil_awvalid, .s_axil_awaddr, .s_axil_awprot, .s_axil_wready,
    .s_axil_wvalid, .s_axil_wdata, .s_axil_wstrb, .s_axil_bready, .s_axil_bvalid, .s_axil_bresp,
    .s_axil_arready, .s_axil_arvalid, .s_axil_araddr, .s_axil_arprot, .s_axil_rready,
    .s_axil_rvalid, .s_axil_rdata, .s_axil_rresp, .hwif_in, .hwif_out);

  pidm_cfg #(.TRIS(TRIS)) u_cfg (
    .clk_i, .rst_ni, .hwif_i(hwif_out),
    .cfg_method_o, .cfg_width_o, .cfg_height_o, .cfg_root_level_o, .cfg_bits16_o, .cfg_base_o,
    .cfg_root_code_o, .cfg_iter_cap_o, .cfg_depth_o, .cfg_mip_en_o,
    .cfg_levels_colour_o, .cfg_levels_normal_o, .cfg_shade_o, .cfg_miss_rgb_o, .cfg_tex_su_o,
    .cfg_tex_sv_o, .cfg_tex_base_o, .tt_we_o, .tt_waddr_o, .tt_wdata_o, .lvt_we_o, .lvt_waddr_o,
    .lvt_wdata_o, .hwif_height_o(hwif_in_height), .hwif_tex_o(hwif_in_tex));

  assign start_o       = hwif_out.CTRL.start.value;
  assign soft_reset_o  = hwif_out.CTRL.soft_reset.value;
  assign clear_stats_o = hwif_out.CTRL.clear_stats.value;
  assign pyr_start_o   = hwif_out.CTRL.pyr_start.value;
  assign error_o = {hwif_out.ERROR.start_refused.value, hwif_out.ERROR.pyr_config.value,
                    hwif_out.ERROR.pyr_write.value, hwif_out.ERROR.pyr_read.value,
                    hwif_out.ERROR.bad_config.value, hwif_out.ERROR.fb_write.value,
                    hwif_out.ERROR.frag_dma.value, hwif_out.ERROR.t_axi.value,
                    hwif_out.ERROR.h_axi.value};
  assign intr_o        = hwif_out.INTR_STATE.intr;
  assign frag_base_o   = {hwif_out.FRAME.FRAG_BASE.HI.val.value, hwif_out.FRAME.FRAG_BASE.LO.val.value};
  assign frag_count_o  = hwif_out.FRAME.FRAG_COUNT.val.value;
  assign fb_base_o     = {hwif_out.FRAME.FB_BASE.HI.val.value, hwif_out.FRAME.FB_BASE.LO.val.value};
  assign fb_pitch_o    = hwif_out.FRAME.FB_PITCH.val.value;
  assign status_base_o = {hwif_out.FRAME.STATUS_BASE.HI.val.value,
                          hwif_out.FRAME.STATUS_BASE.LO.val.value};
  assign xbits_o       = hwif_out.FRAME.FB_LAYOUT.xbits.value;
  assign status_en_o   = hwif_out.FRAME.FB_LAYOUT.status_en.value;

  always_comb begin
    hwif_in.HWCFG.pix_w.next      = hwcfg_i[7:0];
    hwif_in.HWCFG.tris.next       = hwcfg_i[15:8];
    hwif_in.HWCFG.addr_w.next     = hwcfg_i[23:16];
    hwif_in.HWCFG.data_bytes.next = hwcfg_i[31:24];
    hwif_in.STATUS.busy.next      = busy_i;
    hwif_in.STATUS.idle.next      = idle_i;
    hwif_in.STATUS.pyr_busy.next  = pyr_status_i[0];
    hwif_in.STATUS.pyr_done.next  = pyr_status_i[1];
    hwif_in.STATUS.pyr_err_code.next = pyr_status_i[5:2];
    hwif_in.PYR.INFO.present.next = pyr_info_i[0];
    hwif_in.PYR.INFO.max_lg.next  = pyr_info_i[4:1];
    hwif_in.ERROR.h_axi.hwset      = error_set_i[0];
    hwif_in.ERROR.t_axi.hwset      = error_set_i[1];
    hwif_in.ERROR.frag_dma.hwset   = error_set_i[2];
    hwif_in.ERROR.fb_write.hwset   = error_set_i[3];
    hwif_in.ERROR.bad_config.hwset = error_set_i[4];
    hwif_in.ERROR.pyr_read.hwset   = error_set_i[5];
    hwif_in.ERROR.pyr_write.hwset  = error_set_i[6];
    hwif_in.ERROR.pyr_config.hwset = error_set_i[7];
    hwif_in.ERROR.start_refused.hwset = error_set_i[8];
    hwif_in.PROGRESS.pixels.next   = progress_i;
    hwif_in.INTR_STATE.frame_done.next = intr_event_i[0] | hwif_out.INTR_TEST.frame_done.value;
    hwif_in.INTR_STATE.axi_error.next  = intr_event_i[1] | hwif_out.INTR_TEST.axi_error.value;
    hwif_in.INTR_STATE.pyr_done.next   = intr_event_i[2] | hwif_out.INTR_TEST.pyr_done.value;
    hwif_in.STATS.cycles.LO.val.next        = stats_i[0][31:0];
    hwif_in.STATS.cycles.HI.val.next        = stats_i[0][47:32];
    hwif_in.STATS.pixels.LO.val.next        = stats_i[1][31:0];
    hwif_in.STATS.pixels.HI.val.next        = stats_i[1][47:32];
    hwif_in.STATS.iters.LO.val.next         = stats_i[2][31:0];
    hwif_in.STATS.iters.HI.val.next         = stats_i[2][47:32];
    hwif_in.STATS.h_hits.LO.val.next        = stats_i[3][31:0];
    hwif_in.STATS.h_hits.HI.val.next        = stats_i[3][47:32];
    hwif_in.STATS.h_misses.LO.val.next      = stats_i[4][31:0];
    hwif_in.STATS.h_misses.HI.val.next      = stats_i[4][47:32];
    hwif_in.STATS.h_bytes.LO.val.next       = stats_i[5][31:0];
    hwif_in.STATS.h_bytes.HI.val.next       = stats_i[5][47:32];
    hwif_in.STATS.t_requests.LO.val.next    = stats_i[6][31:0];
    hwif_in.STATS.t_requests.HI.val.next    = stats_i[6][47:32];
    hwif_in.STATS.t_quad_hits.LO.val.next   = stats_i[7][31:0];
    hwif_in.STATS.t_quad_hits.HI.val.next   = stats_i[7][47:32];
    hwif_in.STATS.t_line_misses.LO.val.next = stats_i[8][31:0];
    hwif_in.STATS.t_line_misses.HI.val.next = stats_i[8][47:32];
    hwif_in.STATS.t_texel_hits.LO.val.next  = stats_i[9][31:0];
    hwif_in.STATS.t_texel_hits.HI.val.next  = stats_i[9][47:32];
    hwif_in.STATS.t_bytes.LO.val.next       = stats_i[10][31:0];
    hwif_in.STATS.t_bytes.HI.val.next       = stats_i[10][47:32];
    hwif_in.HEIGHT = hwif_in_height;
    for (int x = 0; x < 2; x++) hwif_in.TEX[x] = hwif_in_tex[x];
  end

endmodule
