// SPDX-License-Identifier: Apache-2.0
// pidm_top: the displacement-mapping core as a system IP: registers on AXI4-Lite, fragments in
// and pixels out over AXI4, the two memory read masters of the pipeline, an interrupt line.
//
//   s_axil (CPU) -> pidm_regs (generated from rtl/top/pidm_regs.rdl) -> pidm_cfg -> cfg_*;
//                   triangle table and level table writes (tt_*, lvt_*);
//                   frame descriptor, control, status, interrupts, statistics
//   m_axi_f (AR/R)  -> frag_dma -> dm_pipeline -> pix_dma -> m_axi_w (AW/W/B)
//                                  |  m_axi_h (AR/R): height pyramid
//                                  |  m_axi_t (AR/R): colour and normal textures
//   pyr_build (PYR_BUILD): reads level 0 over m_axi_h, writes levels 1..n over m_axi_w
//   irq_o = INTR_STATE & INTR_ENABLE (frame_done, axi_error, pyr_done)
//
// Memory formats (rtl/top/pidm_pkg.sv): the fragment record (64 bytes; pixel id {y, x}, x in
// FB_LAYOUT.xbits bits), the framebuffer pixel (RGBA8 at FB_BASE + y * FB_PITCH + 4 x) and the
// status word (STATUS_BASE + the same offset, when FB_LAYOUT.status_en).
//
// The frame (state_q):
//   IDLE --CTRL.start, configuration good--> RUN: frag_dma and pix_dma take the frame
//     descriptor; busy.  CTRL.start with a bad configuration (below) sets ERROR.bad_config and
//     INTR_STATE.axi_error and stays IDLE.
//   RUN: frag_dma streams the records into dm_pipeline, pix_dma writes its pixels.  The frame
//     ends when frag_dma is done, dm_pipeline holds no pixel and pix_dma is idle (every write's B
//     response back): IDLE, INTR_STATE.frame_done.  An AXI error (RRESP / BRESP other than OKAY
//     on any of the four masters) sets its ERROR flag and INTR_STATE.axi_error at once and
//     ends the frame early: frag_dma stops reading fragments (it drains its reads), the
//     fragments already in the pipeline finish and are written, then IDLE with frame_done.
//   CTRL.soft_reset in RUN -> STOP: frag_dma stops and drains, pix_dma drops the pixels that
//     still come (a write already offered completes), dm_pipeline finishes the fragments inside
//     (every AXI read it issued is answered: no port is left mid-transaction); then FLUSH.
//     CTRL.soft_reset in IDLE -> FLUSH.  FLUSH: dm_pipeline is reset for one clock (its caches
//     forget every line, its statistics return to 0, its slot free list refills, during which
//     it takes no fragment), then IDLE; no frame_done.  Configuration registers and ERROR keep
//     their values.  The caches are not otherwise invalidated: after changing the pyramid or
//     the textures in memory, software writes CTRL.soft_reset before the next frame.
// Every wait above is bounded (the masters' outstanding transactions, the pipeline's slots), so
// none can hang while the AXI slaves answer.
//
// The pyramid build (PYR registers, rtl/pyramid/pyr_build.sv, docs/pyramid.md):
//   IDLE --CTRL.pyr_start, PYR configuration in range--> BUILD: pyr_build owns the height read
//     port m_axi_h (its reads of level 0 and, for a dirty rebuild, of the levels) and the write
//     port m_axi_w (its writes of levels 1..n); STATUS.pyr_busy.  The ports' owner is state_q
//     (BUILD: the builder, any other state: dm_pipeline and pix_dma), so it changes only on
//     IDLE -> BUILD (the pipeline holds no pixel, so its height reads are all answered, and
//     pix_dma has every B response) and BUILD -> BFLUSH (pyr_build's done_o: its reader and
//     writer are idle, every read burst and every write answered): never with a transaction
//     of either side outstanding.  The builder's ID is 0 on both ports.
//   BUILD ends with pyr_build's done_o -> BFLUSH: dm_pipeline is reset for one clock as in
//     FLUSH, which invalidates the height cache (and the texture cache; the statistics return
//     to 0): no line of the old pyramid is served by the next frame.  Then IDLE with
//     INTR_STATE.pyr_done, STATUS.pyr_done, STATUS.pyr_err_code = the builder's err_code_o,
//     ERROR.pyr_read / pyr_write for its AXI errors and ERROR.pyr_config for a configuration it
//     refused (the three raise INTR_STATE.axi_error).  CTRL.soft_reset during a build is
//     ignored (pyr_build has no abort; the build ends within its bounded length and BFLUSH
//     resets the pipeline anyway).
//   Refused starts (ERROR.start_refused and INTR_STATE.axi_error, nothing else happens):
//     CTRL.start in BUILD or BFLUSH; CTRL.pyr_start outside IDLE or in the same write as
//     CTRL.start or CTRL.soft_reset.  CTRL.start during a frame stays ignored as before.
//   CTRL.pyr_start with a size, a rectangle corner or an offset index beyond PYR_MAX_LG, or
//     with PYR_BUILD = 0: ERROR.pyr_config and INTR_STATE.axi_error at once, no build.
//
// Bad configuration (checked at CTRL.start; ERROR.bad_config): FRAG_COUNT 0 or wider than
// CNT_W; FRAG_BASE not 64-byte aligned; FB_BASE, STATUS_BASE or FB_PITCH not 4-byte aligned;
// FB_PITCH of 2^PITCH_W bytes or more;
// FB_LAYOUT.xbits > PIX_W; HEIGHT.MODE.method not a method code (0 .. 9); a texture's MIP level
// count 0 or above TEX_LEVELS; a height map of width or height 0.  The buffer bases' bits above
// ADDR_W are ignored (the register map's 64-bit addresses serve every ADDR_W).
//
// Configuration registers feed dm_pipeline's cfg_* inputs directly: they must not change while
// STATUS.busy is 1 (the driver's obligation, as for dm_pipeline).  The level tables
// HEIGHT.LEVEL_OFF and TEX[x].LEVEL_OFF / LEVEL_SIZE are not stored in the register block
// (external registers): pidm_cfg turns each write into one write of dm_pipeline's lvt_* port
// (its LUT-RAM tables, not reset: the height pyramid's level offsets in each traverse ring, the
// texture entries in tex_addr), a clock after the bus write.  The pipeline's height and texture
// addresses are 32 bits (traverse_pkg::ADDR_W, pipe_pkg::TEX_ADDR_W): its masters reach the
// first 4 GiB of the ADDR_W space (upper address bits 0).
module pidm_top
  import f24_pkg::*;
  import traverse_pkg::ITER_W;
  import traverse_pkg::DIM_W;
  import traverse_pkg::LVL_W;
  import traverse_pkg::CODE_W;
  import pipe_pkg::TEX_LEVELS;
  import pipe_pkg::TEX_ADDR_W;
  import pipe_pkg::LVT_ADDR_W;
  import pipe_pkg::MIP_LEVEL_W;
  import shade_pkg::shade_cfg_t;
  import pidm_pkg::*;
