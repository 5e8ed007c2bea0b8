// SPDX-License-Identifier: Apache-2.0
// pix_dma: writes dm_pipeline's finished pixels into the framebuffer (RGBA8) and, when enabled,
// their status words into a status buffer, over an AXI4 write master (pidm_pkg: the layouts).
//
//   px_* -> pixel FIFO (IN_DEPTH) -> split register (pixel (x, y) from the id) -> job register
//   (offset y * pitch + x * 4) -> colour write at fb_base + offset, then (st_en) status write at
//   st_base + offset -> AW + W (single-beat INCR writes of 4 bytes, WSTRB on the word's lanes)
//   -> B (counted)
//
// Pixels arrive in completion order, each its own 4-byte write; a write is issued when AW and W
// are both free (or empty in this clock) and fewer than MAX_OUTST writes wait for their B
// response.  AW and W of a write are offered in the same clock and each held until its ready;
// BREADY is always 1.  px_ready_o is the pixel FIFO's room (a register).
//
// A frame: start_i takes the bases, the pitch, xbits_i and st_en_i and clears the counters and err_o.
// err_o: a B response other than OKAY in this frame (the writes go on).  While abort_i is high,
// pixels are taken and dropped (no new write; a write already offered completes).  idle_o: no
// pixel held, no write offered or outstanding (with the pipeline idle, the frame's writes are
// all done).  pixels_o counts the pixels taken this frame, written_o those whose writes all had
// their B response.
module pix_dma
  import pidm_pkg::*;
