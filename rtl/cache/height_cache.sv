// SPDX-License-Identifier: Apache-2.0
// height_cache: the traverse unit's exclusive, non-blocking height cache (Park et al. 2013, sec. 4):
// a miss never stalls; the lookup answers "miss" and the ray retries on its next pass.
//
// Lookup port: one lookup per clock, fully pipelined, fixed latency cache_pkg::LOOKUP_LAT = 3: the
// answer to the lookup presented at clock c (lk_valid_i) is on rs_*_o at clock c + 3.
//   stage 0 (c):     read the tag RAM and the data RAM of every way at the set (synchronous
//                    read) and the set's valid bits; note whether a line fill writes that set in
//                    this clock.
//   stage 1 (c + 1): copy the RAMs' read registers into fabric registers (the texel's 16-bit word
//                    of each way, its tags and valid bits, and the set's replacement word for a
//                    fill, corrected for a fill of the set in this clock); note whether a fill
//                    writes the lookup's line in this clock.  (The block RAMs' 4.3 ns
//                    clock-to-out was in series with the compare: 81 MHz.)
//   stage 2 (c + 2): compare tags, select the texel, search the MSHRs; register the answer, and
//                    whether the lookup is a miss to allocate an MSHR for.
//   c + 3:           rs_valid_o, rs_hit_o, rs_err_o, rs_data_o; stage 3: the miss allocates an
//                    MSHR (it keeps the set's replacement word for its fill).  The allocation
//                    is a clock after the compare so that the tag compare drives registers only
//                    (in the routed top its path into the MSHRs' state was the slowest).
// rs_data_o on a hit: lk_wide_i = 0: {8'h00, byte at lk_addr_i}; lk_wide_i = 1: the little-endian
// 16-bit code at lk_addr_i (lk_addr_i[0] is ignored; the client keeps 16-bit texels aligned).
// rs_data_o is 0 when rs_hit_o is 0; rs_hit_o and rs_err_o are 0 when rs_valid_o is 0.
//
// Organisation: SETS sets x WAYS ways of LINE_BYTES-byte lines; set index = addr[OFF_W +: SET_W],
// tag = the bits above.  Per way two simple dual-port RAMs (cache_sdp_ram): the tags, and the
// lines, written a whole line at a time and read one 16-bit word (the one holding the texel) at a
// time; the valid bits are a RAM too (per set a word of WAYS valid bits and the set's
// round-robin pointer), read by the lookup's stage 0 like the tags.
// Replacement: an invalid way first (lowest index), else round robin per set (FIFO order: the
// way after the one last filled in the set), so only fills write the replacement state and it
// needs no port for hits.  (A tree pseudo-LRU touched by hits needs two writers a clock, a hit's
// and a fill's, and three reads: as flip-flops, 512 sets x 3 bits, it was about 5,700 of the
// pipeline's 91,000 LUT4s.)  Timing only, results unchanged: the miss that allocates an MSHR
// keeps its set's replacement word (valid bits and pointer, as its lookup read them) in the MSHR,
// and every fill of that set until the MSHR's own fill rewrites the copy, so the fill chooses
// its victim from registers, not from a RAM read in the clock before (see "fill").  The lookup
// path is plain data flow, nowhere wider than 64 bits: a lookup reads one 16-bit word per way,
// never a whole line.
//
// Misses (stage 2, rs_hit_o = 0):
//   - the line is already held by an MSHR (being read, or errored): merged, no new read;
//   - the line is being allocated (by the lookup in stage 3, whether or not that one finds a free
//     MSHR): no new read either;
//   - otherwise the miss is registered, and in stage 3, with a free MSHR (lowest index then), the
//     MSHR is allocated and its AR is queued (a FIFO of MSHRS entries, so it can never overflow;
//     an allocated miss is never dropped);
//   - with every MSHR busy in stage 3 the miss is not recorded: the client's retry tries again.
//   AR: one INCR burst per line (arlen = BEATS - 1, arsize = log2(DATA_W / 8)), line-aligned,
//   arid = {epoch, MSHR index} (see reset).  ARs leave in allocation order.
// Fill: rready is tied to 1 (each MSHR buffers its own line, so beats of different reads may
//   interleave in any order the interconnect likes).  The clock after a line's last beat, the line
//   is written into the cache and its MSHR is freed.  A lookup presented in that same clock to the
//   same set (whatever its line) answers a miss and allocates nothing: its RAM read overlaps the
//   write.  So does a lookup of the filled line itself presented in the clock before: it read
//   the set before the fill but reaches the MSHRs (stage 2) after the fill freed its MSHR (it
//   would read the line again).  Their retries see the filled set.  Every other lookup sees a
//   consistent set: one presented in the clock before a fill of another line of its set reads
//   the set as it was (a hit there returns the line's bytes even if the fill replaces it; the
//   memory behind the cache is read-only).
// AXI errors (rresp SLVERR / DECERR on any beat): the line is not written into the cache; its
//   MSHR turns to MSHR_ERR and keeps the line address.  The first lookup to that line that reaches
//   stage 2 answers rs_err_o = 1 (rs_hit_o = 0), and so does every lookup to that line in the next
//   ERR_HOLD clocks (so all the rays that were waiting for the line, retrying once per pass, learn
//   of the error); then the MSHR is freed and a later lookup to the line reads it again.  The MSHR
//   waits for its first erroring lookup however long that takes, so an error is never lost.
// Reset (rst_ni low, synchronous): clears the replacement state, MSHRs, the AR queue, the lookup
//   pipeline and the statistics, and starts the valid bits' sweep: for the SETS clocks after
//   rst_ni rises one set a clock is cleared, and a lookup presented in those clocks answers a
//   miss and allocates nothing (the ray retries; SETS = 512: 512 clocks); m_axi_arvalid is 0
//   while rst_ni is low.  Reads
//   issued before the reset may still return: rready stays 1 and their beats are ignored, because
//   the arid carries an EPOCH_W-bit epoch (EPOCH_W = ID_W - log2(MSHRS), 2 by default) that
//   advances at each reset.  Requirement: a read issued before a reset returns before 2^EPOCH_W - 1
//   further resets (power-on is fine: the epoch may start at any value).  The RAM contents are
//   not cleared (the valid bits are).
// Statistics (48-bit, cleared by reset and by clr_stats_i; a clock with clr_stats_i counts
//   nothing): stat_hits_o / stat_misses_o count answered lookups with rs_hit_o = 1 / 0 (a miss
//   includes errors and unrecorded misses; each counted a clock after stage 2 decides it,
//   through a register), stat_lines_o counts AR handshakes (line reads issued), stat_bytes_o
//   counts the bytes of accepted R beats (DATA_W / 8 each; stale beats after a reset
//   are not counted), so stat_bytes_o = stat_lines_o * LINE_BYTES once the reads have returned.
module height_cache
  import cache_pkg::*;