#(
  parameter int unsigned ADDR_W     = 32,  // AXI address width of the four masters (>= 32)
  parameter int unsigned DATA_W     = 64,  // AXI data width of the four masters (64 .. 256)
  parameter int unsigned PIX_W      = 24,  // pixel id width (<= FRAG_ID_BITS)
  parameter int unsigned TRIS       = 16,  // triangle table entries
  parameter int unsigned F_ID_W     = 4,   // AXI ID widths: fragments, framebuffer writes,
  parameter int unsigned W_ID_W     = 4,
  parameter int unsigned H_ID_W     = 4,   //   heights,
  parameter int unsigned T_ID_W     = 6,   //   textures (> log2 of tex_cache MSHRS)
  parameter int unsigned ARCACHE    = 3,   // AxCACHE of every read / write: normal non-cacheable
  parameter int unsigned AWCACHE    = 3,   //   bufferable
  parameter int unsigned ARPROT     = 0,   // AxPROT: unprivileged, secure, data
  parameter int unsigned AWPROT     = 0,
  parameter int unsigned CNT_W      = 32,  // fragment / pixel counters of a frame
  parameter int unsigned PITCH_W    = 20,  // framebuffer pitch: < 2^PITCH_W bytes
  parameter int unsigned FRAG_BURST = 4,   // frag_dma: records per burst
  parameter int unsigned FRAG_FIFO  = 8,   // frag_dma: records buffered
  parameter int unsigned PIX_OUTST  = 8,   // pix_dma: writes outstanding
  parameter bit          PYR_BUILD  = 1'b1, // 1: the pyramid builder pyr_build is present
  parameter int unsigned PYR_MAX_LG = 10,  // pyr_build: largest map side 2^PYR_MAX_LG (<= 15)
  parameter int unsigned PYR_BURST  = 16,  // pyr_build: beats per burst at most
  parameter int unsigned TRI_W      = (TRIS > 1) ? $clog2(TRIS) : 1
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  output logic                 irq_o,
  // AXI4-Lite slave: the registers (4 KiB)
  input  logic                 s_axil_awvalid,
  output logic                 s_axil_awready,
  input  logic [11:0]          s_axil_awaddr,
  input  logic [2:0]           s_axil_awprot,
  input  logic                 s_axil_wvalid,
  output logic                 s_axil_wready,
  input  logic [31:0]          s_axil_wdata,
  input  logic [3:0]           s_axil_wstrb,
  output logic                 s_axil_bvalid,
  input  logic                 s_axil_bready,
  output logic [1:0]           s_axil_bresp,
  input  logic                 s_axil_arvalid,
  output logic                 s_axil_arready,
  input  logic [11:0]          s_axil_araddr,
  input  logic [2:0]           s_axil_arprot,
  output logic                 s_axil_rvalid,
  input  logic                 s_axil_rready,
  output logic [31:0]          s_axil_rdata,
  output logic [1:0]           s_axil_rresp,
  // AXI4 read master: fragment records
  output logic [F_ID_W-1:0]    m_axi_f_arid,
  output logic [ADDR_W-1:0]    m_axi_f_araddr,
  output logic [7:0]           m_axi_f_arlen,
  output logic [2:0]           m_axi_f_arsize,
  output logic [1:0]           m_axi_f_arburst,
  output logic                 m_axi_f_arlock,
  output logic [3:0]           m_axi_f_arcache,
  output logic [2:0]           m_axi_f_arprot,
  output logic [3:0]           m_axi_f_arqos,
  output logic                 m_axi_f_arvalid,
  input  logic                 m_axi_f_arready,
  input  logic [F_ID_W-1:0]    m_axi_f_rid,
  input  logic [DATA_W-1:0]    m_axi_f_rdata,
  input  logic [1:0]           m_axi_f_rresp,
  input  logic                 m_axi_f_rlast,
  input  logic                 m_axi_f_rvalid,
  output logic                 m_axi_f_rready,
  // AXI4 write master: framebuffer and status words
  output logic [W_ID_W-1:0]    m_axi_w_awid,
  output logic [ADDR_W-1:0]    m_axi_w_awaddr,
  output logic [7:0]           m_axi_w_awlen,
  output logic [2:0]           m_axi_w_awsize,
  output logic [1:0]           m_axi_w_awburst,
  output logic                 m_axi_w_awlock,
  output logic [3:0]           m_axi_w_awcache,
  output logic [2:0]           m_axi_w_awprot,
  output logic [3:0]           m_axi_w_awqos,
  output logic                 m_axi_w_awvalid,
  input  logic                 m_axi_w_awready,
  output logic [DATA_W-1:0]    m_axi_w_wdata,
  output logic [DATA_W/8-1:0]  m_axi_w_wstrb,
  output logic                 m_axi_w_wlast,
  output logic                 m_axi_w_wvalid,
  input  logic                 m_axi_w_wready,
  input  logic [W_ID_W-1:0]    m_axi_w_bid,
  input  logic [1:0]           m_axi_w_bresp,
  input  logic                 m_axi_w_bvalid,
  output logic                 m_axi_w_bready,
  // AXI4 read master: heights
  output logic [H_ID_W-1:0]    m_axi_h_arid,
  output logic [ADDR_W-1:0]    m_axi_h_araddr,
  output logic [7:0]           m_axi_h_arlen,
  output logic [2:0]           m_axi_h_arsize,
  output logic [1:0]           m_axi_h_arburst,
  output logic                 m_axi_h_arlock,
  output logic [3:0]           m_axi_h_arcache,
  output logic [2:0]           m_axi_h_arprot,
  output logic [3:0]           m_axi_h_arqos,
  output logic                 m_axi_h_arvalid,
  input  logic                 m_axi_h_arready,
  input  logic [H_ID_W-1:0]    m_axi_h_rid,
  input  logic [DATA_W-1:0]    m_axi_h_rdata,
  input  logic [1:0]           m_axi_h_rresp,
  input  logic                 m_axi_h_rlast,
  input  logic                 m_axi_h_rvalid,
  output logic                 m_axi_h_rready,
  // AXI4 read master: textures
  output logic [T_ID_W-1:0]    m_axi_t_arid,
  output logic [ADDR_W-1:0]    m_axi_t_araddr,
  output logic [7:0]           m_axi_t_arlen,
  output logic [2:0]           m_axi_t_arsize,
  output logic [1:0]           m_axi_t_arburst,
  output logic                 m_axi_t_arlock,
  output logic [3:0]           m_axi_t_arcache,
  output logic [2:0]           m_axi_t_arprot,
  output logic [3:0]           m_axi_t_arqos,
  output logic                 m_axi_t_arvalid,
  input  logic                 m_axi_t_arready,
  input  logic [T_ID_W-1:0]    m_axi_t_rid,
  input  logic [DATA_W-1:0]    m_axi_t_rdata,
  input  logic [1:0]           m_axi_t_rresp,
  input  logic                 m_axi_t_rlast,
  input  logic                 m_axi_t_rvalid,
  output logic                 m_axi_t_rready
);

  if (ADDR_W < 32 || ADDR_W > 64 || PIX_W > FRAG_ID_BITS || PITCH_W > 32 || CNT_W > 32
      || PYR_MAX_LG < 1 || PYR_MAX_LG > 15)
  begin : g_check_params
    $error("pidm_top: ADDR_W (32 .. 64), PIX_W, PITCH_W, CNT_W or PYR_MAX_LG out of range");
  end

  // ---- registers ---------------------------------------------------------------------------
  pidm_regs_pkg::pidm_regs__in_t  hw_in;
  pidm_regs_pkg::pidm_regs__out_t hw;

  pidm_regs u_regs (
    .clk(clk_i), .rst_n(rst_ni),
    .s_axil_awready, .s_axil_awvalid, .s_axil_awaddr, .s_axil_awprot,
    .s_axil_wready, .s_axil_wvalid, .s_axil_wdata, .s_axil_wstrb,
    .s_axil_bready, .s_axil_bvalid, .s_axil_bresp,
    .s_axil_arready, .s_axil_arvalid, .s_axil_araddr, .s_axil_arprot,
    .s_axil_rready, .s_axil_rvalid, .s_axil_rdata, .s_axil_rresp,
    .hwif_in(hw_in), .hwif_out(hw));

  // ---- the frame descriptor and its check ----------------------------------------------------
  logic [63:0] frag_base64, fb_base64, st_base64;
  assign frag_base64 = {hw.FRAME.FRAG_BASE.HI.val.value, hw.FRAME.FRAG_BASE.LO.val.value};
  assign fb_base64   = {hw.FRAME.FB_BASE.HI.val.value, hw.FRAME.FB_BASE.LO.val.value};
  assign st_base64   = {hw.FRAME.STATUS_BASE.HI.val.value, hw.FRAME.STATUS_BASE.LO.val.value};

  if (ADDR_W < 64) begin : g_addr_hi   // address bits above ADDR_W: ignored
    logic unused_hi;
    assign unused_hi = ^{frag_base64[63:ADDR_W], fb_base64[63:ADDR_W], st_base64[63:ADDR_W]};
  end

  logic [31:0] frag_count, fb_pitch;
  logic [4:0]  xbits;
  assign frag_count = hw.FRAME.FRAG_COUNT.val.value;
  assign fb_pitch   = hw.FRAME.FB_PITCH.val.value;
  assign xbits      = hw.FRAME.FB_LAYOUT.xbits.value;

  function automatic logic levels_bad(input logic [5:0] n);
    return n == 6'd0 || 32'(n) > TEX_LEVELS;
  endfunction

  logic bad_cfg;
  assign bad_cfg = frag_count == '0 || ((64'(frag_count) >> CNT_W) != 64'd0)
                || frag_base64[$clog2(FRAG_BYTES)-1:0] != '0
                || fb_base64[1:0] != 2'b00 || st_base64[1:0] != 2'b00 || fb_pitch[1:0] != 2'b00
                || ((64'(fb_pitch) >> PITCH_W) != 64'd0)
                || 32'(xbits) > PIX_W
                || hw.HEIGHT.MODE.method.value > 4'(traverse_pkg::M_PARK_XOR)
                || levels_bad(hw.SHADE.MIP.levels_colour.value)
                || levels_bad(hw.SHADE.MIP.levels_normal.value)
                || hw.HEIGHT.SIZE.width.value == '0 || hw.HEIGHT.SIZE.height.value == '0;

  // ---- frame state -------------------------------------------------------------------------
  typedef enum logic [2:0] {S_IDLE, S_RUN, S_STOP, S_FLUSH, S_BUILD, S_BFLUSH} state_e;
  state_e state_q;

  logic start_cmd, soft_rst, go, bad_start, frame_end, stop_end;
  logic pyr_cmd, pyr_go, pyr_bad_start, pyr_cfg_bad, refused, pyr_end, pyr_done_ev;
  logic b_done, b_busy;
  logic [3:0] b_code;
  logic own_b;   // the builder owns m_axi_h and m_axi_w
  logic frag_busy, frag_err, pix_idle, pix_err, dm_idle;
  logic err_seen_q, frag_err_q, pix_err_q;
  logic h_err_beat, t_err_beat, frag_err_new, pix_err_new, any_err;

  assign start_cmd = hw.CTRL.start.value;
  assign soft_rst  = hw.CTRL.soft_reset.value;
  assign go        = state_q == S_IDLE && start_cmd && !bad_cfg;
  assign bad_start = state_q == S_IDLE && start_cmd && bad_cfg;
  assign pyr_cmd   = hw.CTRL.pyr_start.value;
  assign pyr_go    = state_q == S_IDLE && pyr_cmd && !start_cmd && !soft_rst && !pyr_cfg_bad;
  assign pyr_bad_start = state_q == S_IDLE && pyr_cmd && !start_cmd && !soft_rst && pyr_cfg_bad;
  assign refused   = (start_cmd && (state_q == S_BUILD || state_q == S_BFLUSH))
                  || (pyr_cmd && (state_q != S_IDLE || start_cmd || soft_rst));
  assign pyr_end   = state_q == S_BUILD && b_done;
  assign pyr_done_ev = state_q == S_BFLUSH;
  assign own_b     = state_q == S_BUILD;

  logic drained;   // frag_dma done, no pixel in the pipeline, every write answered
  assign drained   = !frag_busy && dm_idle && pix_idle;
  assign frame_end = state_q == S_RUN && !soft_rst && drained;
  assign stop_end  = state_q == S_STOP && drained;

  // dm_pipeline's reset: the system reset, or FLUSH (a register: no reset from logic paths)
  logic pipe_rst_nq;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) pipe_rst_nq <= 1'b1;
    else         pipe_rst_nq <= !(state_q == S_IDLE && !go && soft_rst) && !stop_end && !pyr_end;
  end

  assign h_err_beat   = !own_b && m_axi_h_rvalid && m_axi_h_rready && m_axi_h_rresp != 2'b00;
  assign t_err_beat   = m_axi_t_rvalid && m_axi_t_rready && m_axi_t_rresp != 2'b00;
  assign frag_err_new = frag_err && !frag_err_q;
  assign pix_err_new  = pix_err && !pix_err_q;
  assign any_err      = h_err_beat || t_err_beat || frag_err_new || pix_err_new;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      state_q    <= S_IDLE;
      err_seen_q <= 1'b0;
      frag_err_q <= 1'b0;
      pix_err_q  <= 1'b0;
    end else begin
      frag_err_q <= frag_err;
      pix_err_q  <= pix_err;
      unique case (state_q)
        S_IDLE:  if (go) state_q <= S_RUN;
                 else if (soft_rst) state_q <= S_FLUSH;
                 else if (pyr_go) state_q <= S_BUILD;
        S_RUN:   if (soft_rst) state_q <= S_STOP;
                 else if (drained) state_q <= S_IDLE;
        S_STOP:  if (drained) state_q <= S_FLUSH;
        S_FLUSH: state_q <= S_IDLE;
        S_BUILD: if (b_done) state_q <= S_BFLUSH;
        S_BFLUSH: state_q <= S_IDLE;
        default: state_q <= S_IDLE;
      endcase
      if (go)           err_seen_q <= 1'b0;
      else if (any_err) err_seen_q <= 1'b1;
    end
  end

  // ---- fragments: frag_dma -> dm_pipeline ----------------------------------------------------
  logic             fr_valid, fr_ready;
  logic [PIX_W-1:0] fr_id;
  f24_t             fr_u0, fr_v0, fr_pl0;
  logic [TRI_W-1:0] fr_tri;
  f24_t [8:0]       fr_tbn;
  f24_t [2:0]       fr_view;
  logic [CNT_W-1:0] frag_sent;

  frag_dma #(
    .ADDR_W(ADDR_W), .DATA_W(DATA_W), .ID_W(F_ID_W), .ARCACHE(ARCACHE), .ARPROT(ARPROT),
    .MAX_BURST(FRAG_BURST), .FIFO_RECS(FRAG_FIFO), .CNT_W(CNT_W), .PIX_W(PIX_W), .TRI_W(TRI_W)
  ) u_frag (
    .clk_i, .rst_ni,
    .start_i(go), .abort_i(state_q == S_STOP || soft_rst || err_seen_q || any_err),
    .base_i(frag_base64[ADDR_W-1:0]), .count_i(CNT_W'(frag_count)),
    .busy_o(frag_busy), .done_o(), .err_o(frag_err), .sent_o(frag_sent),
    .frag_valid_o(fr_valid), .frag_ready_i(fr_ready), .frag_id_o(fr_id), .frag_u0_o(fr_u0),
    .frag_v0_o(fr_v0), .frag_pl0_o(fr_pl0), .frag_tri_o(fr_tri), .frag_tbn_o(fr_tbn),
    .frag_view_o(fr_view),
    .m_axi_arid(m_axi_f_arid), .m_axi_araddr(m_axi_f_araddr), .m_axi_arlen(m_axi_f_arlen),
    .m_axi_arsize(m_axi_f_arsize), .m_axi_arburst(m_axi_f_arburst),
    .m_axi_arlock(m_axi_f_arlock), .m_axi_arcache(m_axi_f_arcache),
    .m_axi_arprot(m_axi_f_arprot), .m_axi_arqos(m_axi_f_arqos),
    .m_axi_arvalid(m_axi_f_arvalid), .m_axi_arready(m_axi_f_arready),
    .m_axi_rid(m_axi_f_rid), .m_axi_rdata(m_axi_f_rdata), .m_axi_rresp(m_axi_f_rresp),
    .m_axi_rlast(m_axi_f_rlast), .m_axi_rvalid(m_axi_f_rvalid), .m_axi_rready(m_axi_f_rready));

  // ---- the pipeline ------------------------------------------------------------------------
  logic                px_valid, px_ready, px_hit, px_inv, px_err;
  logic [PIX_W-1:0]    px_id;
  logic [2:0][7:0]     px_rgb;
  logic [ITER_W-1:0]   px_iters;
  logic [47:0] st_cycles, st_pixels, st_iters, st_h_hits, st_h_misses, st_h_bytes,
               st_t_requests, st_t_quad_hits, st_t_line_misses, st_t_texel_hits, st_t_bytes;
  logic [31:0] h_araddr, t_araddr;
  // dm_pipeline's side of the height port (before the owner mux)
  logic [H_ID_W-1:0] p_h_arid;
  logic [7:0]        p_h_arlen;
  logic [2:0]        p_h_arsize;
  logic [1:0]        p_h_arburst;
  logic              p_h_arvalid, p_h_arready, p_h_rvalid, p_h_rready;

  // the configuration registers as dm_pipeline's cfg_* ports, triangle-table write port and
  // level table write port (HEIGHT.LEVEL_OFF, TEX[x].LEVEL_OFF / LEVEL_SIZE: external registers)
  logic [3:0]                        c_method;
  logic [DIM_W-1:0]                  c_width, c_height;
  logic [LVL_W-1:0]                  c_root_level;
  logic                              c_bits16, c_mip_en, tt_we;
  logic [31:0]                       c_base;
  logic [CODE_W-1:0]                 c_root_code;
  logic [ITER_W-1:0]                 c_iter_cap;
  f24_t                              c_depth, tt_wdata;
  logic [MIP_LEVEL_W:0]              c_levels_colour, c_levels_normal;
  shade_cfg_t                        c_shade;
  logic [2:0][7:0]                   c_miss_rgb;
  f24_t [1:0]                        c_tex_su, c_tex_sv;
  logic [1:0][TEX_ADDR_W-1:0]        c_tex_base;
  logic [TRI_W:0]                    tt_waddr;
  logic                              lvt_we;       // level table write
  logic [LVT_ADDR_W-1:0]             lvt_waddr;
  logic [31:0]                       lvt_wdata;
  // the external level-table registers' acknowledges (pidm_cfg)
  pidm_regs_pkg::pidm_regs__HEIGHT__in_t hw_in_height;
  pidm_regs_pkg::pidm_regs__TEXx__in_t   hw_in_tex [2];

  pidm_cfg #(.TRIS(TRIS), .TRI_W(TRI_W)) u_cfg (
    .clk_i, .rst_ni, .hwif_i(hw),
    .cfg_method_o(c_method), .cfg_width_o(c_width), .cfg_height_o(c_height),
    .cfg_root_level_o(c_root_level), .cfg_bits16_o(c_bits16), .cfg_base_o(c_base),
    .cfg_root_code_o(c_root_code), .cfg_iter_cap_o(c_iter_cap),
    .cfg_depth_o(c_depth), .cfg_mip_en_o(c_mip_en), .cfg_levels_colour_o(c_levels_colour),
    .cfg_levels_normal_o(c_levels_normal), .cfg_shade_o(c_shade), .cfg_miss_rgb_o(c_miss_rgb),
    .cfg_tex_su_o(c_tex_su), .cfg_tex_sv_o(c_tex_sv), .cfg_tex_base_o(c_tex_base),
    .tt_we_o(tt_we), .tt_waddr_o(tt_waddr), .tt_wdata_o(tt_wdata),
    .lvt_we_o(lvt_we), .lvt_waddr_o(lvt_waddr), .lvt_wdata_o(lvt_wdata),
    .hwif_height_o(hw_in_height), .hwif_tex_o(hw_in_tex));

  dm_pipeline #(
    .PIX_W(PIX_W), .TRIS(TRIS), .H_ID_W(H_ID_W), .T_ID_W(T_ID_W), .AXI_DATA_W(DATA_W)
  ) u_pipe (
    .clk_i, .rst_ni(rst_ni && pipe_rst_nq),
    .cfg_method_i(c_method), .cfg_width_i(c_width), .cfg_height_i(c_height),
    .cfg_root_level_i(c_root_level), .cfg_bits16_i(c_bits16), .cfg_base_i(c_base),
    .cfg_root_code_i(c_root_code), .cfg_iter_cap_i(c_iter_cap),
    .cfg_depth_i(c_depth), .cfg_mip_en_i(c_mip_en), .cfg_levels_colour_i(c_levels_colour),
    .cfg_levels_normal_i(c_levels_normal), .cfg_shade_i(c_shade), .cfg_miss_rgb_i(c_miss_rgb),
    .cfg_tex_su_i(c_tex_su), .cfg_tex_sv_i(c_tex_sv), .cfg_tex_base_i(c_tex_base),
    .tt_we_i(tt_we), .tt_waddr_i(tt_waddr), .tt_wdata_i(tt_wdata),
    .lvt_we_i(lvt_we), .lvt_waddr_i(lvt_waddr), .lvt_wdata_i(lvt_wdata),
    .frag_valid_i(fr_valid), .frag_ready_o(fr_ready), .frag_id_i(fr_id), .frag_u0_i(fr_u0),
    .frag_v0_i(fr_v0), .frag_pl0_i(fr_pl0), .frag_tri_i(fr_tri), .frag_tbn_i(fr_tbn),
    .frag_view_i(fr_view),
    .px_valid_o(px_valid), .px_ready_i(px_ready), .px_id_o(px_id), .px_rgb_o(px_rgb),
    .px_hit_o(px_hit), .px_invalid_o(px_inv), .px_err_o(px_err), .px_iters_o(px_iters),
    .m_axi_h_arid(p_h_arid), .m_axi_h_araddr(h_araddr), .m_axi_h_arlen(p_h_arlen),
    .m_axi_h_arsize(p_h_arsize), .m_axi_h_arburst(p_h_arburst), .m_axi_h_arvalid(p_h_arvalid),
    .m_axi_h_arready(p_h_arready), .m_axi_h_rid, .m_axi_h_rdata, .m_axi_h_rresp,
    .m_axi_h_rlast, .m_axi_h_rvalid(p_h_rvalid), .m_axi_h_rready(p_h_rready),
    .m_axi_t_arid, .m_axi_t_araddr(t_araddr), .m_axi_t_arlen, .m_axi_t_arsize,
    .m_axi_t_arburst, .m_axi_t_arvalid, .m_axi_t_arready, .m_axi_t_rid, .m_axi_t_rdata,
    .m_axi_t_rresp, .m_axi_t_rlast, .m_axi_t_rvalid, .m_axi_t_rready,
    .clr_stats_i(hw.CTRL.clear_stats.value),
    .stat_cycles_o(st_cycles), .stat_pixels_o(st_pixels), .stat_iters_o(st_iters),
    .stat_h_hits_o(st_h_hits), .stat_h_misses_o(st_h_misses), .stat_h_bytes_o(st_h_bytes),
    .stat_t_requests_o(st_t_requests), .stat_t_quad_hits_o(st_t_quad_hits),
    .stat_t_line_misses_o(st_t_line_misses), .stat_t_texel_hits_o(st_t_texel_hits),
    .stat_t_bytes_o(st_t_bytes), .idle_o(dm_idle));

  assign m_axi_t_araddr  = ADDR_W'(t_araddr);
  assign m_axi_h_arlock  = 1'b0;
  assign m_axi_h_arcache = 4'(ARCACHE);
  assign m_axi_h_arprot  = 3'(ARPROT);
  assign m_axi_h_arqos   = 4'd0;
  assign m_axi_t_arlock  = 1'b0;
  assign m_axi_t_arcache = 4'(ARCACHE);
  assign m_axi_t_arprot  = 3'(ARPROT);
  assign m_axi_t_arqos   = 4'd0;

  // ---- pixels: dm_pipeline -> pix_dma ------------------------------------------------------
  logic [CNT_W-1:0] pix_taken, pix_written;
  // pix_dma's side of the write port (before the owner mux)
  logic [W_ID_W-1:0]   p_w_awid;
  logic [ADDR_W-1:0]   p_w_awaddr;
  logic [7:0]          p_w_awlen;
  logic [2:0]          p_w_awsize;
  logic [1:0]          p_w_awburst;
  logic                p_w_awlock;
  logic [3:0]          p_w_awcache, p_w_awqos;
  logic [2:0]          p_w_awprot;
  logic                p_w_awvalid, p_w_awready, p_w_wlast, p_w_wvalid, p_w_wready;
  logic [DATA_W-1:0]   p_w_wdata;
  logic [DATA_W/8-1:0] p_w_wstrb;
  logic                p_w_bvalid, p_w_bready;

  pix_dma #(
    .ADDR_W(ADDR_W), .DATA_W(DATA_W), .ID_W(W_ID_W), .AWCACHE(AWCACHE), .AWPROT(AWPROT),
    .MAX_OUTST(PIX_OUTST), .PIX_W(PIX_W), .PITCH_W(PITCH_W), .ITER_W(ITER_W), .CNT_W(CNT_W)
  ) u_pix (
    .clk_i, .rst_ni,
    .start_i(go), .abort_i(state_q == S_STOP || soft_rst),
    .fb_base_i(fb_base64[ADDR_W-1:0]), .st_base_i(st_base64[ADDR_W-1:0]),
    .pitch_i(fb_pitch[PITCH_W-1:0]), .st_en_i(hw.FRAME.FB_LAYOUT.status_en.value),
    .xbits_i(xbits), .idle_o(pix_idle), .err_o(pix_err), .pixels_o(pix_taken),
    .written_o(pix_written),
    .px_valid_i(px_valid), .px_ready_o(px_ready), .px_id_i(px_id), .px_rgb_i(px_rgb),
    .px_hit_i(px_hit), .px_invalid_i(px_inv), .px_err_i(px_err), .px_iters_i(px_iters),
    .m_axi_awid(p_w_awid), .m_axi_awaddr(p_w_awaddr), .m_axi_awlen(p_w_awlen),
    .m_axi_awsize(p_w_awsize), .m_axi_awburst(p_w_awburst),
    .m_axi_awlock(p_w_awlock), .m_axi_awcache(p_w_awcache),
    .m_axi_awprot(p_w_awprot), .m_axi_awqos(p_w_awqos),
    .m_axi_awvalid(p_w_awvalid), .m_axi_awready(p_w_awready),
    .m_axi_wdata(p_w_wdata), .m_axi_wstrb(p_w_wstrb), .m_axi_wlast(p_w_wlast),
    .m_axi_wvalid(p_w_wvalid), .m_axi_wready(p_w_wready), .m_axi_bid(m_axi_w_bid),
    .m_axi_bresp(m_axi_w_bresp), .m_axi_bvalid(p_w_bvalid), .m_axi_bready(p_w_bready));

  // ---- the pyramid builder and the owner mux of m_axi_h and m_axi_w --------------------------
  // The PYR registers as pyr_build's configuration: sizes and rectangle corners must fit its
  // SZ_W / XY_W bits (else ERROR.pyr_config at CTRL.pyr_start, no build); the 64-bit bases'
  // bits above ADDR_W are ignored as the frame's are; LEVEL_OFF[0 .. PYR_MAX_LG] are used.
  localparam int unsigned PSZ_W = PYR_MAX_LG + 1;
  localparam int unsigned PXY_W = PYR_MAX_LG;
  logic [63:0] src_base64, pyr_base64;
  logic [15:0] pw16, ph16, px0, py0, px1, py1;
  logic [PYR_MAX_LG:0][ADDR_W-1:0] pyr_off;
  assign src_base64 = {hw.PYR.SRC_BASE.HI.val.value, hw.PYR.SRC_BASE.LO.val.value};
  assign pyr_base64 = {hw.PYR.PYR_BASE.HI.val.value, hw.PYR.PYR_BASE.LO.val.value};
  if (ADDR_W < 64) begin : g_pyr_addr_hi   // address bits above ADDR_W: ignored
    logic unused_pyr_hi;
    assign unused_pyr_hi = ^{src_base64[63:ADDR_W], pyr_base64[63:ADDR_W]};
  end
  assign pw16 = hw.PYR.SIZE.width.value;
  assign ph16 = hw.PYR.SIZE.height.value;
  assign px0  = hw.PYR.DIRTY0.x0.value;
  assign py0  = hw.PYR.DIRTY0.y0.value;
  assign px1  = hw.PYR.DIRTY1.x1.value;
  assign py1  = hw.PYR.DIRTY1.y1.value;
  for (genvar k = 0; k <= PYR_MAX_LG; k++) begin : g_pyr_off
    assign pyr_off[k] = ADDR_W'(hw.PYR.LEVEL_OFF[k].val.value);
  end
  assign pyr_cfg_bad = !PYR_BUILD
                    || ((32'(pw16) >> PSZ_W) != 0) || ((32'(ph16) >> PSZ_W) != 0)
                    || ((32'(px0) >> PXY_W) != 0) || ((32'(py0) >> PXY_W) != 0)
                    || ((32'(px1) >> PXY_W) != 0) || ((32'(py1) >> PXY_W) != 0);

  // the builder's side of the two ports
  logic              b_arid, b_awid;
  logic [ADDR_W-1:0] b_araddr, b_awaddr;
  logic [7:0]        b_arlen, b_awlen;
  logic [2:0]        b_arsize, b_awsize;
  logic [1:0]        b_arburst, b_awburst;
  logic              b_arvalid, b_rready, b_awvalid, b_wlast, b_wvalid, b_bready;
  logic [DATA_W-1:0]   b_wdata;
  logic [DATA_W/8-1:0] b_wstrb;

  if (PYR_BUILD) begin : g_pyr
    logic [3:0] b_arcache, b_awcache;   // = ARCACHE / AWCACHE (parameters of the instance)
    logic [2:0] b_arprot, b_awprot;     // = ARPROT / AWPROT
    logic       b_err;                  // = |b_code
    pyr_build #(
      .ADDR_W(ADDR_W), .AXI_DATA_W(DATA_W), .ID_W(1), .MAX_LG(PYR_MAX_LG), .BURST(PYR_BURST),
      .AXI_CACHE(4'(ARCACHE)), .AXI_PROT(3'(ARPROT))
    ) u_pyr (
      .clk_i, .rst_ni,
      .cfg_src_base_i(src_base64[ADDR_W-1:0]), .cfg_pyr_base_i(pyr_base64[ADDR_W-1:0]),
      .cfg_level_off_i(pyr_off), .cfg_width_i(PSZ_W'(pw16)), .cfg_height_i(PSZ_W'(ph16)),
      .cfg_bits16_i(hw.PYR.FORMAT.bits16.value),
      .dirty_x0_i(PXY_W'(px0)), .dirty_y0_i(PXY_W'(py0)),
      .dirty_x1_i(PXY_W'(px1)), .dirty_y1_i(PXY_W'(py1)),
      .start_i(pyr_go), .busy_o(b_busy), .done_o(b_done), .err_o(b_err), .err_code_o(b_code),
      .m_axi_arid(b_arid), .m_axi_araddr(b_araddr), .m_axi_arlen(b_arlen),
      .m_axi_arsize(b_arsize), .m_axi_arburst(b_arburst), .m_axi_arcache(b_arcache),
      .m_axi_arprot(b_arprot), .m_axi_arvalid(b_arvalid), .m_axi_arready(m_axi_h_arready && own_b),
      .m_axi_rid(m_axi_h_rid[0]), .m_axi_rdata(m_axi_h_rdata), .m_axi_rresp(m_axi_h_rresp),
      .m_axi_rlast(m_axi_h_rlast), .m_axi_rvalid(m_axi_h_rvalid && own_b), .m_axi_rready(b_rready),
      .m_axi_awid(b_awid), .m_axi_awaddr(b_awaddr), .m_axi_awlen(b_awlen),
      .m_axi_awsize(b_awsize), .m_axi_awburst(b_awburst), .m_axi_awcache(b_awcache),
      .m_axi_awprot(b_awprot), .m_axi_awvalid(b_awvalid), .m_axi_awready(m_axi_w_awready && own_b),
      .m_axi_wdata(b_wdata), .m_axi_wstrb(b_wstrb), .m_axi_wlast(b_wlast),
      .m_axi_wvalid(b_wvalid), .m_axi_wready(m_axi_w_wready && own_b),
      .m_axi_bid(m_axi_w_bid[0]), .m_axi_bresp(m_axi_w_bresp),
      .m_axi_bvalid(m_axi_w_bvalid && own_b), .m_axi_bready(b_bready));
    logic unused_pyr;
    assign unused_pyr = ^{b_arcache, b_awcache, b_arprot, b_awprot, b_err};
  end else begin : g_no_pyr
    assign b_busy = 1'b0;
    assign b_done = 1'b0;
    assign b_code = '0;
    assign {b_arid, b_araddr, b_arlen, b_arsize, b_arburst, b_arvalid, b_rready} = '0;
    assign {b_awid, b_awaddr, b_awlen, b_awsize, b_awburst, b_awvalid} = '0;
    assign {b_wdata, b_wstrb, b_wlast, b_wvalid, b_bready} = '0;
    logic unused_pyr_cfg;   // no builder: its configuration is not read
    assign unused_pyr_cfg = ^{src_base64[ADDR_W-1:0], pyr_base64[ADDR_W-1:0], pyr_off};
  end

  // the owner mux: own_b (state BUILD) selects the builder, else dm_pipeline / pix_dma; the
  // other side's valid and ready inputs are held at 0
  assign m_axi_h_arid    = own_b ? H_ID_W'(b_arid) : p_h_arid;
  assign m_axi_h_araddr  = own_b ? b_araddr : ADDR_W'(h_araddr);
  assign m_axi_h_arlen   = own_b ? b_arlen : p_h_arlen;
  assign m_axi_h_arsize  = own_b ? b_arsize : p_h_arsize;
  assign m_axi_h_arburst = own_b ? b_arburst : p_h_arburst;
  assign m_axi_h_arvalid = own_b ? b_arvalid : p_h_arvalid;
  assign m_axi_h_rready  = own_b ? b_rready : p_h_rready;
  assign p_h_arready     = m_axi_h_arready && !own_b;
  assign p_h_rvalid      = m_axi_h_rvalid && !own_b;

  assign m_axi_w_awid    = own_b ? W_ID_W'(b_awid) : p_w_awid;
  assign m_axi_w_awaddr  = own_b ? b_awaddr : p_w_awaddr;
  assign m_axi_w_awlen   = own_b ? b_awlen : p_w_awlen;
  assign m_axi_w_awsize  = own_b ? b_awsize : p_w_awsize;
  assign m_axi_w_awburst = own_b ? b_awburst : p_w_awburst;
  assign m_axi_w_awlock  = own_b ? 1'b0 : p_w_awlock;
  assign m_axi_w_awcache = own_b ? 4'(AWCACHE) : p_w_awcache;
  assign m_axi_w_awprot  = own_b ? 3'(AWPROT) : p_w_awprot;
  assign m_axi_w_awqos   = own_b ? 4'd0 : p_w_awqos;
  assign m_axi_w_awvalid = own_b ? b_awvalid : p_w_awvalid;
  assign m_axi_w_wdata   = own_b ? b_wdata : p_w_wdata;
  assign m_axi_w_wstrb   = own_b ? b_wstrb : p_w_wstrb;
  assign m_axi_w_wlast   = own_b ? b_wlast : p_w_wlast;
  assign m_axi_w_wvalid  = own_b ? b_wvalid : p_w_wvalid;
  assign m_axi_w_bready  = own_b ? b_bready : p_w_bready;
  assign p_w_awready     = m_axi_w_awready && !own_b;
  assign p_w_wready      = m_axi_w_wready && !own_b;
  assign p_w_bvalid      = m_axi_w_bvalid && !own_b;

  // the build's result, kept until the next CTRL.pyr_start
  logic       pyr_done_q;
  logic [3:0] pyr_code_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      pyr_done_q <= 1'b0;
      pyr_code_q <= '0;
    end else if (pyr_go) begin
      pyr_done_q <= 1'b0;
      pyr_code_q <= '0;
    end else if (pyr_end) begin
      pyr_done_q <= 1'b1;
      pyr_code_q <= b_code;
    end
  end

  // ---- status, errors, interrupts, statistics ----------------------------------------------
  always_comb begin
    hw_in.HWCFG.pix_w.next      = 8'(PIX_W);
    hw_in.HWCFG.tris.next       = 8'(TRIS);
    hw_in.HWCFG.addr_w.next     = 8'(ADDR_W);
    hw_in.HWCFG.data_bytes.next = 8'(DATA_W / 8);
    hw_in.STATUS.busy.next      = state_q == S_RUN || state_q == S_STOP || state_q == S_FLUSH;
    hw_in.STATUS.idle.next      = dm_idle;
    hw_in.STATUS.pyr_busy.next  = state_q == S_BUILD || state_q == S_BFLUSH;
    hw_in.STATUS.pyr_done.next  = pyr_done_q && state_q != S_BFLUSH;
    hw_in.STATUS.pyr_err_code.next = pyr_code_q;
    hw_in.PYR.INFO.present.next = PYR_BUILD;
    hw_in.PYR.INFO.max_lg.next  = 4'(PYR_MAX_LG);
    hw_in.ERROR.h_axi.hwset      = h_err_beat;
    hw_in.ERROR.t_axi.hwset      = t_err_beat;
    hw_in.ERROR.frag_dma.hwset   = frag_err_new;
    hw_in.ERROR.fb_write.hwset   = pix_err_new;
    hw_in.ERROR.bad_config.hwset = bad_start;
    hw_in.ERROR.pyr_read.hwset   = pyr_end && b_code[0];
    hw_in.ERROR.pyr_write.hwset  = pyr_end && b_code[1];
    hw_in.ERROR.pyr_config.hwset = (pyr_end && b_code[2]) || pyr_bad_start;
    hw_in.ERROR.start_refused.hwset = refused;
    hw_in.PROGRESS.pixels.next   = 32'(pix_written);
    hw_in.INTR_STATE.frame_done.next = frame_end || hw.INTR_TEST.frame_done.value;
    hw_in.INTR_STATE.axi_error.next  = any_err || bad_start || refused || pyr_bad_start
                                     || (pyr_end && b_code[2:0] != 3'b000)
                                     || hw.INTR_TEST.axi_error.value;
    hw_in.INTR_STATE.pyr_done.next   = pyr_done_ev || hw.INTR_TEST.pyr_done.value;
    hw_in.STATS.cycles.LO.val.next        = st_cycles[31:0];
    hw_in.STATS.cycles.HI.val.next        = st_cycles[47:32];
    hw_in.STATS.pixels.LO.val.next        = st_pixels[31:0];
    hw_in.STATS.pixels.HI.val.next        = st_pixels[47:32];
    hw_in.STATS.iters.LO.val.next         = st_iters[31:0];
    hw_in.STATS.iters.HI.val.next         = st_iters[47:32];
    hw_in.STATS.h_hits.LO.val.next        = st_h_hits[31:0];
    hw_in.STATS.h_hits.HI.val.next        = st_h_hits[47:32];
    hw_in.STATS.h_misses.LO.val.next      = st_h_misses[31:0];
    hw_in.STATS.h_misses.HI.val.next      = st_h_misses[47:32];
    hw_in.STATS.h_bytes.LO.val.next       = st_h_bytes[31:0];
    hw_in.STATS.h_bytes.HI.val.next       = st_h_bytes[47:32];
    hw_in.STATS.t_requests.LO.val.next    = st_t_requests[31:0];
    hw_in.STATS.t_requests.HI.val.next    = st_t_requests[47:32];
    hw_in.STATS.t_quad_hits.LO.val.next   = st_t_quad_hits[31:0];
    hw_in.STATS.t_quad_hits.HI.val.next   = st_t_quad_hits[47:32];
    hw_in.STATS.t_line_misses.LO.val.next = st_t_line_misses[31:0];
    hw_in.STATS.t_line_misses.HI.val.next = st_t_line_misses[47:32];
    hw_in.STATS.t_texel_hits.LO.val.next  = st_t_texel_hits[31:0];
    hw_in.STATS.t_texel_hits.HI.val.next  = st_t_texel_hits[47:32];
    hw_in.STATS.t_bytes.LO.val.next       = st_t_bytes[31:0];
    hw_in.STATS.t_bytes.HI.val.next       = st_t_bytes[47:32];
    hw_in.HEIGHT = hw_in_height;                               // pidm_cfg: level table acks
    for (int x = 0; x < 2; x++) hw_in.TEX[x] = hw_in_tex[x];
  end

  assign irq_o = hw.INTR_STATE.intr;

  // unused: the ERROR flags' values (software reads them), frag_dma's delivered count and
  // pix_dma's taken count (the bound checker reads them)
  logic unused;
  assign unused = ^{hw.ERROR.h_axi.value, hw.ERROR.t_axi.value, hw.ERROR.frag_dma.value,
                    hw.ERROR.fb_write.value, hw.ERROR.bad_config.value,
                    hw.ERROR.pyr_read.value, hw.ERROR.pyr_write.value,
                    hw.ERROR.pyr_config.value, hw.ERROR.start_refused.value,
                    frag_sent, pix_taken, b_busy, b_code[3]};

endmodule
