// SPDX-License-Identifier: Apache-2.0
// dm_pipeline_fpga_top: dm_pipeline with a pin count that fits an FPGA package, for place and
// route (scripts/flow/synth.py, `make synth`).  Not used by the simulations.
//
// dm_pipeline has about 1,500 port bits (the configuration alone about 520); an LFE5U-85F has at
// most 365 user I/Os (CABGA756).  This wrapper keeps both AXI4 read ports as they are (252 pins)
// and replaces the configuration, fragment, pixel and statistics ports by a 32-bit register
// port: every configuration field, the fragment fields, the triangle table and the control
// strobes are registers written through it, and the pixel and the statistics are read back
// through it.  Every bit of dm_pipeline stays observable, so synthesis removes nothing.  This is
// the shape a host interface (an AXI4-Lite slave, a soft CPU's bus) would give it; a real
// system would feed fragments from a rasteriser instead of one register write per field.
//
// Register port: synchronous; inputs are registered once; reg_rdata_o is the read-map word at the
// reg_addr_i of two clocks earlier.
//
// AXI ports: each of the four channels (AR and R of both ports) passes a register slice
// (axi_read_slice: a skid_buffer with REG_OUT 1 per channel) between the pins and dm_pipeline,
// as an interconnect's register slice would: every pin meets a flip-flop, so no path runs from a pin through the caches' logic
// and the placer does not pull that logic towards the pins (the I/O are not located). Each
// slice adds one clock to its channel (two to a read's latency) and keeps one beat a clock.
//
// Write map (word address: fields; unlisted bits ignored)
//   0x00  [3:0] method, [7:4] root level, [8] bits16, [9] mip_en, [21:16] levels colour,
//         [29:24] levels normal
//   0x01  [15:0] width, [31:16] height           0x02  base (height pyramid byte address)
//   0x03  [15:0] root code, [31:16] iteration cap
//   0x04  [23:0] depth D                          0x05  [23:0] miss colour (R in [7:0])
//   0x06 .. 0x0D  [23:0] shade_cfg_t fields: light_x, light_y, light_z, ambient, kd, ks, d, d2
//   0x0E, 0x0F  texture su [0] colour, [1] normal map;   0x10, 0x11  sv;   0x12, 0x13  base
//   0x20 + k            height level offset k (k = 0 .. 15)
//   0x40 + 16 x + k     texture x level k offset
//   0x60 + 16 x + k     texture x level k: [15:0] width, [31:16] height
//         (0x20 .. 0x2F and 0x40 .. 0x7F go straight to dm_pipeline's level tables, lvt_*: no
//         register here)
//   0x80  [PIX_W-1:0] fragment id     0x81 u0   0x82 v0   0x83 Pl0   0x84 [TRI_W-1:0] triangle
//   0x85 .. 0x8D  TBN (T 0..2, B 3..5, N 6..8)     0x8E .. 0x90  view vector
//   0x91  control, write 1 to: [0] push the fragment (waits in the register until accepted),
//         [1] pop the output pixel, [2] clear the statistics
//   0x92  triangle table write: [23:0] data, [24 +: TRI_W + 1] address
// Read map
//   0x00  [0] pixel valid, [1] fragment pending, [2] idle
//   0x01  [PIX_W-1:0] pixel id, [29] hit, [30] invalid, [31] error
//   0x02  [23:0] pixel rgb        0x03  [15:0] pixel iterations
//   0x20 + 2 i, 0x21 + 2 i   statistic i, low 32 bits and high 16 bits: i = 0 cycles, 1 pixels,
//         2 iterations, 3 height hits, 4 height misses, 5 height bytes, 6 texture requests,
//         7 texture quad hits, 8 texture line misses, 9 texture bytes, 10 texture texel hits
module dm_pipeline_fpga_top
  import f24_pkg::*;
  import traverse_pkg::*;
  import pipe_pkg::*;
  import shade_pkg::*;
