// SPDX-License-Identifier: Apache-2.0
// cache_axi_read: the AXI4 read machinery shared by the height cache and the texture cache: the
// queue of MSHR indices waiting for their AR, the AR channel, the reset epoch carried in the arid,
// the R channel's decode with each MSHR's beat count and error bit, and the sweep that clears a
// cache's valid (live) bits after a reset.  The MSHRs themselves (their state, line address and
// line buffer or data slot) stay in the cache.
//
// AR queue: MSHR indices in allocation order, MSHRS entries (it holds busy MSHRs only, so it never
//   overflows).  Up to NPUSH MSHRs join per clock: lane k with alloc_i[k] joins after the lanes
//   below it.  alloc_wr_i[k] writes lane k's index into the entry it would take (with alloc_i[k]
//   or without: the entry is free whenever the cache has a free MSHR, so an early write may
//   anticipate the allocation and only the pointer and the count wait for alloc_i).
// AR channel: one INCR burst per line (arlen = BEATS - 1, arsize = log2(DATA_W / 8)), arid =
//   {epoch, MSHR index}, araddr = {line address, zeros}; the line address of MSHR la_idx_o comes
//   back on la_i in the same clock.
//   AR_REG = 0: the port shows the queue's head (arvalid = rst_ni && queue not empty; la_idx_o is
//     the head; the head leaves at the handshake).
//   AR_REG = 1: two registers: the head moves into a register of the next read's MSHR index
//     (la_idx_o; arq_pop_o with the leaving index on arq_head_o), then into the port's register
//     (arid, araddr from la_i); each moves on while the one after it is empty or moves on itself,
//     so no RAM read or multiplexer drives the port.
// R channel: rready is 1.  A beat is the current epoch's (r_cur_o) when its rid carries the epoch;
//   r_ours_o adds that its MSHR index exists.  The cache accepts the beat (r_acc_i) when that
//   MSHR waits for its line; r_beat_o is the beat's index in the line, r_last_o marks the line's
//   last beat, r_bad_o an SLVERR / DECERR on this beat or an earlier one of the line.
// Reset (rst_ni low, synchronous): empties the queue and the AR registers (arvalid is 0 from the
//   first clock of reset), clears the beat counts and error bits, and starts the sweep: for the
//   SETS clocks after rst_ni rises, sweep_o is 1 and sweep_set_o walks the sets 0 .. SETS - 1.
//   The epoch (EPOCH_W = ID_W - log2(MSHRS) bits of the arid) is not reset: it advances at each
//   reset, so beats of reads issued before it are told apart (requirement: a read returns before
//   2^EPOCH_W - 1 further resets).
module cache_axi_read
  import cache_pkg::*;
