// SPDX-License-Identifier: Apache-2.0
// frag_dma: reads a frame's fragment records (pidm_pkg: FRAG_BYTES = 64 bytes each) from memory
// over an AXI4 read master and hands them to dm_pipeline's fragment port (valid / ready).
//
//   start_i: base_i (record aligned), count_i records -> AR bursts (INCR, full data width,
//   at most MAX_BURST records, never across a 4 KiB boundary) -> R beats -> beat FIFO
//   (FIFO_RECS records) -> assembly register (BEATS beats) -> output register -> frag_*_o
//
// A burst is requested only when the beat FIFO has room for every beat requested and not yet
// taken (inflight_q counts beats from the request until their R handshake, when they enter
// the FIFO), so R is always taken: rready is 1.  Records leave in
// memory order; the output register holds its payload while frag_valid_o && !frag_ready_i.
//
// Ending.  The frame ends (done_o high for its last clock, then busy_o falls) when
//   - every record was delivered (sent_o = count_i), or
//   - a read beat came back with RRESP != OKAY (err_o, held until the next start_i), or
//   - abort_i was raised during the frame (one clock suffices: it is remembered);
// in the last two cases no further burst is requested, the beats of the bursts already
// requested are taken and dropped (the AXI port is idle when busy_o falls), the records in
// the FIFO and the partly assembled one are dropped, and only a record already in the output
// register is still offered (until the pipeline takes it).  Every delivered record is one
// whose beats all came back OKAY; sent_o counts them.  count_i = 0 ends at once (done_o).
module frag_dma
  import f24_pkg::*;
  import pidm_pkg::*;