#(
  parameter int unsigned PIX_W      = 20,   // at most 28 (read word 0x01)
  parameter int unsigned SLOTS      = 128,
  parameter int unsigned N_RINGS    = 1,    // traverse rings (dm_pipeline N_RINGS)
  parameter int unsigned TRIS       = 16,
  parameter int unsigned H_ID_W     = 4,
  parameter int unsigned T_ID_W     = 6,
  parameter int unsigned AXI_DATA_W = 64,
  // the texture cache's tags and reference counts (dm_pipeline T_DIR_RAM): LUT RAM ("auto");
  // "block" takes 32 EBRs for fewer LUT4 but routes slower (docs/synthesis.md, "Where the area
  // goes"), and with two rings too few EBRs are left for it
  parameter string       T_DIR_RAM  = "auto",
  parameter int unsigned TRI_W      = (TRIS > 1) ? $clog2(TRIS) : 1
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  // register port
  input  logic                   reg_we_i,
  input  logic [7:0]             reg_addr_i,
  input  logic [31:0]            reg_wdata_i,
  output logic [31:0]            reg_rdata_o,
  output logic                   px_valid_o,   // a pixel is waiting (interrupt)
  output logic                   idle_o,
  // AXI4 read master: heights
  output logic [H_ID_W-1:0]      m_axi_h_arid,
  output logic [ADDR_W-1:0]      m_axi_h_araddr,
  output logic [7:0]             m_axi_h_arlen,
  output logic [2:0]             m_axi_h_arsize,
  output logic [1:0]             m_axi_h_arburst,
  output logic                   m_axi_h_arvalid,
  input  logic                   m_axi_h_arready,
  input  logic [H_ID_W-1:0]      m_axi_h_rid,
  input  logic [AXI_DATA_W-1:0]  m_axi_h_rdata,
  input  logic [1:0]             m_axi_h_rresp,
  input  logic                   m_axi_h_rlast,
  input  logic                   m_axi_h_rvalid,
  output logic                   m_axi_h_rready,
  // AXI4 read master: textures
  output logic [T_ID_W-1:0]      m_axi_t_arid,
  output logic [TEX_ADDR_W-1:0]  m_axi_t_araddr,
  output logic [7:0]             m_axi_t_arlen,
  output logic [2:0]             m_axi_t_arsize,
  output logic [1:0]             m_axi_t_arburst,
  output logic                   m_axi_t_arvalid,
  input  logic                   m_axi_t_arready,
  input  logic [T_ID_W-1:0]      m_axi_t_rid,
  input  logic [AXI_DATA_W-1:0]  m_axi_t_rdata,
  input  logic [1:0]             m_axi_t_rresp,
  input  logic                   m_axi_t_rlast,
  input  logic                   m_axi_t_rvalid,
  output logic                   m_axi_t_rready
);

  if (PIX_W > 28) begin : g_check_pix
    $error("dm_pipeline_fpga_top: PIX_W must be at most 28");
  end

  // ---- register port inputs, registered -----------------------------------------------------
  logic        rst_nq, we_q;
  logic [7:0]  addr_q;
  logic [31:0] wdata_q;
  always_ff @(posedge clk_i) begin
    rst_nq  <= rst_ni;
    we_q    <= reg_we_i;
    addr_q  <= reg_addr_i;
    wdata_q <= reg_wdata_i;
  end

  // ---- configuration registers ----------------------------------------------------------------
  logic [3:0]                        cfg_method_q;
  logic [DIM_W-1:0]                  cfg_width_q, cfg_height_q;
  logic [LVL_W-1:0]                  cfg_root_level_q;
  logic                              cfg_bits16_q, cfg_mip_en_q;
  logic [ADDR_W-1:0]                 cfg_base_q;
  logic [CODE_W-1:0]                 cfg_root_code_q;
  logic [ITER_W-1:0]                 cfg_iter_cap_q;
  f24_t                              cfg_depth_q;
  logic [MIP_LEVEL_W:0]              cfg_levels_colour_q, cfg_levels_normal_q;
  f24_t [7:0]                        cfg_shade_q;     // [7] light_x .. [0] d2 (shade_cfg_t order)
  logic [2:0][7:0]                   cfg_miss_rgb_q;
  f24_t [1:0]                        cfg_tex_su_q, cfg_tex_sv_q;
  logic [1:0][TEX_ADDR_W-1:0]                 cfg_tex_base_q;
  // The level tables are dm_pipeline's (LUT RAM): the words 0x20 .. 0x2F and 0x40 .. 0x7F are
  // its lvt_* writes, word address {kind, texture, level} = reg_addr_i[6:0] (pipe_pkg::LVT_*).
  logic lvt_we;
  assign lvt_we = we_q && (addr_q[7:4] == 4'h2 || addr_q[7:6] == 2'b01);

  // fragment registers
  logic [PIX_W-1:0] frag_id_q;
  f24_t             frag_u0_q, frag_v0_q, frag_pl0_q;
  logic [TRI_W-1:0] frag_tri_q;
  f24_t [8:0]       frag_tbn_q;
  f24_t [2:0]       frag_view_q;

  logic [3:0] a_lo;
  assign a_lo = addr_q[3:0];

  always_ff @(posedge clk_i) begin
    if (we_q) begin
      case (addr_q[7:4])
        4'h0: case (a_lo)
          4'h0: begin
            cfg_method_q        <= wdata_q[3:0];
            cfg_root_level_q    <= wdata_q[7:4];
            cfg_bits16_q        <= wdata_q[8];
            cfg_mip_en_q        <= wdata_q[9];
            cfg_levels_colour_q <= wdata_q[16 +: MIP_LEVEL_W + 1];
            cfg_levels_normal_q <= wdata_q[24 +: MIP_LEVEL_W + 1];
          end
          4'h1: begin
            cfg_width_q  <= wdata_q[15:0];
            cfg_height_q <= wdata_q[31:16];
          end
          4'h2: cfg_base_q <= wdata_q;
          4'h3: begin
            cfg_root_code_q <= wdata_q[15:0];
            cfg_iter_cap_q  <= wdata_q[31:16];
          end
          4'h4: cfg_depth_q    <= wdata_q[23:0];
          4'h5: cfg_miss_rgb_q <= wdata_q[23:0];
          4'h6, 4'h7, 4'h8, 4'h9, 4'hA, 4'hB, 4'hC, 4'hD:
            cfg_shade_q[4'd13 - a_lo] <= wdata_q[23:0];
          4'hE: cfg_tex_su_q[0] <= wdata_q[23:0];
          default: cfg_tex_su_q[1] <= wdata_q[23:0];
        endcase
        4'h1: case (a_lo)
          4'h0: cfg_tex_sv_q[0]   <= wdata_q[23:0];
          4'h1: cfg_tex_sv_q[1]   <= wdata_q[23:0];
          4'h2: cfg_tex_base_q[0] <= wdata_q;
          4'h3: cfg_tex_base_q[1] <= wdata_q;
          default: ;
        endcase
        4'h8: case (a_lo)
          4'h0: frag_id_q  <= wdata_q[PIX_W-1:0];
          4'h1: frag_u0_q  <= wdata_q[23:0];
          4'h2: frag_v0_q  <= wdata_q[23:0];
          4'h3: frag_pl0_q <= wdata_q[23:0];
          4'h4: frag_tri_q <= wdata_q[TRI_W-1:0];
          4'hE, 4'hF: frag_view_q[a_lo - 4'hE] <= wdata_q[23:0];
          default: frag_tbn_q[a_lo - 4'h5] <= wdata_q[23:0];
        endcase
        4'h9: if (a_lo == 4'h0) frag_view_q[2] <= wdata_q[23:0];
        default: ;
      endcase
    end
  end

  // ---- control strobes, fragment handshake, triangle table ------------------------------------
  logic             ctl_wr;
  logic             frag_valid_q, frag_ready, pop_q, clr_q;
  logic             tt_we_q;
  logic [TRI_W:0]   tt_waddr_q;
  f24_t             tt_wdata_q;
  logic             px_valid, px_ready;

  assign ctl_wr   = we_q && addr_q == 8'h91;
  assign px_ready = pop_q && px_valid;

  always_ff @(posedge clk_i) begin
    if (!rst_nq) begin
      frag_valid_q <= 1'b0;
      pop_q        <= 1'b0;
      clr_q        <= 1'b0;
      tt_we_q      <= 1'b0;
    end else begin
      if (ctl_wr && wdata_q[0])         frag_valid_q <= 1'b1;
      else if (frag_ready)              frag_valid_q <= 1'b0;
      if (ctl_wr && wdata_q[1])         pop_q <= 1'b1;
      else if (px_valid)                pop_q <= 1'b0;
      clr_q   <= ctl_wr && wdata_q[2];
      tt_we_q <= we_q && addr_q == 8'h92;
    end
  end
  always_ff @(posedge clk_i) begin
    tt_waddr_q <= wdata_q[24 +: TRI_W + 1];
    tt_wdata_q <= wdata_q[23:0];
  end

  // ---- the pipeline -----------------------------------------------------------------------------
  logic [PIX_W-1:0]  px_id;
  logic [2:0][7:0]   px_rgb;
  logic              px_hit, px_invalid, px_err, idle;
  logic [ITER_W-1:0] px_iters;
  logic [10:0][47:0] stat;

  // ---- AXI register slices ------------------------------------------------------------------
  // dm_pipeline's side of the two read ports (h_*: heights, t_*: textures)
  logic [H_ID_W-1:0]     h_arid, h_rid;
  logic [ADDR_W-1:0]     h_araddr;
  logic [7:0]            h_arlen;
  logic [2:0]            h_arsize;
  logic [1:0]            h_arburst, h_rresp;
  logic                  h_arvalid, h_arready, h_rvalid, h_rready, h_rlast;
  logic [AXI_DATA_W-1:0] h_rdata;
  logic [T_ID_W-1:0]     t_arid, t_rid;
  logic [TEX_ADDR_W-1:0] t_araddr;
  logic [7:0]            t_arlen;
  logic [2:0]            t_arsize;
  logic [1:0]            t_arburst, t_rresp;
  logic                  t_arvalid, t_arready, t_rvalid, t_rready, t_rlast;
  logic [AXI_DATA_W-1:0] t_rdata;

  axi_read_slice #(.ID_W(H_ID_W), .ADDR_W(ADDR_W), .DATA_W(AXI_DATA_W)) u_h_slice (
    .clk_i, .rst_ni(rst_nq),
    .s_arid(h_arid), .s_araddr(h_araddr), .s_arlen(h_arlen), .s_arsize(h_arsize),
    .s_arburst(h_arburst), .s_arvalid(h_arvalid), .s_arready(h_arready),
    .s_rid(h_rid), .s_rdata(h_rdata), .s_rresp(h_rresp), .s_rlast(h_rlast),
    .s_rvalid(h_rvalid), .s_rready(h_rready),
    .m_arid(m_axi_h_arid), .m_araddr(m_axi_h_araddr), .m_arlen(m_axi_h_arlen),
    .m_arsize(m_axi_h_arsize), .m_arburst(m_axi_h_arburst), .m_arvalid(m_axi_h_arvalid),
    .m_arready(m_axi_h_arready), .m_rid(m_axi_h_rid), .m_rdata(m_axi_h_rdata),
    .m_rresp(m_axi_h_rresp), .m_rlast(m_axi_h_rlast), .m_rvalid(m_axi_h_rvalid),
    .m_rready(m_axi_h_rready));
  axi_read_slice #(.ID_W(T_ID_W), .ADDR_W(TEX_ADDR_W), .DATA_W(AXI_DATA_W)) u_t_slice (
    .clk_i, .rst_ni(rst_nq),
    .s_arid(t_arid), .s_araddr(t_araddr), .s_arlen(t_arlen), .s_arsize(t_arsize),
    .s_arburst(t_arburst), .s_arvalid(t_arvalid), .s_arready(t_arready),
    .s_rid(t_rid), .s_rdata(t_rdata), .s_rresp(t_rresp), .s_rlast(t_rlast),
    .s_rvalid(t_rvalid), .s_rready(t_rready),
    .m_arid(m_axi_t_arid), .m_araddr(m_axi_t_araddr), .m_arlen(m_axi_t_arlen),
    .m_arsize(m_axi_t_arsize), .m_arburst(m_axi_t_arburst), .m_arvalid(m_axi_t_arvalid),
    .m_arready(m_axi_t_arready), .m_rid(m_axi_t_rid), .m_rdata(m_axi_t_rdata),
    .m_rresp(m_axi_t_rresp), .m_rlast(m_axi_t_rlast), .m_rvalid(m_axi_t_rvalid),
    .m_rready(m_axi_t_rready));

  dm_pipeline #(.PIX_W(PIX_W), .SLOTS(SLOTS), .N_RINGS(N_RINGS), .TRIS(TRIS), .H_ID_W(H_ID_W),
                .T_ID_W(T_ID_W), .AXI_DATA_W(AXI_DATA_W), .T_DIR_RAM(T_DIR_RAM)) u_pipe (
    .clk_i, .rst_ni(rst_nq),
    .cfg_method_i(cfg_method_q), .cfg_width_i(cfg_width_q), .cfg_height_i(cfg_height_q),
    .cfg_root_level_i(cfg_root_level_q), .cfg_bits16_i(cfg_bits16_q), .cfg_base_i(cfg_base_q),
    .cfg_root_code_i(cfg_root_code_q),
    .cfg_iter_cap_i(cfg_iter_cap_q),
    .cfg_depth_i(cfg_depth_q), .cfg_mip_en_i(cfg_mip_en_q),
    .cfg_levels_colour_i(cfg_levels_colour_q), .cfg_levels_normal_i(cfg_levels_normal_q),
    .cfg_shade_i(shade_cfg_t'(cfg_shade_q)), .cfg_miss_rgb_i(cfg_miss_rgb_q),
    .cfg_tex_su_i(cfg_tex_su_q), .cfg_tex_sv_i(cfg_tex_sv_q),
    .cfg_tex_base_i(cfg_tex_base_q),
    .lvt_we_i(lvt_we), .lvt_waddr_i(addr_q[LVT_ADDR_W-1:0]), .lvt_wdata_i(wdata_q),
    .tt_we_i(tt_we_q), .tt_waddr_i(tt_waddr_q), .tt_wdata_i(tt_wdata_q),
    .frag_valid_i(frag_valid_q), .frag_ready_o(frag_ready), .frag_id_i(frag_id_q),
    .frag_u0_i(frag_u0_q), .frag_v0_i(frag_v0_q), .frag_pl0_i(frag_pl0_q),
    .frag_tri_i(frag_tri_q), .frag_tbn_i(frag_tbn_q), .frag_view_i(frag_view_q),
    .px_valid_o(px_valid), .px_ready_i(px_ready), .px_id_o(px_id), .px_rgb_o(px_rgb),
    .px_hit_o(px_hit), .px_invalid_o(px_invalid), .px_err_o(px_err), .px_iters_o(px_iters),
    .m_axi_h_arid(h_arid), .m_axi_h_araddr(h_araddr), .m_axi_h_arlen(h_arlen),
    .m_axi_h_arsize(h_arsize), .m_axi_h_arburst(h_arburst), .m_axi_h_arvalid(h_arvalid),
    .m_axi_h_arready(h_arready), .m_axi_h_rid(h_rid), .m_axi_h_rdata(h_rdata),
    .m_axi_h_rresp(h_rresp), .m_axi_h_rlast(h_rlast), .m_axi_h_rvalid(h_rvalid),
    .m_axi_h_rready(h_rready),
    .m_axi_t_arid(t_arid), .m_axi_t_araddr(t_araddr), .m_axi_t_arlen(t_arlen),
    .m_axi_t_arsize(t_arsize), .m_axi_t_arburst(t_arburst), .m_axi_t_arvalid(t_arvalid),
    .m_axi_t_arready(t_arready), .m_axi_t_rid(t_rid), .m_axi_t_rdata(t_rdata),
    .m_axi_t_rresp(t_rresp), .m_axi_t_rlast(t_rlast), .m_axi_t_rvalid(t_rvalid),
    .m_axi_t_rready(t_rready),
    .clr_stats_i(clr_q),
    .stat_cycles_o(stat[0]), .stat_pixels_o(stat[1]), .stat_iters_o(stat[2]),
    .stat_h_hits_o(stat[3]), .stat_h_misses_o(stat[4]), .stat_h_bytes_o(stat[5]),
    .stat_t_requests_o(stat[6]), .stat_t_quad_hits_o(stat[7]),
    .stat_t_line_misses_o(stat[8]), .stat_t_bytes_o(stat[9]), .stat_t_texel_hits_o(stat[10]),
    .idle_o(idle));

  // ---- read mux (registered) ----------------------------------------------------------------------
  logic [31:0] rdata_q;
  logic [3:0]  st_i;
  assign st_i = addr_q[4:1];

  always_ff @(posedge clk_i) begin
    rdata_q <= '0;
    if (addr_q[7:6] == 2'b00 && addr_q[5]) begin
      if (st_i < 4'd11) rdata_q <= addr_q[0] ? {16'b0, stat[st_i][47:32]} : stat[st_i][31:0];
    end else begin
      case (addr_q)
        8'h00: rdata_q <= {29'b0, idle, frag_valid_q, px_valid};
        8'h01: rdata_q <= {px_err, px_invalid, px_hit, (29 - PIX_W)'(0), px_id};
        8'h02: rdata_q <= {8'b0, px_rgb};
        8'h03: rdata_q <= {16'b0, px_iters};
        default: ;
      endcase
    end
  end

  assign reg_rdata_o = rdata_q;
  assign px_valid_o  = px_valid;
  assign idle_o      = idle;

endmodule