#(
  parameter int unsigned ADDR_W    = 32,    // AXI address width
  parameter int unsigned DATA_W    = 64,    // AXI data width: 32 .. 1024, a power of two
  parameter int unsigned ID_W      = 4,     // AXI ID width
  parameter int unsigned AWID      = 0,     // the ID of every write (one ID: in order)
  parameter int unsigned AWCACHE   = 3,     // AWCACHE 4'b0011: normal non-cacheable bufferable
  parameter int unsigned AWPROT    = 0,     // AWPROT 3'b000: unprivileged, secure, data
  parameter int unsigned MAX_OUTST = 8,     // writes awaiting B (>= 2)
  parameter int unsigned IN_DEPTH  = 4,     // pixel FIFO (power of two)
  parameter int unsigned PIX_W     = FRAG_ID_BITS, // pixel id width: {y, x}, x in the low xbits_i
  parameter int unsigned PITCH_W   = 16,    // framebuffer pitch width, bytes
  parameter int unsigned ITER_W    = 16,    // iteration count width (<= 16)
  parameter int unsigned CNT_W     = 24     // pixel counters
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // control
  input  logic                 start_i,
  input  logic                 abort_i,
  input  logic [ADDR_W-1:0]    fb_base_i,   // framebuffer base (4-byte aligned)
  input  logic [ADDR_W-1:0]    st_base_i,   // status buffer base (4-byte aligned)
  input  logic [PITCH_W-1:0]   pitch_i,     // bytes per row of both buffers (a multiple of 4)
  input  logic                 st_en_i,     // write status words
  input  logic [4:0]           xbits_i,     // x = id[xbits_i-1:0], y = id >> xbits_i (< PIX_W)
  output logic                 idle_o,
  output logic                 err_o,
  output logic [CNT_W-1:0]     pixels_o,
  output logic [CNT_W-1:0]     written_o,
  // pixels (dm_pipeline's px_* outputs)
  input  logic                 px_valid_i,
  output logic                 px_ready_o,
  input  logic [PIX_W-1:0]     px_id_i,
  input  logic [2:0][7:0]      px_rgb_i,    // [0] red, [1] green, [2] blue
  input  logic                 px_hit_i,
  input  logic                 px_invalid_i,
  input  logic                 px_err_i,
  input  logic [ITER_W-1:0]    px_iters_i,
  // AXI4 write master
  output logic [ID_W-1:0]      m_axi_awid,
  output logic [ADDR_W-1:0]    m_axi_awaddr,
  output logic [7:0]           m_axi_awlen,
  output logic [2:0]           m_axi_awsize,
  output logic [1:0]           m_axi_awburst,
  output logic                 m_axi_awlock,
  output logic [3:0]           m_axi_awcache,
  output logic [2:0]           m_axi_awprot,
  output logic [3:0]           m_axi_awqos,
  output logic                 m_axi_awvalid,
  input  logic                 m_axi_awready,
  output logic [DATA_W-1:0]    m_axi_wdata,
  output logic [DATA_W/8-1:0]  m_axi_wstrb,
  output logic                 m_axi_wlast,
  output logic                 m_axi_wvalid,
  input  logic                 m_axi_wready,
  input  logic [ID_W-1:0]      m_axi_bid,
  input  logic [1:0]           m_axi_bresp,
  input  logic                 m_axi_bvalid,
  output logic                 m_axi_bready
);

  localparam int unsigned LANES  = DATA_W / 32;           // 32-bit words per beat
  localparam int unsigned LANE_W = (LANES > 1) ? $clog2(LANES) : 1;
  localparam int unsigned OUT_W  = $clog2(MAX_OUTST + 1);
  localparam int unsigned PX_W   = PIX_W + 24 + 3 + ITER_W; // a pixel in the FIFO

  if (DATA_W < 32 || (1 << $clog2(DATA_W)) != DATA_W) begin : g_check_data
    $error("pix_dma: DATA_W must be a power of two >= 32");
  end
  if (MAX_OUTST < 2 || ITER_W > STW_ITERS_BITS || PIX_W > 31)
  begin : g_check_params
    $error("pix_dma: MAX_OUTST, ITER_W or PIX_W out of range");
  end

  // ---- frame registers ---------------------------------------------------------------------
  logic [ADDR_W-1:0]  fb_base_q, st_base_q;
  logic [PITCH_W-1:0] pitch_q;
  logic               st_en_q, err_q;
  logic [4:0]         xbits_q;
  logic [CNT_W-1:0]   pixels_q, written_q;

  // ---- pixel FIFO --------------------------------------------------------------------------
  logic            in_wr, in_rd, in_full, in_empty;
  logic [PX_W-1:0] in_head;
  logic [$clog2(IN_DEPTH):0] in_count;
  assign px_ready_o = !in_full;
  assign in_wr      = px_valid_i && !in_full;
  traverse_fifo #(.W(PX_W), .DEPTH(IN_DEPTH)) u_in (
    .clk_i, .rst_ni, .wr_i(in_wr),
    .wr_data_i({px_id_i, px_rgb_i, px_hit_i, px_invalid_i, px_err_i, px_iters_i}),
    .rd_i(in_rd), .rd_data_o(in_head), .full_o(in_full), .empty_o(in_empty),
    .count_o(in_count));

  localparam int unsigned REST_W = PX_W - PIX_W;   // a pixel's fields after its id
  logic [PIX_W-1:0]  h_id;
  logic [REST_W-1:0] h_rest;
  assign {h_id, h_rest} = in_head;

  // ---- split: the head pixel's (x, y) from its id, registered so that the FIFO's LUT-RAM
  // read and the shift by xbits are not in the clock of the offset's multiply --------------
  logic              sp_q, sp_take;        // a pixel held; it moves on to the job register
  logic [PIX_W-1:0]  sp_y_q, sp_x_q;
  logic [REST_W-1:0] sp_rest_q;

  logic [23:0]       p_rgb;
  logic              p_hit, p_inv, p_err;
  logic [ITER_W-1:0] p_iters;
  assign {p_rgb, p_hit, p_inv, p_err, p_iters} = sp_rest_q;

  // ---- job: the pixel whose writes are being issued ----------------------------------------
  logic              job_q, phase_q;       // a pixel held; 1: its status write is next
  logic [ADDR_W-1:0] off_q;
  logic [31:0]       rgba_q, stw_q;
  logic              issue, job_last, job_free;

  logic [ADDR_W-1:0] p_off;
  assign p_off = ADDR_W'((PIX_W + PITCH_W)'(sp_y_q) * (PIX_W + PITCH_W)'(pitch_q))
               + (ADDR_W'(sp_x_q) << 2);

  assign job_last = !st_en_q || phase_q;
  assign job_free = !job_q || (issue && job_last);
  assign sp_take  = sp_q && job_free;
  // a pixel leaves the FIFO into the split register, or is dropped during an abort
  assign in_rd    = !in_empty && (abort_i || !sp_q || sp_take);

  always_ff @(posedge clk_i) begin
    if (!rst_ni)                sp_q <= 1'b0;
    else if (abort_i)           sp_q <= 1'b0;     // dropped
    else if (in_rd)             sp_q <= 1'b1;
    else if (sp_take)           sp_q <= 1'b0;
  end
  always_ff @(posedge clk_i) begin
    if (in_rd && !abort_i) begin
      sp_y_q    <= h_id >> xbits_q;
      sp_x_q    <= h_id & ~({PIX_W{1'b1}} << xbits_q);
      sp_rest_q <= h_rest;
    end
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      job_q   <= 1'b0;
      phase_q <= 1'b0;
    end else begin
      if (sp_take && !abort_i) begin
        job_q   <= 1'b1;
        phase_q <= 1'b0;
      end else if (issue) begin
        if (job_last) job_q <= 1'b0;
        else          phase_q <= 1'b1;
      end else if (abort_i) begin        // a job not yet (fully) issued is dropped
        job_q   <= 1'b0;
        phase_q <= 1'b0;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (sp_take && !abort_i) begin
      off_q  <= p_off;
      rgba_q <= {8'(PIX_ALPHA), p_rgb};
      stw_q  <= '0;
      stw_q[STW_ITERS_LSB +: STW_ITERS_BITS] <= STW_ITERS_BITS'(p_iters);
      stw_q[STW_HIT_BIT]     <= p_hit;
      stw_q[STW_INVALID_BIT] <= p_inv;
      stw_q[STW_ERR_BIT]     <= p_err;
    end
  end

  // ---- AW / W ------------------------------------------------------------------------------
  logic              aw_q, w_q;
  logic [ADDR_W-1:0] aw_addr_q;
  logic [31:0]       w_word_q;
  logic [LANE_W-1:0] w_lane_q;
  logic [OUT_W-1:0]  outst_q;               // writes issued, B not yet back
  logic              b_take;
  logic [ADDR_W-1:0] wr_addr;

  assign b_take  = m_axi_bvalid && m_axi_bready;
  // A job's write is issued when both channels are free; abort_i holds back a job's writes
  // that were not yet issued (the job is dropped: see job_q above).
  assign issue   = job_q && !abort_i && (!aw_q || m_axi_awready) && (!w_q || m_axi_wready)
                && (outst_q < OUT_W'(MAX_OUTST));
  assign wr_addr = (phase_q ? st_base_q : fb_base_q) + off_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      aw_q    <= 1'b0;
      w_q     <= 1'b0;
      outst_q <= '0;
    end else begin
      if (issue)              aw_q <= 1'b1;
      else if (m_axi_awready) aw_q <= 1'b0;
      if (issue)              w_q  <= 1'b1;
      else if (m_axi_wready)  w_q  <= 1'b0;
      outst_q <= outst_q + OUT_W'(issue) - OUT_W'(b_take);
    end
  end

  always_ff @(posedge clk_i) begin
    if (issue) begin
      aw_addr_q <= {wr_addr[ADDR_W-1:2], 2'b00};
      w_word_q  <= phase_q ? stw_q : rgba_q;
      if (LANES > 1) w_lane_q <= wr_addr[2 +: LANE_W];
      else           w_lane_q <= '0;
    end
  end

  assign m_axi_awid    = ID_W'(AWID);
  assign m_axi_awaddr  = aw_addr_q;
  assign m_axi_awlen   = 8'd0;
  assign m_axi_awsize  = 3'd2;                   // 4 bytes
  assign m_axi_awburst = 2'b01;                  // INCR
  assign m_axi_awlock  = 1'b0;
  assign m_axi_awcache = 4'(AWCACHE);
  assign m_axi_awprot  = 3'(AWPROT);
  assign m_axi_awqos   = 4'd0;
  assign m_axi_awvalid = aw_q;
  assign m_axi_wvalid  = w_q;
  assign m_axi_wlast   = 1'b1;
  assign m_axi_bready  = 1'b1;
  always_comb begin
    m_axi_wdata = '0;
    m_axi_wstrb = '0;
    for (int unsigned l = 0; l < LANES; l++) begin
      if (LANE_W'(l) == w_lane_q) begin
        m_axi_wdata[32 * l +: 32] = w_word_q;
        m_axi_wstrb[4 * l +: 4]   = 4'hF;
      end
    end
  end

  // ---- counters, error, end ----------------------------------------------------------------
  // written_o: a pixel counts once the B response of its last write is back (one ID: B comes
  // in issue order); lastq_q remembers, per outstanding write, whether it ends its pixel.
  // Entry 0 is the oldest outstanding write: a B response shifts the flags down, an issued
  // write appends its flag behind the ones outstanding.
  logic [MAX_OUTST-1:0] lastq_q, lastq_d;
  always_comb begin
    lastq_d = lastq_q;
    if (b_take) lastq_d = lastq_d >> 1;
    for (int unsigned i = 0; i < MAX_OUTST; i++) begin
      if (issue && OUT_W'(i) == outst_q - OUT_W'(b_take)) lastq_d[i] = job_last;
    end
  end
  always_ff @(posedge clk_i) begin
    if (!rst_ni) lastq_q <= '0;
    else         lastq_q <= lastq_d;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      fb_base_q <= '0;
      st_base_q <= '0;
      pitch_q   <= '0;
      st_en_q   <= 1'b0;
      xbits_q   <= '0;
      err_q     <= 1'b0;
      pixels_q  <= '0;
      written_q <= '0;
    end else if (start_i) begin
      fb_base_q <= fb_base_i;
      st_base_q <= st_base_i;
      pitch_q   <= pitch_i;
      st_en_q   <= st_en_i;
      xbits_q   <= xbits_i;
      err_q     <= 1'b0;
      pixels_q  <= '0;
      written_q <= '0;
    end else begin
      if (in_wr) pixels_q <= pixels_q + 1'b1;
      if (b_take && lastq_q[0]) written_q <= written_q + 1'b1;
      if (b_take && m_axi_bresp != 2'b00) err_q <= 1'b1;
    end
  end

  assign idle_o    = in_empty && !sp_q && !job_q && !aw_q && !w_q && outst_q == '0;
  assign err_o     = err_q;
  assign pixels_o  = pixels_q;
  assign written_o = written_q;

  logic unused;
  assign unused = ^{m_axi_bid, in_count, wr_addr[1:0]};

endmodule