#(
  parameter int unsigned ADDR_W     = 32,  // byte address width
  parameter int unsigned DATA_W     = 64,  // AXI data width
  parameter int unsigned LINE_BYTES = 32,  // cache line size (power of two, a multiple of DATA_W/8)
  parameter int unsigned SETS       = 64,  // sets (power of two, >= 2)
  parameter int unsigned WAYS       = 2,   // associativity (power of two); round robin per set
  parameter int unsigned MSHRS      = 4,   // outstanding line reads (misses merged per line)
  parameter int unsigned ID_W       = 4,   // AXI ID width (> log2(MSHRS): the rest is the epoch)
  parameter int unsigned ERR_HOLD   = 64   // clocks an errored line keeps answering rs_err_o
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  // lookup port
  input  logic              lk_valid_i,
  input  logic [ADDR_W-1:0] lk_addr_i,
  input  logic              lk_wide_i,   // 1: 16-bit texel (unorm16, 2-byte aligned), 0: 8-bit
  output logic              rs_valid_o,  // lk_valid_i delayed by LOOKUP_LAT (3)
  output logic              rs_hit_o,
  output logic              rs_err_o,    // the line came back with an AXI error
  output logic [15:0]       rs_data_o,
  // AXI4 read master (AR and R channels)
  output logic [ID_W-1:0]   m_axi_arid,
  output logic [ADDR_W-1:0] m_axi_araddr,
  output logic [7:0]        m_axi_arlen,
  output logic [2:0]        m_axi_arsize,
  output logic [1:0]        m_axi_arburst,
  output logic              m_axi_arvalid,
  input  logic              m_axi_arready,
  input  logic [ID_W-1:0]   m_axi_rid,
  input  logic [DATA_W-1:0] m_axi_rdata,
  input  logic [1:0]        m_axi_rresp,
  input  logic              m_axi_rlast,
  input  logic              m_axi_rvalid,
  output logic              m_axi_rready,
  // statistics
  input  logic              clr_stats_i,
  output logic [47:0]       stat_hits_o,
  output logic [47:0]       stat_misses_o,
  output logic [47:0]       stat_bytes_o,   // AXI bytes read
  output logic [47:0]       stat_lines_o    // line reads issued
);

  localparam int unsigned OFF_W      = $clog2(LINE_BYTES);
  localparam int unsigned SET_W      = $clog2(SETS);
  localparam int unsigned TAG_W      = ADDR_W - OFF_W - SET_W;
  localparam int unsigned LA_W       = ADDR_W - OFF_W;           // line address width
  localparam int unsigned LINE_W     = LINE_BYTES * 8;
  localparam int unsigned BEATS      = LINE_W / DATA_W;          // beats per line read
  localparam int unsigned BEAT_W     = (BEATS > 1) ? $clog2(BEATS) : 1;
  localparam int unsigned BEAT_BYTES = DATA_W / 8;
  localparam int unsigned WAY_W      = (WAYS > 1) ? $clog2(WAYS) : 1;
  localparam int unsigned WAY_LVLS   = $clog2(WAYS);
  localparam int unsigned MIDX_W     = (MSHRS > 1) ? $clog2(MSHRS) : 1;
  localparam int unsigned QCNT_W     = $clog2(MSHRS + 1);
  localparam int unsigned ERRC_W     = $clog2(ERR_HOLD + 1);
  localparam int unsigned LANES      = LINE_BYTES / 2;           // 16-bit words per line
  localparam int unsigned LANE_W     = (LANES > 1) ? $clog2(LANES) : 1;

  if (LINE_BYTES < 2 || LINE_BYTES > 4096 || (1 << OFF_W) != LINE_BYTES) begin : g_check_line
    $error("height_cache: LINE_BYTES must be a power of two in 2..4096");
  end
  if (DATA_W < 8 || DATA_W > 1024 || (1 << $clog2(DATA_W)) != DATA_W || LINE_W < DATA_W
      || BEATS > 256) begin : g_check_data
    $error("height_cache: DATA_W must be a power of two in 8..LINE_BYTES*8 with <= 256 beats");
  end
  if (SETS < 2 || (1 << SET_W) != SETS || ADDR_W <= OFF_W + SET_W) begin : g_check_sets
    $error("height_cache: SETS must be a power of two >= 2 leaving at least one tag bit");
  end
  if (WAYS < 1 || (1 << WAY_LVLS) != WAYS) begin : g_check_ways
    $error("height_cache: WAYS must be a power of two");
  end
  if (MSHRS < 1 || ID_W <= MIDX_W) begin : g_check_mshrs
    $error("height_cache: MSHRS must be >= 1 and ID_W > log2(MSHRS) (epoch bits)");
  end
  if (ERR_HOLD < 1) begin : g_check_err_hold
    $error("height_cache: ERR_HOLD must be >= 1");
  end

  // ---------------------------------------------------------------- state
  // Cache directory (flops) and RAM read ports.
  // The valid bits and each set's round-robin pointer are RAM (u_valid), cleared by a sweep after
  // reset (see "valid bits").
  logic [TAG_W-1:0]  tag_rd  [WAYS];  // the tag of each way at the looked-up set
  logic [15:0]       word_rd [WAYS];  // the 16-bit word holding the texel, of each way

  // MSHRs.
  mshr_state_e                  mshr_state_q [MSHRS];
  logic [LA_W-1:0]              mshr_la_q    [MSHRS];  // line address
  logic [ERRC_W-1:0]            mshr_errc_q  [MSHRS];  // MSHR_ERR: 0 = no lookup erred yet
  logic [WAY_W+WAYS-1:0]        mshr_rw_q    [MSHRS];  // its set's {pointer, valid bits} now
  (* ram_style = "block" *)  // (a 16x4 LUT RAM costs 6 LUT4s; EBRs are plentiful here)
  logic [BEATS-1:0][DATA_W-1:0] mshr_buf_q   [MSHRS];  // the line being read

  // The AR queue, the reset epoch, the R channel's beat counts (u_axi).
  logic [QCNT_W-1:0] arq_cnt;     // reads queued (for the assertions)

  // Fill (the clock after a line's last good beat).
  logic              fill_q;
  logic [MIDX_W-1:0] fill_idx_q;
  logic [LA_W-1:0]   fill_la_q;   // its line address, registered with the last beat
  logic [MIDX_W-1:0] r_idx;       // the MSHR an R beat belongs to (R channel, below)

  // The valid bits' reset sweep (see "valid bits"; u_axi).
  logic              sweep;            // the sweep is running
  logic [SET_W-1:0]  sweep_set;        // the set it clears in this clock

  // Pipeline.
  logic              s1_valid_q, s1_wide_q, s1_conflict_q;
  logic [ADDR_W-1:0] s1_addr_q;
  logic [WAYS-1:0]   s1_vbits;     // the RAM's read register: the set's valid bits
  logic [WAY_W-1:0]  s1_ptr;       // ... and its round-robin pointer
  logic              s2_valid_q, s2_wide_q, s2_conflict_q;
  /* verilator lint_off UNUSEDSIGNAL */  // the word within the line was chosen in stage 0
  logic [ADDR_W-1:0] s2_addr_q;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [WAYS-1:0]   s2_vbits_q;
  logic [WAY_W+WAYS-1:0] s2_rw_q;  // the set's replacement word, with the fills up to stage 1
  logic [TAG_W-1:0]  s2_tag_q  [WAYS];  // stage 1's copies of the RAMs' reads
  logic [15:0]       s2_word_q [WAYS];
  logic              rs_valid_q, rs_hit_q, rs_err_q;
  logic [15:0]       rs_data_q;
  logic              s3_miss_q;    // stage 3: a miss to allocate an MSHR for
  logic [LA_W-1:0]   s3_la_q;      // ... its line address
  logic [WAY_W+WAYS-1:0] s3_rw_q;  // ... its set's replacement word, with the fills up to stage 2

  logic [47:0] st_hits_q, st_misses_q, st_bytes_q, st_lines_q;

  // ---------------------------------------------------------------- fill
  logic [LA_W-1:0]   fill_la;
  logic [SET_W-1:0]  fill_set;
  logic [TAG_W-1:0]  fill_tag;
  logic [WAY_W-1:0]  fill_way;
  logic [WAYS-1:0]   fill_vbits;
  logic [WAY_W-1:0]  fill_ptr;     // the set's round-robin pointer
  logic [WAY_W+WAYS-1:0] fill_rw;  // the word the fill writes: {pointer, valid bits} after it

  // The way after w in round-robin order.
  function automatic logic [WAY_W-1:0] rr_next(input logic [WAY_W-1:0] w);
    return WAY_W'((32'(w) + 1) % WAYS);
  endfunction

  // The fill clock starts from registers.  The line address is loaded in the clock of the last
  // beat (the MSHR's address cannot change from then until this fill frees it), and the set's
  // valid bits and round-robin pointer are the MSHR's copy (mshr_rw_q: the set's word as its
  // allocating lookup read it, rewritten by every fill of the set since), so the victim is chosen
  // from exactly the state the fills before it left, with no RAM output on the way to the RAMs'
  // write enables.
  assign fill_la    = fill_la_q;
  assign fill_set   = fill_la[SET_W-1:0];
  assign fill_tag   = fill_la[LA_W-1:SET_W];
  assign {fill_ptr, fill_vbits} = mshr_rw_q[fill_idx_q];
  always_comb begin
    fill_way = fill_ptr;
    for (int w = WAYS - 1; w >= 0; w--) begin
      if (!fill_vbits[w]) fill_way = WAY_W'(w);  // an invalid way first, the lowest
    end
  end
  assign fill_rw = {rr_next(fill_way), fill_vbits | (WAYS'(1) << fill_way)};

  // ---------------------------------------------------------------- stage 0: RAM read
  logic [SET_W-1:0] lk_set;
  assign lk_set = lk_addr_i[OFF_W +: SET_W];

  for (genvar w = 0; w < WAYS; w++) begin : g_way
    logic we;
    assign we = fill_q && (fill_way == WAY_W'(w));
    cache_sdp_ram #(.DEPTH(SETS), .WIDTH(TAG_W)) u_tags (
      .clk_i   (clk_i),
      .we_i    (we),
      .waddr_i (fill_set),
      .wdata_i (fill_tag),
      .re_i    (lk_valid_i),
      .raddr_i (lk_set),
      .rdata_o (tag_rd[w])
    );
    cache_sdp_ram #(.DEPTH(SETS), .WIDTH(LINE_W), .LANES(LANES)) u_lines (
      .clk_i   (clk_i),
      .we_i    (we),
      .waddr_i (fill_set),
      .wdata_i (mshr_buf_q[fill_idx_q]),
      .re_i    (lk_valid_i),
      .raddr_i (lk_set),
      .rlane_i (LANE_W'(lk_addr_i[OFF_W-1:0] >> 1)),  // the 16-bit word holding the texel
      .rdata_o (word_rd[w])
    );
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
    end else begin
      s1_valid_q <= lk_valid_i;
    end
    if (lk_valid_i) begin
      s1_addr_q     <= lk_addr_i;
      s1_wide_q     <= lk_wide_i;
      s1_conflict_q <= (fill_q && (fill_set == lk_set)) || sweep;
    end
  end

  // ---------------------------------------------------------------- stage 1: RAM reads copied
  // The RAMs' read registers into fabric registers beside the compare; a fill of the lookup's own
  // line in this clock makes it a conflict too (see "Fill").  The set's replacement word for a
  // fill (s2_rw_q) takes a fill of the set in this clock (its write is after the stage-0 read);
  // one in the stage-0 clock made the lookup a conflict (it allocates nothing).  The valid bits
  // of the compare (s2_vbits_q) stay as read, consistent with the tags.
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      s2_valid_q <= 1'b0;
    end else begin
      s2_valid_q <= s1_valid_q;
    end
    if (s1_valid_q) begin
      s2_addr_q     <= s1_addr_q;
      s2_wide_q     <= s1_wide_q;
      s2_conflict_q <= s1_conflict_q || (fill_q && (fill_la == s1_addr_q[ADDR_W-1:OFF_W]));
      s2_vbits_q    <= s1_vbits;
      s2_rw_q       <= (fill_q && fill_set == s1_addr_q[OFF_W +: SET_W]) ? fill_rw
                     : {s1_ptr, s1_vbits};
      for (int w = 0; w < WAYS; w++) begin
        s2_tag_q[w]  <= tag_rd[w];
        s2_word_q[w] <= word_rd[w];
      end
    end
  end

  // ---------------------------------------------------------------- stage 2: compare
  logic [TAG_W-1:0]  s2_tag;
  logic [LA_W-1:0]   s2_la;
  logic [WAYS-1:0]   way_hit;
  logic [15:0]       way_texel [WAYS];  // each way's texel (its word, or its byte of the word)
  logic              s2_hit, s2_err, s2_miss, s3_same, s3_alloc, free_any;
  logic [15:0]       s2_data;
  logic [MSHRS-1:0]  mshr_match, mshr_busy, mshr_err;
  logic [MIDX_W-1:0] alloc_idx;

  assign s2_tag = s2_addr_q[ADDR_W-1 -: TAG_W];
  assign s2_la  = s2_addr_q[ADDR_W-1:OFF_W];

  for (genvar w = 0; w < WAYS; w++) begin : g_hit
    assign way_hit[w] = s2_vbits_q[w] && (s2_tag_q[w] == s2_tag);
  end

  // 16-bit texel: the word; 8-bit texel: its byte of the word.  Each way's texel is picked
  // beside the tag compare, and the hit then selects among them (ORed over the ways that hit, at
  // most one), gated by the answer's own conditions: the compare is the last thing before
  // rs_data_q.
  for (genvar w = 0; w < WAYS; w++) begin : g_texel
    assign way_texel[w] = s2_wide_q ? s2_word_q[w]
                        : {8'h00, s2_addr_q[0] ? s2_word_q[w][15:8] : s2_word_q[w][7:0]};
  end

  always_comb begin
    s2_data = '0;  // rs_data_o: the texel on a hit, else 0
    for (int w = 0; w < WAYS; w++) begin
      s2_data = s2_data
              | ((s2_valid_q && !s2_conflict_q && way_hit[w]) ? way_texel[w] : 16'h0000);
    end
  end

  assign s2_hit  = s2_valid_q && !s2_conflict_q && (|way_hit);

  for (genvar i = 0; i < MSHRS; i++) begin : g_search
    assign mshr_busy[i]  = (mshr_state_q[i] != MSHR_FREE);
    assign mshr_match[i] = mshr_busy[i] && (mshr_la_q[i] == s2_la);
    assign mshr_err[i]   = mshr_match[i] && (mshr_state_q[i] == MSHR_ERR);
  end

  always_comb begin
    free_any  = 1'b0;
    alloc_idx = '0;
    for (int i = MSHRS - 1; i >= 0; i--) begin
      if (!mshr_busy[i]) begin
        free_any  = 1'b1;
        alloc_idx = MIDX_W'(i);  // the lowest free MSHR
      end
    end
  end

  // An errored line is never in the cache (hit_not_in_mshr: a hit matches no MSHR), so the error
  // needs no !s2_hit, and the tag compare is not on the way to rs_err_q.
  assign s2_err  = s2_valid_q && (|mshr_err);
  // A miss that no MSHR holds and that stage 3 is not allocating already; its MSHR is allocated
  // in stage 3 (the lowest free one then).
  assign s3_same = s3_miss_q && (s3_la_q == s2_la);
  assign s2_miss = s2_valid_q && !s2_conflict_q && !(|way_hit) && !(|mshr_match) && !s3_same;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      rs_valid_q <= 1'b0;
      rs_hit_q   <= 1'b0;
      rs_err_q   <= 1'b0;
      rs_data_q  <= '0;
    end else begin
      rs_valid_q <= s2_valid_q;
      rs_hit_q   <= s2_hit;
      rs_err_q   <= s2_err;
      rs_data_q  <= s2_data;
    end
  end

  assign rs_valid_o = rs_valid_q;
  assign rs_hit_o   = rs_hit_q;
  assign rs_err_o   = rs_err_q;
  assign rs_data_o  = rs_data_q;

  // ---------------------------------------------------------------- stage 3: allocation
  // The miss's set word takes a fill of the set in the stage-2 clock (as s2_rw_q takes one in
  // stage 1); the allocation below takes one in the stage-3 clock.
  always_ff @(posedge clk_i) begin
    s3_miss_q <= rst_ni && s2_miss;  // (cleared by the synchronous reset)
    if (s2_miss) begin
      s3_la_q <= s2_la;
      s3_rw_q <= (fill_q && fill_set == s2_la[SET_W-1:0]) ? fill_rw : s2_rw_q;
    end
  end

  assign s3_alloc = s3_miss_q && free_any;

  // ---------------------------------------------------------------- valid bits
  // Per set a word of WAYS valid bits and the set's round-robin pointer in one RAM (u_valid) with
  // a synchronous read, read by the lookup's stage 0 (like the tags).  A fill writes the whole
  // word of its set (fill_rw): fill_vbits (the set's bits as they are before this fill) with the
  // filled way set, and the pointer to the way after the filled one.  Reset starts a sweep: for
  // the SETS clocks after rst_ni rises, sweep is 1 and one set a clock is written to 0 (valid
  // bits and pointer); a lookup presented in those clocks answers a miss and allocates nothing
  // (like a lookup that meets a fill of its set), and with no MSHR allocated no fill can happen.
  // A read of the word written in the same clock is discarded (a lookup meeting a fill or the
  // sweep: a miss, no allocation), so the RAM may return the old or the new word.
  logic             vb_we;
  logic [SET_W-1:0] vb_waddr;
  logic [WAY_W+WAYS-1:0] vb_wdata;

  // (no fill during the sweep: every MSHR is free from the reset on until the sweep ends)
  assign vb_we    = rst_ni && (sweep || fill_q);
  assign vb_waddr = sweep ? sweep_set : fill_set;
  assign vb_wdata = sweep ? '0 : fill_rw;

  cache_sdp_ram #(.DEPTH(SETS), .WIDTH(WAY_W + WAYS)) u_valid (
    .clk_i, .we_i(vb_we), .waddr_i(vb_waddr), .wdata_i(vb_wdata),
    .re_i(lk_valid_i), .raddr_i(lk_set), .rlane_i('0), .rdata_o({s1_ptr, s1_vbits}));

  // ---------------------------------------------------------------- AXI read (AR queue, R channel)
  // The lowest free MSHR's index is written into the AR queue whenever an MSHR is free (then the
  // queue, holding busy MSHRs only, has room); only its pointer and count wait for the allocation.
  logic               r_ours, r_acc, r_last_beat, r_bad;
  logic [BEAT_W-1:0]  r_beat;
  logic [MIDX_W-1:0]  ar_idx;
  logic               la_we;  // (MSHRs, below)

  cache_axi_read #(
    .ADDR_W(ADDR_W), .DATA_W(DATA_W), .LINE_BYTES(LINE_BYTES), .MSHRS(MSHRS), .ID_W(ID_W),
    .SETS(SETS), .NPUSH(1), .AR_REG(1'b0)
  ) u_axi (
    .clk_i, .rst_ni,
    .alloc_i(s3_alloc), .alloc_wr_i(la_we), .alloc_idx_i(alloc_idx),
    .la_idx_o(ar_idx), .la_i(mshr_la_q[ar_idx]),
    .arq_pop_o(), .arq_head_o(), .arq_cnt_o(arq_cnt),
    .r_idx_o(r_idx), .r_cur_o(), .r_ours_o(r_ours), .r_acc_i(r_acc), .r_beat_o(r_beat),
    .r_last_o(r_last_beat), .r_bad_o(r_bad),
    .sweep_o(sweep), .sweep_set_o(sweep_set),
    .m_axi_arid, .m_axi_araddr, .m_axi_arlen, .m_axi_arsize, .m_axi_arburst, .m_axi_arvalid,
    .m_axi_arready, .m_axi_rid, .m_axi_rresp, .m_axi_rlast, .m_axi_rvalid, .m_axi_rready);

  assign r_acc = r_ours && (mshr_state_q[r_idx] == MSHR_WAIT);

  // ---------------------------------------------------------------- MSHRs
  // The allocation (stage 3, from registers) writes the lowest free MSHR's line address and set
  // word (and the AR queue its index).  (Its beat count and error bit, in u_axi, are clear since
  // its last line's last beat.)
  assign la_we = s3_alloc;

  logic ar_pop;  // an AR handshake
  assign ar_pop = m_axi_arvalid && m_axi_arready;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int i = 0; i < MSHRS; i++) begin
        mshr_state_q[i] <= MSHR_FREE;
        mshr_errc_q[i]  <= '0;
      end
      fill_q     <= 1'b0;
      fill_idx_q <= '0;
    end else begin
      for (int i = 0; i < MSHRS; i++) begin
        unique case (mshr_state_q[i])
          MSHR_WAIT: begin
            if (r_acc && r_idx == MIDX_W'(i) && r_last_beat) begin
              mshr_state_q[i] <= r_bad ? MSHR_ERR : MSHR_FILL;
              mshr_errc_q[i]  <= '0;
            end
          end
          MSHR_FILL: mshr_state_q[i] <= MSHR_FREE;  // written into the cache this clock
          MSHR_ERR: begin
            if (mshr_errc_q[i] != '0) begin
              mshr_errc_q[i] <= mshr_errc_q[i] - ERRC_W'(1);
              if (mshr_errc_q[i] == ERRC_W'(1)) mshr_state_q[i] <= MSHR_FREE;
            end else if (s2_valid_q && mshr_match[i]) begin
              mshr_errc_q[i] <= ERRC_W'(ERR_HOLD);  // the first lookup told of the error
            end
          end
          default: ;
        endcase
        if (s3_alloc && alloc_idx == MIDX_W'(i)) mshr_state_q[i] <= MSHR_WAIT;
      end
      fill_q     <= r_acc && r_last_beat && !r_bad;
      fill_idx_q <= r_idx;
    end
  end

  always_ff @(posedge clk_i) begin
    fill_la_q <= mshr_la_q[r_idx];
  end

  // Each MSHR's copy of its set's replacement word: loaded with the line address (from the
  // miss's stage-3 copy, or the word of a fill of the set in this clock), then rewritten by
  // every fill of the set (a free MSHR's copy is read by nothing).
  logic [SET_W-1:0] s3_set;
  assign s3_set = s3_la_q[SET_W-1:0];
  always_ff @(posedge clk_i) begin
    for (int i = 0; i < MSHRS; i++) begin
      if (la_we && alloc_idx == MIDX_W'(i)) begin
        mshr_rw_q[i] <= (fill_q && fill_set == s3_set) ? fill_rw : s3_rw_q;
      end else if (fill_q && mshr_la_q[i][SET_W-1:0] == fill_set) begin
        mshr_rw_q[i] <= fill_rw;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (la_we) mshr_la_q[alloc_idx] <= s3_la_q;
    if (r_acc) mshr_buf_q[r_idx][r_beat] <= m_axi_rdata;
  end

  // ---------------------------------------------------------------- statistics
  // The hit and the miss of stage 2 go through a register (st_hit_q, st_miss_q) into the
  // counters' enables, so the compare's logic does not drive the enable of 48 flip-flops that
  // placement may put far from the cache (a routed top's worst path, 13.3 ns); the counts of
  // lookups come a clock after the answer.  The count + 1 from the register, the event as its
  // enable: no event enters a 48-bit carry chain.
  logic st_hit_q, st_miss_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni || clr_stats_i) begin
      st_hit_q    <= 1'b0;
      st_miss_q   <= 1'b0;
      st_hits_q   <= '0;
      st_misses_q <= '0;
      st_bytes_q  <= '0;
      st_lines_q  <= '0;
    end else begin
      st_hit_q  <= s2_hit;
      st_miss_q <= s2_valid_q && !s2_hit;
      if (st_hit_q)  st_hits_q   <= st_hits_q + 48'd1;
      if (st_miss_q) st_misses_q <= st_misses_q + 48'd1;
      if (ar_pop)    st_lines_q  <= st_lines_q + 48'd1;
      if (r_acc)     st_bytes_q  <= st_bytes_q + 48'(BEAT_BYTES);
    end
  end

  assign stat_hits_o   = st_hits_q;
  assign stat_misses_o = st_misses_q;
  assign stat_bytes_o  = st_bytes_q;
  assign stat_lines_o  = st_lines_q;

endmodule