#(
  parameter int unsigned ADDR_W     = 32,  // byte address width
  parameter int unsigned DATA_W     = 64,  // AXI data width (power of two, <= LINE_BYTES * 8)
  parameter int unsigned LINE_BYTES = 32,  // line size, bytes (power of two)
  parameter int unsigned MSHRS      = 4,   // line reads in flight
  parameter int unsigned ID_W       = 4,   // AXI ID width (> log2(MSHRS): the rest is the epoch)
  parameter int unsigned SETS       = 64,  // sets the reset sweep walks (power of two, >= 2)
  parameter int unsigned NPUSH      = 1,   // MSHRs allocated per clock at most
  parameter bit          AR_REG     = 1'b0,  // 0: AR from the queue's head, 1: two registers
  // derived (not to be overridden)
  parameter int unsigned OFF_W      = $clog2(LINE_BYTES),
  parameter int unsigned LA_W       = ADDR_W - OFF_W,                 // line address width
  parameter int unsigned BEATS      = LINE_BYTES * 8 / DATA_W,        // beats per line read
  parameter int unsigned BEAT_W     = (BEATS > 1) ? $clog2(BEATS) : 1,
  parameter int unsigned MIDX_W     = (MSHRS > 1) ? $clog2(MSHRS) : 1,  // MSHR index width
  parameter int unsigned QCNT_W     = $clog2(MSHRS + 1),
  parameter int unsigned SET_W      = $clog2(SETS)
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  // allocations, joining the AR queue
  input  logic [NPUSH-1:0]             alloc_i,      // lane k allocates MSHR alloc_idx_i[k]
  input  logic [NPUSH-1:0]             alloc_wr_i,   // write lane k's index (see above)
  input  logic [NPUSH-1:0][MIDX_W-1:0] alloc_idx_i,
  // the line address of an MSHR (for araddr)
  output logic [MIDX_W-1:0]            la_idx_o,
  input  logic [LA_W-1:0]              la_i,
  // the queue's head as it leaves (AR_REG = 1: into the first register)
  output logic                         arq_pop_o,
  output logic [MIDX_W-1:0]            arq_head_o,
  output logic [QCNT_W-1:0]            arq_cnt_o,    // reads queued (for the assertions)
  // R channel, decoded
  output logic [MIDX_W-1:0]            r_idx_o,      // the beat's MSHR
  output logic                         r_cur_o,      // rvalid, and the rid carries the epoch
  output logic                         r_ours_o,     // ... and names an MSHR
  input  logic                         r_acc_i,      // the cache accepts the beat
  output logic [BEAT_W-1:0]            r_beat_o,     // its index in the line
  output logic                         r_last_o,     // it is the line's last
  output logic                         r_bad_o,      // the line has an error (this beat or before)
  // reset sweep
  output logic                         sweep_o,
  output logic [SET_W-1:0]             sweep_set_o,
  // AXI4 read master (AR and R channels)
  output logic [ID_W-1:0]              m_axi_arid,
  output logic [ADDR_W-1:0]            m_axi_araddr,
  output logic [7:0]                   m_axi_arlen,
  output logic [2:0]                   m_axi_arsize,
  output logic [1:0]                   m_axi_arburst,
  output logic                         m_axi_arvalid,
  input  logic                         m_axi_arready,
  input  logic [ID_W-1:0]              m_axi_rid,
  input  logic [1:0]                   m_axi_rresp,
  input  logic                         m_axi_rlast,  // (implied by the beat count; checked)
  input  logic                         m_axi_rvalid,
  output logic                         m_axi_rready
);

  localparam int unsigned EPOCH_W    = ID_W - MIDX_W;
  localparam int unsigned BEAT_BYTES = DATA_W / 8;

  if (OFF_W != $clog2(LINE_BYTES) || LA_W != ADDR_W - OFF_W || BEATS != LINE_BYTES * 8 / DATA_W
      || BEATS < 1 || BEATS > 256 || BEAT_W != ((BEATS > 1) ? $clog2(BEATS) : 1)
      || MIDX_W != ((MSHRS > 1) ? $clog2(MSHRS) : 1) || QCNT_W != $clog2(MSHRS + 1)
      || SET_W != $clog2(SETS)) begin : g_check_derived
    $error("cache_axi_read: the derived parameters must keep their defaults");
  end
  if (MSHRS < 1 || ID_W <= MIDX_W || NPUSH < 1 || NPUSH > MSHRS) begin : g_check_mshrs
    $error("cache_axi_read: MSHRS >= NPUSH >= 1 and ID_W > log2(MSHRS) (epoch bits)");
  end
  if (SETS < 2 || (1 << SET_W) != SETS) begin : g_check_sets
    $error("cache_axi_read: SETS must be a power of two >= 2");
  end

  // ---------------------------------------------------------------- reset epoch
  // (deliberately not reset: it advances at each reset)
  logic [EPOCH_W-1:0] epoch_q;
  logic               in_rst_q;

  always_ff @(posedge clk_i) begin
    in_rst_q <= !rst_ni;
    if (!rst_ni && !in_rst_q) epoch_q <= epoch_q + EPOCH_W'(1);
  end

  // ---------------------------------------------------------------- AR queue
  logic [QCNT_W-1:0] arq_cnt;
  logic              ar_pop;   // the head leaves

  circ_queue #(.WIDTH(MIDX_W), .DEPTH(MSHRS), .NPUSH(NPUSH), .NPOP(1)) u_arq (
    .clk_i, .rst_ni, .push_i(alloc_i), .wr_i(alloc_wr_i), .wdata_i(alloc_idx_i),
    .pop_n_i(ar_pop), .rdata_o(arq_head_o), .peek_o(), .count_o(arq_cnt));

  assign arq_pop_o = ar_pop;
  assign arq_cnt_o = arq_cnt;

  // ---------------------------------------------------------------- AR channel
  if (AR_REG) begin : g_ar_reg
    logic              ap_go;
    logic              ap_v_q, ar_v_q;
    logic [MIDX_W-1:0] ap_idx_q;
    logic [ID_W-1:0]   ar_id_q;
    logic [ADDR_W-1:0] ar_addr_q;
    assign ap_go  = ap_v_q && (!ar_v_q || m_axi_arready);
    assign ar_pop = (arq_cnt != '0) && (!ap_v_q || ap_go);

    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        ap_v_q <= 1'b0;
        ar_v_q <= 1'b0;
      end else begin
        if (!ap_v_q || ap_go)         ap_v_q <= arq_cnt != '0;
        if (!ar_v_q || m_axi_arready) ar_v_q <= ap_v_q;
      end
      if (ar_pop) ap_idx_q <= arq_head_o;
      if (ap_go) begin
        ar_id_q   <= {epoch_q, ap_idx_q};
        ar_addr_q <= {la_i, {OFF_W{1'b0}}};
      end
    end

    assign la_idx_o      = ap_idx_q;
    assign m_axi_arvalid = rst_ni && ar_v_q;  // (0 in reset from its first clock)
    assign m_axi_arid    = ar_id_q;
    assign m_axi_araddr  = ar_addr_q;
  end else begin : g_ar_head
    assign ar_pop        = m_axi_arvalid && m_axi_arready;
    assign la_idx_o      = arq_head_o;
    assign m_axi_arvalid = rst_ni && (arq_cnt != '0);
    assign m_axi_arid    = {epoch_q, arq_head_o};
    assign m_axi_araddr  = {la_i, {OFF_W{1'b0}}};
  end

  assign m_axi_arlen   = 8'(BEATS - 1);
  assign m_axi_arsize  = 3'($clog2(BEAT_BYTES));
  assign m_axi_arburst = AXI_BURST_INCR;

  // ---------------------------------------------------------------- R channel
  logic [BEAT_W-1:0] beat_q [MSHRS];  // beats received
  logic              rerr_q [MSHRS];  // an earlier beat had an error
  logic [EPOCH_W-1:0] r_epoch;

  assign r_idx_o   = m_axi_rid[MIDX_W-1:0];
  assign r_epoch   = m_axi_rid[ID_W-1:MIDX_W];
  assign r_cur_o   = m_axi_rvalid && (r_epoch == epoch_q);
  assign r_ours_o  = r_cur_o && (32'(r_idx_o) < MSHRS);
  assign r_beat_o  = beat_q[r_idx_o];
  assign r_last_o  = (beat_q[r_idx_o] == BEAT_W'(BEATS - 1));
  assign r_bad_o   = m_axi_rresp[1] || rerr_q[r_idx_o];  // SLVERR / DECERR now or earlier

  assign m_axi_rready = 1'b1;

  // An MSHR's count and error bit are cleared by its line's last beat (and reset), so they are
  // clear when it is allocated again.
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int m = 0; m < MSHRS; m++) begin
        beat_q[m] <= '0;
        rerr_q[m] <= 1'b0;
      end
    end else if (r_acc_i) begin
      beat_q[r_idx_o] <= beat_q[r_idx_o] + BEAT_W'(1);
      rerr_q[r_idx_o] <= r_bad_o;
      if (r_last_o) begin
        beat_q[r_idx_o] <= '0;
        rerr_q[r_idx_o] <= 1'b0;
      end
    end
  end

  // ---------------------------------------------------------------- reset sweep
  logic             sweep_q;
  logic [SET_W-1:0] sweep_set_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      sweep_q     <= 1'b1;
      sweep_set_q <= '0;
    end else if (sweep_q) begin
      sweep_set_q <= sweep_set_q + SET_W'(1);
      if (sweep_set_q == SET_W'(SETS - 1)) sweep_q <= 1'b0;
    end
  end

  assign sweep_o     = sweep_q;
  assign sweep_set_o = sweep_set_q;

  // rresp[0] only tells EXOKAY from OKAY and DECERR from SLVERR; both errors are treated alike.
  // rlast is implied by the beat count (cache_axi_read_assert checks that it agrees).
  logic unused;
  assign unused = ^{m_axi_rresp[0], m_axi_rlast};

endmodule