#(
  parameter int unsigned ADDR_W    = 32,      // AXI address width (>= 13)
  parameter int unsigned DATA_W    = 64,      // AXI data width: 32 .. 256, a power of two
  parameter int unsigned ID_W      = 4,       // AXI ID width
  parameter int unsigned ARID      = 0,       // the ID of every burst (one ID: in order)
  parameter int unsigned ARCACHE   = 3,       // ARCACHE 4'b0011: normal non-cacheable bufferable
  parameter int unsigned ARPROT    = 0,       // ARPROT 3'b000: unprivileged, secure, data
  parameter int unsigned MAX_BURST = 4,       // records per burst (power of two; <= 256 beats)
  parameter int unsigned FIFO_RECS = 8,       // beat FIFO, records (power of two, >= MAX_BURST)
  parameter int unsigned CNT_W     = 24,      // record count width
  parameter int unsigned PIX_W     = FRAG_ID_BITS, // pixel id bits passed on (<= FRAG_ID_BITS)
  parameter int unsigned TRI_W     = 4        // triangle id bits passed on (<= FRAG_TRI_BITS)
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  // control
  input  logic                 start_i,     // a frame: base_i, count_i (ignored while busy_o)
  input  logic                 abort_i,     // end the frame early (see above)
  input  logic [ADDR_W-1:0]    base_i,      // byte address, REC_BYTES aligned (low bits ignored)
  input  logic [CNT_W-1:0]     count_i,     // records
  output logic                 busy_o,
  output logic                 done_o,      // the frame's last clock (busy_o falls after it)
  output logic                 err_o,       // an RRESP != OKAY in this frame
  output logic [CNT_W-1:0]     sent_o,      // records delivered in this frame
  // fragments (dm_pipeline's frag_* inputs)
  output logic                 frag_valid_o,
  input  logic                 frag_ready_i,
  output logic [PIX_W-1:0]     frag_id_o,
  output f24_t                 frag_u0_o,
  output f24_t                 frag_v0_o,
  output f24_t                 frag_pl0_o,
  output logic [TRI_W-1:0]     frag_tri_o,
  output f24_t [8:0]           frag_tbn_o,
  output f24_t [2:0]           frag_view_o,
  // AXI4 read master
  output logic [ID_W-1:0]      m_axi_arid,
  output logic [ADDR_W-1:0]    m_axi_araddr,
  output logic [7:0]           m_axi_arlen,
  output logic [2:0]           m_axi_arsize,
  output logic [1:0]           m_axi_arburst,
  output logic                 m_axi_arlock,
  output logic [3:0]           m_axi_arcache,
  output logic [2:0]           m_axi_arprot,
  output logic [3:0]           m_axi_arqos,
  output logic                 m_axi_arvalid,
  input  logic                 m_axi_arready,
  input  logic [ID_W-1:0]      m_axi_rid,
  input  logic [DATA_W-1:0]    m_axi_rdata,
  input  logic [1:0]           m_axi_rresp,
  input  logic                 m_axi_rlast,
  input  logic                 m_axi_rvalid,
  output logic                 m_axi_rready
);

  localparam int unsigned REC_W      = 8 * FRAG_BYTES;
  localparam int unsigned REC_SHIFT  = $clog2(FRAG_BYTES);
  localparam int unsigned PAGE_SHIFT = 12;                     // AXI: no burst across 4 KiB
  localparam int unsigned BEATS     = REC_W / DATA_W;         // beats per record
  localparam int unsigned BEAT_W    = $clog2(BEATS) + 1;
  localparam int unsigned FIFO_BEATS = FIFO_RECS * BEATS;
  localparam int unsigned FB_W      = $clog2(FIFO_BEATS) + 1; // beat counts up to FIFO_BEATS
  localparam int unsigned PAGE_RECS = 1 << (PAGE_SHIFT - REC_SHIFT);
  localparam int unsigned BURST_W   = $clog2(MAX_BURST) + 1;

  if (DATA_W < 32 || DATA_W >= REC_W || (1 << $clog2(DATA_W)) != DATA_W) begin : g_check_data
    $error("frag_dma: DATA_W must be a power of two, 32 .. 256");
  end
  if ((1 << $clog2(MAX_BURST)) != MAX_BURST || MAX_BURST * BEATS > 256 ||
      MAX_BURST > PAGE_RECS) begin : g_check_burst
    $error("frag_dma: MAX_BURST must be a power of two of at most 256 beats and 4 KiB");
  end
  if (FIFO_RECS < MAX_BURST || (1 << $clog2(FIFO_RECS)) != FIFO_RECS) begin : g_check_fifo
    $error("frag_dma: FIFO_RECS must be a power of two >= MAX_BURST");
  end
  if (PIX_W > FRAG_ID_BITS || TRI_W > FRAG_TRI_BITS || ADDR_W < PAGE_SHIFT + 1) begin : g_check_fields
    $error("frag_dma: PIX_W, TRI_W or ADDR_W out of range");
  end

  // ---- frame state ------------------------------------------------------------------------
  logic                busy_q, stop_q, err_q;
  logic [ADDR_W-1:0]   addr_q;      // next record to request
  logic [CNT_W-1:0]    left_q;      // records not yet requested
  logic [CNT_W-1:0]    sent_q;
  logic [FB_W-1:0]     inflight_q;  // beats requested, not yet written into the FIFO
  logic                ar_valid_q;
  logic [ADDR_W-1:0]   ar_addr_q;
  logic [7:0]          ar_len_q;

  logic                drain;       // error or abort: drop what comes
  assign drain = stop_q || err_q;

  // beat FIFO
  logic              f_wr, f_rd, f_full, f_empty;
  logic [DATA_W-1:0] f_head;
  logic [FB_W-1:0]   f_count;

  traverse_fifo #(.W(DATA_W), .DEPTH(FIFO_BEATS)) u_fifo (
    .clk_i, .rst_ni, .wr_i(f_wr), .wr_data_i(m_axi_rdata), .rd_i(f_rd), .rd_data_o(f_head),
    .full_o(f_full), .empty_o(f_empty), .count_o(f_count));

  // ---- burst requests ----------------------------------------------------------------------
  // records to the 4 KiB boundary, and the burst: min(left, MAX_BURST, to the boundary)
  logic [PAGE_SHIFT-REC_SHIFT:0] to_page;
  logic [BURST_W-1:0]            burst;
  logic [FB_W:0]                 burst_beats;
  logic                          room, issue;
  assign to_page = (PAGE_SHIFT - REC_SHIFT + 1)'(PAGE_RECS)
                 - {1'b0, addr_q[PAGE_SHIFT-1:REC_SHIFT]};
  always_comb begin
    burst = BURST_W'(MAX_BURST);
    if (CNT_W'(burst) > left_q) burst = BURST_W'(left_q);
    if ((PAGE_SHIFT - REC_SHIFT + 1)'(burst) > to_page) burst = BURST_W'(to_page);
  end
  assign burst_beats = (FB_W + 1)'(burst) * (FB_W + 1)'(BEATS);
  assign room  = ({1'b0, inflight_q} + {1'b0, f_count} + burst_beats) <= (FB_W + 1)'(FIFO_BEATS);
  assign issue = busy_q && !drain && !ar_valid_q && left_q != '0 && room;

  logic r_take;
  assign r_take = m_axi_rvalid && m_axi_rready;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      ar_valid_q <= 1'b0;
      ar_addr_q  <= '0;
      ar_len_q   <= '0;
      addr_q     <= '0;
      left_q     <= '0;
      inflight_q <= '0;
    end else begin
      if (start_i && !busy_q) begin
        addr_q <= {base_i[ADDR_W-1:REC_SHIFT], REC_SHIFT'(0)};
        left_q <= count_i;
      end else if (issue) begin
        addr_q <= addr_q + (ADDR_W'(burst) << REC_SHIFT);
        left_q <= left_q - CNT_W'(burst);
      end
      if (issue) begin
        ar_valid_q <= 1'b1;
        ar_addr_q  <= addr_q;
        ar_len_q   <= 8'(burst_beats - 1'b1);
      end else if (m_axi_arready) begin
        ar_valid_q <= 1'b0;
      end
      inflight_q <= inflight_q + (issue ? FB_W'(burst_beats) : '0) - FB_W'(r_take);
    end
  end

  assign m_axi_arid    = ID_W'(ARID);
  assign m_axi_araddr  = ar_addr_q;
  assign m_axi_arlen   = ar_len_q;
  assign m_axi_arsize  = 3'($clog2(DATA_W / 8));
  assign m_axi_arburst = 2'b01;                 // INCR
  assign m_axi_arlock  = 1'b0;
  assign m_axi_arcache = 4'(ARCACHE);
  assign m_axi_arprot  = 3'(ARPROT);
  assign m_axi_arqos   = 4'd0;
  assign m_axi_arvalid = ar_valid_q;
  // Room for every requested beat was reserved: R is never held back.
  assign m_axi_rready  = 1'b1;

  logic r_err;
  assign r_err = r_take && m_axi_rresp != 2'b00;
  assign f_wr  = r_take && !drain && !r_err;

  // ---- assembly and output -----------------------------------------------------------------
  logic [BEATS-1:0][DATA_W-1:0] asm_q;
  logic [BEAT_W-1:0]            asm_cnt_q;    // beats in asm_q
  logic                         asm_full, move;
  logic [REC_W-1:0]             out_q;
  logic                         out_valid_q;
  logic [BEAT_W-1:0]            asm_idx;

  assign asm_full = asm_cnt_q == BEAT_W'(BEATS);
  assign move     = asm_full && !drain && (!out_valid_q || frag_ready_i);
  // a beat enters the assembly register while it is not full (or empties this clock); during
  // a drain the FIFO is emptied a beat a clock
  assign f_rd     = !f_empty && (drain || !asm_full || move);
  assign asm_idx  = move ? '0 : asm_cnt_q;

  always_ff @(posedge clk_i) begin
    if (f_rd && !drain) asm_q[asm_idx[BEAT_W-2:0]] <= f_head;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      asm_cnt_q   <= '0;
      out_valid_q <= 1'b0;
    end else begin
      if (drain)     asm_cnt_q <= '0;
      else           asm_cnt_q <= asm_idx + BEAT_W'(f_rd);
      if (move)                      out_valid_q <= 1'b1;
      else if (frag_ready_i)         out_valid_q <= 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (move) out_q <= asm_q;
  end

  logic [FRAG_WORDS-1:0][31:0] rec_w;     // the record's words
  assign rec_w = out_q;

  assign frag_valid_o = out_valid_q;
  assign frag_u0_o    = rec_w[FRAG_U0_WORD][F24_W-1:0];
  assign frag_v0_o    = rec_w[FRAG_V0_WORD][F24_W-1:0];
  assign frag_pl0_o   = rec_w[FRAG_PL0_WORD][F24_W-1:0];
  assign frag_tri_o   = rec_w[FRAG_TRI_WORD][FRAG_TRI_LSB +: TRI_W];
  assign frag_id_o    = rec_w[FRAG_ID_WORD][FRAG_ID_LSB +: PIX_W];
  for (genvar i = 0; i < 9; i++) begin : g_tbn
    assign frag_tbn_o[i] = rec_w[FRAG_TBN_WORD + i][F24_W-1:0];
  end
  for (genvar i = 0; i < 3; i++) begin : g_view
    assign frag_view_o[i] = rec_w[FRAG_VIEW_WORD + i][F24_W-1:0];
  end

  // ---- end of the frame --------------------------------------------------------------------
  logic fin;
  assign fin = busy_q && inflight_q == '0 && !ar_valid_q && !out_valid_q && f_empty
            && (drain || (left_q == '0 && asm_cnt_q == '0));

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      busy_q <= 1'b0;
      stop_q <= 1'b0;
      err_q  <= 1'b0;
      sent_q <= '0;
    end else begin
      if (start_i && !busy_q) begin
        busy_q <= 1'b1;
        stop_q <= 1'b0;
        err_q  <= 1'b0;
        sent_q <= '0;
      end else begin
        if (fin) busy_q <= 1'b0;
        if (busy_q && abort_i) stop_q <= 1'b1;
        if (r_err) err_q <= 1'b1;
        if (frag_valid_o && frag_ready_i) sent_q <= sent_q + 1'b1;
      end
    end
  end

  assign busy_o = busy_q;
  assign done_o = fin;
  assign err_o  = err_q;
  assign sent_o = sent_q;

  // unused: single ID, the beats are counted (not their RLAST), base_i's offset in a record
  logic unused;
  assign unused = ^{m_axi_rid, m_axi_rlast, f_full, base_i[REC_SHIFT-1:0]};

endmodule
