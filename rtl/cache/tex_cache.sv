// tex_cache: the unified texture / normal-map cache of Park et al. 2013, Fig. 6.  It serves the
// bilinear filter one 2x2 texel quad per clock, in request order, and hides the memory latency by
// prefetching in the style of Igehy, Eldridge and Proudfoot ("Prefetching in a texture cache
// architecture", 1998): tags are checked when a request enters, misses go to memory at once, the
// request waits in an in-order FIFO, and its texels are read from the data RAMs at the FIFO head
// once its lines are there.
//
// ---- Streams -----------------------------------------------------------------------------------
// Request (valid / ready; req_valid_i must not depend on req_ready_o, and the payload must hold
// while req_valid_i && !req_ready_o): req_addr_i[t], t = 0 .. 3, the byte addresses of the texels
// c00 = T[i0, j0], c01 = T[i0, j1], c10 = T[i1, j0], c11 = T[i1, j1] (model.texture.sample's
// order), 4-byte aligned; req_tag_i is side-band returned with the response.  req_ready_o does not
// depend on req_valid_i (nor on req_addr_i): it looks at the request held in the entry register.
// Response (valid / ready, in request order, payload stable while rsp_valid_o && !rsp_ready_i):
// rsp_texel_o[t] the 32-bit word at req_addr_i[t] as stored in memory (little-endian: R in bits
// 7:0, A in bits 31:24), rsp_tag_o, rsp_err_o = 1 when a line of the quad came back from memory
// with SLVERR / DECERR (the texels are then undefined).  Nothing is lost, duplicated or reordered.
//
// ---- Organisation: four sub-caches, one lookup and one data read each per clock -----------------
// A line holds LINE_BYTES / 4 consecutive texels.  Texel t lies in line la = addr >> log2(LINE_BYTES)
// and goes to sub-cache {r, la[0]}: la[0] is the line-index parity and r a "row bit", bit j of the
// address of the texel's row's first texel (c00 for the top row, c10 for the bottom one), j chosen
// from the quad's row pitch R = req_addr_i[2] - req_addr_i[0] (4 W for a level W texels wide; 0
// when the rows are clamped, then r = 0): the address bit from the data window's size up that
// adding R flips most reliably (see "row bits" below; for R = 2^k it is bit k).
// The cache cannot know a texel's row parity from its address (that needs the level's width and
// base), so the row bit is read from the quad itself.  For a power-of-two width the bottom row
// starts R after the top row, which flips bit j: the top row's texels go to the sub-caches {r, *}
// and the bottom row's to {~r, *}, and within a row the two texels are in one line or in two of
// different parity, so the quad's lines fall into distinct sub-caches or are equal and windowed
// alike (below).  A line may be held in two sub-caches (rows of a small level share lines; rows
// clamped use r = 0): the cache is read-only, so that is harmless.
// Data windows: a sub-cache's RAM holds a line as NWIN = LINE_BYTES / 4 / WW windows of WW =
// min(WIN_WORDS, LINE_BYTES / 4) words, and a pass reads one window plus the word after it
// (an overlap word), so the texels of one line a pass may take from a sub-cache are those in
// the window of its first one there: a quad's horizontal pair always is, and a small level's two
// rows are either in one window or have different row bits (for R < 4 WW bytes, j is the window
// bit WB + 2).  So every quad of a power-of-two-wide level is one pass.
// Any other input is served too, only slower: the request is split into passes, each a greedy
// (texel order) subset of its texels whose lines are in distinct sub-caches, or the same line and
// in the window its first texel in that sub-cache reads; one pass per clock.  Real quads of widths
// that are not powers of two take two passes when a carry defeats the row bit
// (model.tex_cache.passes, 128-byte lines, over the MIP chains of textures 37 .. 1920 texels
// wide: 1.01 - 1.10 passes per quad with the default 2-word windows, 1.01 - 1.06 with 8-word
// ones; odd widths of a few texels are the worst).
// Each sub-cache: SETS sets x WAYS ways of lines; set = la[1 +: S] ^ la[1 + S +: S] (S = log2 SETS,
// an XOR fold, so that rows of power-of-two pitch spread over the sets), tag = la >> (1 + S).
// The live bits (allocated since the reset) are flops; the tags and the reference counts are in
// LUT RAM, one memory per sub-cache and way, the pseudo-LRU bits and the generation and error
// bits that give each slot's valid, pending and error state one memory per sub-cache, each
// written from one place (see "Directory" at the state); the lines are in block RAM
// (cache_sdp_ram), per sub-cache one RAM per DATA_W lane of a window and one for the overlap
// words, SETS * WAYS * NWIN deep (address {set, way, window}; see "Data RAMs").
//
// Why this organisation: a quad needs up to four line lookups and four data reads every clock.
// Four single-ported sub-caches do that only if the lines of a quad never share one, which needs
// a row parity the address alone does not carry; the row bit above supplies it from the quad.  The
// address-only alternative, two banks by line parity each with a duplicated (two-read-port) data
// RAM, is conflict-free for every width but needs twice the RAM for the same capacity; a fixed
// address hash over four banks cannot separate rows of every pitch (about a third of the quads
// would take a second clock).  Fills are written as the beats arrive (one per clock, the R
// channel's rate) rather than in order at the FIFO head as in Igehy et al., where a quad missing
// two lines of one bank would need two write clocks; reference counts then keep lines in use.
// The windows keep the texel select at (WW + 1) * 4 words per texel, not a line's words * 4, and
// let block RAM's depth hold the lines instead of its width.
//
// ---- Pipeline ------------------------------------------------------------------------------------
//   clock 0   request accepted into the entry register (row bits computed from req_addr_i).
//   clock 1   pass selection: the request's next pass (texels, one line and window per
//             sub-cache, set indices, tags) moves into the pass queue (four entries) while it
//             has room; a request of several passes stays in the entry register until its last
//             one has moved.
//   clock 2   lookup, read stage: the next pass in the queue reads the directory at its sets in
//             the four sub-caches (tags, reference counts, pseudo-LRU and state bits) and
//             compares each way's tag with its own.
//   clock 3   lookup, decide stage: hit or miss per sub-cache; a miss picks a victim way and an
//             MSHR.  All or nothing: the pass cannot go while the FIFO is full, while an MSHR is
//             missing for one of its misses, or while every way of a missed set is referenced;
//             then it and the pass behind it are read again (a replay, see "pass queue").  The
//             queue's room is judged from its pointers, so the lookup's outcome steers no enable
//             of the entry register or of the queue's entries in its own clock (only the
//             queue's pointers and the stage valid bits).
//   clock 4   commit: the pass's directory writes (tags, references, pseudo-LRU, valid and
//             pending bits), its MSHRs and line reads, and its push into the request FIFO
//             (FIFO_DEPTH passes) happen from the commit register, so no write waits on the
//             lookup's outcome in its own clock; the next passes' lookups see them forwarded.
//   clock 5   head: when the lines of the head pass are present (no pending fill), the pass
//             leaves the FIFO and reads the data RAMs (one window per sub-cache).
//   clock 6   the data RAMs' words are registered (their 4.3 ns clock-to-out on the ECP5).
//   clock 7   the texels are selected (and merged with earlier passes of the request).
//   clock 8   rsp_valid_o (a 4-entry output buffer).
// So a request that hits answers 8 clocks after its handshake; full throughput is one pass per
// clock.  A miss answers 5 clocks after its line's last beat.  Sizing: the FIFO lets requests
// run ahead of the head by FIFO_DEPTH passes, so it should exceed the memory latency plus a line's
// beats and the queueing of bursts of misses; MSHRS about FIFO_DEPTH / 4.  Measured on camera
// streams (tb/tex_cache, two 256x256 textures, 32-byte lines over 64 bits, one beat per clock):
// with the defaults 0.98 quads per clock at latency 20, 0.91 at 50, 0.62 at 100 (0.92 and 0.67
// with a one-clock lookup and unregistered AR and R channels; 0.97 at 100 with FIFO_DEPTH = 128,
// MSHRS = 32, measured then).
//
// ---- Lines in use are never evicted (reference counts) ------------------------------------------
// Every line slot has a reference count: +1 when a pass that reads it enters the FIFO, -1 when the
// pass reads it at the head.  A victim must have count 0 (invalid ways first, else tree
// pseudo-LRU among the unreferenced ways); the tag is replaced at once and the line is written
// when it arrives.  So a line that queued passes still need is never overwritten, later passes
// that look up a line in flight hit its tag and simply wait for the fill (misses merge per line
// through the tags), and a slot waiting for its fill is always referenced (by its allocator).
//
// ---- Memory (AXI4 read master, AR and R channels) -------------------------------------------------
// One INCR burst per line (arlen = LINE_BYTES * 8 / DATA_W - 1, arsize = log2(DATA_W / 8)),
// line-aligned (never crossing 4 KiB); arid = {epoch, MSHR index}; the ARs of one clock leave in
// sub-cache order, those of different clocks in allocation order (a queue of MSHR indices).
// rready is 1: each beat is written into its MSHR's slot the clock after it arrives (the slot is
// pending, so nothing reads it), so beats of different IDs may interleave.  On the line's last
// beat the MSHR is free again (MSHRS reads in flight at most), and the clock after, the slot
// stops pending.
// Errors: a line whose beats carry SLVERR / DECERR stays partly written; its slot gets the error
// bit and loses its valid bit: the passes already waiting for it answer rsp_err_o = 1 (nothing
// hangs), a later request reads the line again.
// Reset (rst_ni low, synchronous): empties the entry, pass and commit registers, the FIFO, the
// output, the MSHRs and the AR queue and the statistics; requests not yet answered are dropped;
// req_ready_o and m_axi_arvalid are 0.  Then a sweep clears the live bits, one set per clock
// (so no slot is valid, pending or in error): req_ready_o stays 0 for SETS more clocks.  The
// tags, reference counters, pseudo-LRU, generation and error bits (LUT RAM) keep whatever they
// hold, which the live bits make harmless (see "Directory" at the state): the cache behaves as
// if they had been cleared.
// Reads issued before the reset still return (rready stays 1) and are ignored: the arid's
// EPOCH_W = ID_W - log2(MSHRS) epoch bits advance at each reset.  Requirement: a read returns before
// 2^EPOCH_W - 1 further resets.
//
// ---- Statistics (48-bit; cleared by reset and by clr_stats_i, a clock with clr_stats_i counts
// nothing) -----------------------------------------------------------------------------------------
// (The lookup counters count in the commit clock, one clock after the lookup, and the request
// counter the clock after the handshake.)
//   stat_requests_o    requests accepted (req_valid_i && req_ready_o)
//   stat_quad_hits_o   requests whose every line lookup hit (a line in flight counts as a hit)
//   stat_lookups_o     line lookups (distinct lines per pass)
//   stat_line_misses_o line lookups that missed = line reads allocated
//   stat_texel_hits_o  texels (four per request) whose line lookup hit (a line in flight counts
//                      as a hit): texel_hits / (4 requests) is the per-texel hit rate
//   stat_bytes_o       bytes of accepted R beats (stale beats after a reset not counted)
module tex_cache
  import cache_pkg::*;
#(
  parameter int unsigned ADDR_W     = 32,  // byte address width
  parameter int unsigned DATA_W     = 64,  // AXI data width (power of two, 8 .. LINE_BYTES * 8)
  parameter int unsigned LINE_BYTES = 32,  // line size: power of two, 8 .. 4096 (>= 2 texels)
  parameter int unsigned SETS       = 32,  // sets per sub-cache (power of two, >= 2)
  parameter int unsigned WAYS       = 4,   // ways per set (power of two, >= 2); 4 x 32 x 4 x 32 B
                                           // = 16 KiB by default
  parameter int unsigned MSHRS      = 16,  // line reads in flight (>= 4: a pass may miss 4 lines)
  parameter int unsigned FIFO_DEPTH = 64,  // request FIFO (passes; power of two, >= 2): the
                                           // requests that can wait for memory at full rate
  parameter int unsigned ID_W       = 6,   // AXI ID width (> log2(MSHRS): the rest is the epoch)
  parameter int unsigned TAG_W      = 8,   // side-band width (req_tag_i -> rsp_tag_o)
  parameter int unsigned WIN_WORDS  = 2    // data-RAM window: words a sub-cache reads per pass,
                                           // plus one (power of two >= 2; capped at the line's
                                           // words); DATA_W <= 32 * that
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  // requests: one 2x2 quad
  input  logic                     req_valid_i,
  output logic                     req_ready_o,
  input  logic [3:0][ADDR_W-1:0]   req_addr_i,   // [0] c00, [1] c01, [2] c10, [3] c11
  input  logic [TAG_W-1:0]         req_tag_i,
  // responses, in request order
  output logic                     rsp_valid_o,
  input  logic                     rsp_ready_i,
  output logic [3:0][31:0]         rsp_texel_o,
  output logic                     rsp_err_o,
  output logic [TAG_W-1:0]         rsp_tag_o,
  // AXI4 read master (AR and R channels)
  output logic [ID_W-1:0]          m_axi_arid,
  output logic [ADDR_W-1:0]        m_axi_araddr,
  output logic [7:0]               m_axi_arlen,
  output logic [2:0]               m_axi_arsize,
  output logic [1:0]               m_axi_arburst,
  output logic                     m_axi_arvalid,
  input  logic                     m_axi_arready,
  input  logic [ID_W-1:0]          m_axi_rid,
  input  logic [DATA_W-1:0]        m_axi_rdata,
  input  logic [1:0]               m_axi_rresp,
  input  logic                     m_axi_rlast,
  input  logic                     m_axi_rvalid,
  output logic                     m_axi_rready,
  // statistics
  input  logic                     clr_stats_i,
  output logic [47:0]              stat_requests_o,
  output logic [47:0]              stat_quad_hits_o,
  output logic [47:0]              stat_lookups_o,
  output logic [47:0]              stat_line_misses_o,
  output logic [47:0]              stat_texel_hits_o,
  output logic [47:0]              stat_bytes_o
);

  localparam int unsigned NSUB       = 4;                        // sub-caches
  localparam int unsigned OFF_W      = $clog2(LINE_BYTES);
  localparam int unsigned LA_W       = ADDR_W - OFF_W;           // line address width
  localparam int unsigned LINE_W     = LINE_BYTES * 8;
  localparam int unsigned WSEL_W     = OFF_W - 2;                // texel within a line
  localparam int unsigned BEATS      = LINE_W / DATA_W;          // beats per line read
  localparam int unsigned BEAT_W     = (BEATS > 1) ? $clog2(BEATS) : 1;
  localparam int unsigned BEAT_BYTES = DATA_W / 8;
  localparam int unsigned SET_W      = $clog2(SETS);
  localparam int unsigned WAY_W      = $clog2(WAYS);
  localparam int unsigned PLRU_W     = WAYS - 1;
  localparam int unsigned TAGB       = LA_W - 1 - SET_W;         // stored tag bits
  localparam int unsigned MIDX_W     = (MSHRS > 1) ? $clog2(MSHRS) : 1;
  localparam int unsigned QCNT_W     = $clog2(MSHRS + 1);
  localparam int unsigned RC_W       = $clog2(FIFO_DEPTH + 1);   // a slot is read once per pass
  localparam int unsigned FP_W       = $clog2(FIFO_DEPTH);
  localparam int unsigned FC_W       = $clog2(FIFO_DEPTH + 1);
  localparam int unsigned OUT_DEPTH  = 4;                        // (a power of two)
  // data RAM windows (see "Data RAMs" below)
  localparam int unsigned LWORDS     = LINE_BYTES / 4;           // words per line
  localparam int unsigned WW         = (WIN_WORDS < LWORDS) ? WIN_WORDS : LWORDS;
  localparam int unsigned NWIN       = LWORDS / WW;              // windows per line
  localparam int unsigned WB         = $clog2(WW);               // log2 words per window
  localparam int unsigned WIN_W      = (NWIN > 1) ? $clog2(NWIN) : 1;
  localparam int unsigned TOFF_W     = WB + 1;                   // word in a read window, 0 .. WW
  localparam int unsigned NLANE      = WW * 32 / DATA_W;         // beats per window
  localparam int unsigned LANE_B     = (NLANE > 1) ? $clog2(NLANE) : 1;
  localparam int unsigned OVL_W      = (DATA_W < 32) ? DATA_W : 32;  // overlap-word lane width
  localparam int unsigned NOVL       = 32 / OVL_W;               // beats per overlap word
  localparam int unsigned RAM_DEPTH  = SETS * WAYS * NWIN;
  localparam int unsigned RAM_AW     = $clog2(RAM_DEPTH);

  if (LINE_BYTES < 8 || LINE_BYTES > 4096 || (1 << OFF_W) != LINE_BYTES) begin : g_check_line
    $error("tex_cache: LINE_BYTES must be a power of two in 8..4096");
  end
  if (DATA_W < 8 || (1 << $clog2(DATA_W)) != DATA_W || LINE_W < DATA_W || BEATS > 256)
  begin : g_check_data
    $error("tex_cache: DATA_W must be a power of two in 8..LINE_BYTES*8 with <= 256 beats");
  end
  if (SETS < 2 || (1 << SET_W) != SETS || TAGB < 1) begin : g_check_sets
    $error("tex_cache: SETS must be a power of two >= 2 leaving at least one tag bit");
  end
  if (WAYS < 2 || (1 << WAY_W) != WAYS) begin : g_check_ways
    $error("tex_cache: WAYS must be a power of two >= 2");
  end
  if (MSHRS < NSUB || ID_W <= MIDX_W) begin : g_check_mshrs
    $error("tex_cache: MSHRS must be >= 4 and ID_W > log2(MSHRS) (epoch bits)");
  end
  if (FIFO_DEPTH < 2 || (1 << FP_W) != FIFO_DEPTH) begin : g_check_fifo
    $error("tex_cache: FIFO_DEPTH must be a power of two >= 2");
  end
  if (TAG_W < 1) begin : g_check_tag
    $error("tex_cache: TAG_W must be >= 1");
  end
  if (WIN_WORDS < 2 || (1 << $clog2(WIN_WORDS)) != WIN_WORDS || DATA_W > 32 * WW)
  begin : g_check_win
    $error("tex_cache: WIN_WORDS must be a power of two >= 2, DATA_W <= 32 * its window");
  end

  // ---------------------------------------------------------------- helpers
  // XOR-folded set index of a line (bit 0, the parity, selects the sub-cache).
  function automatic logic [SET_W-1:0] set_of(input logic [LA_W-1:0] la);
    logic [SET_W-1:0] s;
    s = '0;
    for (int unsigned i = 0; i < SET_W; i++) begin
      if (1 + i < LA_W) s[i] = la[1 + i];
      if (1 + SET_W + i < LA_W) s[i] = s[i] ^ la[1 + SET_W + i];
    end
    return s;
  endfunction

  // Tree pseudo-LRU (node n = 1 .. WAYS-1 is bit n-1, children 2n, 2n+1; 0: the next victim is on
  // the left).  pick: follow the tree's direction unless that subtree has no candidate (mask m).
  function automatic logic [WAY_W-1:0] plru_pick(input logic [PLRU_W-1:0] b,
                                                 input logic [WAYS-1:0] m);
    int unsigned n, lo, span;
    logic l_has, r_has, go_r;
    n    = 1;
    lo   = 0;
    span = WAYS;
    for (int unsigned l = 0; l < WAY_W; l++) begin
      l_has = 1'b0;
      r_has = 1'b0;
      for (int unsigned w = 0; w < WAYS; w++) begin
        if (w >= lo && w < lo + span / 2 && m[w]) l_has = 1'b1;
        if (w >= lo + span / 2 && w < lo + span && m[w]) r_has = 1'b1;
      end
      go_r = b[n-1] ? r_has : !l_has;
      n    = 2 * n + (go_r ? 1 : 0);
      if (go_r) lo = lo + span / 2;
      span = span / 2;
    end
    return WAY_W'(lo);
  endfunction

  // Mark way w most recently used: every node on its path points away from it.
  function automatic logic [PLRU_W-1:0] plru_touch(input logic [PLRU_W-1:0] b,
                                                   input logic [WAY_W-1:0] w);
    int unsigned n;
    logic [PLRU_W-1:0] r;
    r = b;
    n = int'(w) + WAYS;
    for (int unsigned l = 0; l < WAY_W; l++) begin
      r[(n >> 1) - 1] = (n % 2 == 0);
      n = n >> 1;
    end
    return r;
  endfunction

  // A set's word with way w's bit replaced by b (the state words of g_dir, a bit per way).
  function automatic logic [WAYS-1:0] with_way(input logic [WAYS-1:0] word,
                                                input logic [WAY_W-1:0] w, input logic b);
    logic [WAYS-1:0] r;
    r    = word;
    r[w] = b;
    return r;
  endfunction

  // ---------------------------------------------------------------- state
  // Directory, in LUT RAM (g_dir below), each memory written from one place:
  //  - the live bits (per sub-cache, a word per set with a bit per way): a slot has been
  //    allocated since the reset.  Written by the commit (an allocation sets its slot's bit) and
  //    cleared after a reset by a sweep, one set per clock (SETS clocks, while req_ready_o is 0);
  // the rest is not reset:
  //  - the slot's state as two generation bits and an error bit (per sub-cache, a word per set
  //    with a bit per way): ag, written by the commit (an allocation sets it to the inverse of
  //    fg), and {fg, bad}, written by the fill (fg = ag, bad = the line came back with an error).
  //    The slot is pending (allocated, line not yet written) when ag != fg, has the error bit
  //    (err) when it is live, not pending and bad, and is valid when it is live and has not the
  //    error bit (so valid while pending, as the lookup merges a miss with a line in flight): a
  //    live slot is valid or has the error bit, never both.  An allocation takes a slot that is not
  //    pending (it is unreferenced), and a fill comes only for a pending one (stale beats from
  //    before a reset are dropped), so ag and fg never differ by more than the one allocation;
  //  - the tags (per sub-cache and way), which count only with the valid bit;
  //  - the reference count rc = inc - dec (modulo 2^RC_W) of a slot: the passes in the FIFO that
  //    read it.  inc counts at the commit (per sub-cache and way), dec at the head (likewise).  An
  //    allocation writes inc = dec + 1 (its own reference), so the pair is exact from the slot's
  //    first allocation since the reset on; a slot that is not live is unreferenced (free) whatever
  //    the two hold;
  //  - the pseudo-LRU bits of a set (per sub-cache).  The lookup uses them only when every way of
  //    the set is live (a way that is not live is free and invalid, so it is taken first), so each
  //    way has been allocated, and touched, since the reset; a touch writes every node on the
  //    way's path, so every node of the tree has been written since the reset.
  // (The state bits were flops written by both the commit and the fill, 3 x NSUB x SETS x WAYS
  // of them read through wide multiplexers; in LUT RAM each memory has one writer.)
  logic              swp;          // the live bits are being cleared (after a reset; u_axi)
  logic [SET_W-1:0]  swp_set;      // the set cleared in this clock

  // Entry register (the request being looked up).
  logic                   s0_valid_q;
  logic [3:0][ADDR_W-1:0] s0_addr_q;
  logic [TAG_W-1:0]       s0_tag_q;
  logic [3:0]             s0_todo_q;   // texels not yet sent in a pass
  logic [3:0]             s0_row_q;    // row bit per texel
  logic                   e_missed_q;  // an earlier pass of the request in the lookup missed
  logic [3:0][3:0]        s0_join_q;   // [u][t], u < t: texel t may share texel u's read (below)

  // Request FIFO (one entry per pass).
  typedef struct packed {
    logic [NSUB-1:0]             used;  // sub-cache read by the pass
    logic [NSUB-1:0][SET_W-1:0]  set;
    logic [NSUB-1:0][WAY_W-1:0]  way;
    logic [3:0]                  tsel;  // texels served by the pass
    logic [NSUB-1:0][WIN_W-1:0]  win;   // the window each sub-cache reads
    logic [3:0][1:0]             tsub;  // their sub-cache
    logic [3:0][TOFF_W-1:0]      toff;  // their word in that window (0 .. WW)
    logic [TAG_W-1:0]            tag;
    logic                        last;  // the request's last pass
  } pass_t;

  // (Block RAM: it is read only into fifo_rd_q, below; as LUT RAM it took 128 16x4 RAMs.)
  (* ram_style = "block" *) pass_t fifo_q [FIFO_DEPTH];
  logic [FP_W-1:0]   fifo_wp_q, fifo_rp_q;
  logic [FC_W-1:0]   fifo_cnt_q;

  // Head read stage (the clock after the pop: the RAMs read the lines).
  logic              h0_valid_q, h0_last_q, h0_err_q;
  logic [3:0]        h0_tsel_q;
  logic [3:0][1:0]   h0_tsub_q;
  logic [3:0][TOFF_W-1:0] h0_toff_q;
  logic [TAG_W-1:0]  h0_tag_q;
  // Select stage (the clock after: the RAMs' words in registers, ram_rd_q).
  logic              h1_valid_q, h1_last_q, h1_err_q;
  logic [3:0]        h1_tsel_q;
  logic [3:0][1:0]   h1_tsub_q;
  logic [3:0][TOFF_W-1:0] h1_toff_q;
  logic [TAG_W-1:0]  h1_tag_q;
  logic [3:0][31:0]  acc_texel_q;  // texels of the earlier passes of the request
  logic              acc_err_q;

  // Output buffer.
  typedef struct packed {
    logic [3:0][31:0] texel;
    logic             err;
    logic [TAG_W-1:0] tag;
  } rsp_t;

  (* ram_style = "block" *) rsp_t out_q [OUT_DEPTH];  // 185 bits: 6 EBRs instead of 42 LUT RAMs
  logic [1:0]        out_wp_q, out_rp_q;
  logic [2:0]        out_cnt_q;

  // MSHRs.
  logic                         mshr_busy_q [MSHRS];
  // An MSHR's sub-cache is a flop (a pass allocates up to four MSHRs in a clock, any of them to
  // any sub-cache); its line and slot are in LUT RAM, one memory per sub-cache indexed by the
  // MSHR (g_mshr below), so each has one writer: that sub-cache's allocation.  A read takes the
  // word of the MSHR's sub-cache.
  logic [1:0]                   mshr_sub_q  [MSHRS];
  logic [NSUB-1:0][LA_W-1:0]    mshr_la_ar;   // each sub-cache's line of the MSHR in ap_idx
  logic [NSUB-1:0][SET_W+WAY_W-1:0] mshr_sw_r;  // ... slot (set, way) of the MSHR of the R beat
  logic [NSUB-1:0][LA_W-1:0]    mshr_la_r;    // ... line of the MSHR of the R beat (simulation)
  logic [MIDX_W-1:0]            ar_idx;       // the MSHR at the AR queue's head
  logic [MIDX_W-1:0]            ap_idx;       // the MSHR of the next AR (u_axi's register)
`ifndef SYNTHESIS
  // The memories as the bound checks (tex_cache_assert) see them: the directory's words per
  // sub-cache and set (g_dir), its tags and reference counts per sub-cache, way and set, the
  // MSHRs' lines and slots per sub-cache and MSHR (g_mshr).
  logic [WAYS-1:0]              vw_live [NSUB][SETS];
  logic [WAYS-1:0]              vw_ag   [NSUB][SETS];
  logic [WAYS-1:0]              vw_fg   [NSUB][SETS];
  logic [WAYS-1:0]              vw_bad  [NSUB][SETS];
  logic [TAGB-1:0]              vw_tag  [NSUB][WAYS][SETS];
  logic [RC_W-1:0]              vw_inc  [NSUB][WAYS][SETS];
  logic [RC_W-1:0]              vw_dec  [NSUB][WAYS][SETS];
  logic [LA_W-1:0]              vw_la   [NSUB][MSHRS];
  logic [SET_W+WAY_W-1:0]       vw_sw   [NSUB][MSHRS];
`endif
  // (their beat counts and error bits, the AR queue and the reset epoch: u_axi)
  logic [QCNT_W-1:0]            arq_cnt;      // reads queued (for the assertions)

  logic [47:0] st_req_q, st_qhit_q, st_lk_q, st_miss_q, st_thit_q, st_bytes_q;

  // ---------------------------------------------------------------- row bits (at the input)
  // Row-bit position j: among the address bits j = WB + 2 .. ADDR_W - 1 (from the window's
  // size up), the one where the pitch R is closest to an odd multiple of 2^j, judged by the
  // ROW_P bits below bit j: the distance is e = R[j-1 -: ROW_P] when R[j] = 1, else its
  // complement (2^ROW_P - 1 - that); the smallest e wins, the lowest j on ties.  Adding R then
  // flips bit j of an address unless a carry (or borrow) from below bit j interferes, which
  // happens with probability about e / 2^ROW_P: never when R is a power of two (e = 0 at its
  // only one; for R below a window's bytes, j = WB + 2, which flips exactly when the bottom row
  // is in the next window).  The row bit of a texel is bit j of its row's first texel (c00 for
  // c00, c01; c10 for c10, c11), so that j may be the line-parity bit (R = LINE_BYTES).
  localparam int unsigned ROW_P = 3;
  localparam int unsigned ROW_NJ = ADDR_W - WB - 2;              // candidate positions
  localparam int unsigned ROW_NT = 1 << $clog2(ROW_NJ);          // leaves of the choice tree
  logic [ADDR_W-1:0] in_pitch;
  logic [3:0]        in_row;

  // The choice as a balanced tree of pairwise minima (a left subtree holds the lower positions
  // and wins ties), not a chain along the address: log2 of the candidates levels deep.  Each
  // node carries its best e and that position's row bits of c00 and c10.
  always_comb begin
    logic [2*ROW_NT-1:1]             nd_v;
    logic [2*ROW_NT-1:1][ROW_P-1:0]  nd_e;
    logic [2*ROW_NT-1:1][1:0]        nd_r;
    in_pitch = req_addr_i[2] - req_addr_i[0];
    nd_v = '0;
    nd_e = '1;
    nd_r = '0;
    for (int unsigned i = 0; i < ROW_NJ; i++) begin
      nd_v[ROW_NT + i] = 1'b1;
      nd_e[ROW_NT + i] = in_pitch[WB + 2 + i] ? in_pitch[WB + 1 + i -: ROW_P]
                                              : ~in_pitch[WB + 1 + i -: ROW_P];
      nd_r[ROW_NT + i] = {req_addr_i[2][WB + 2 + i], req_addr_i[0][WB + 2 + i]};
    end
    for (int unsigned n = ROW_NT - 1; n >= 1; n--) begin
      if (!nd_v[2 * n] || (nd_v[2 * n + 1] && nd_e[2 * n + 1] < nd_e[2 * n])) begin
        nd_v[n] = nd_v[2 * n + 1];
        nd_e[n] = nd_e[2 * n + 1];
        nd_r[n] = nd_r[2 * n + 1];
      end else begin
        nd_v[n] = nd_v[2 * n];
        nd_e[n] = nd_e[2 * n];
        nd_r[n] = nd_r[2 * n];
      end
    end
    in_row = {nd_r[1][1], nd_r[1][1], nd_r[1][0], nd_r[1][0]};
    if (in_pitch == '0) in_row = '0;  // rows clamped: one row
  end

  // window of a word (the window it starts in)
  function automatic logic [WIN_W-1:0] win_of(input logic [WSEL_W-1:0] w);
    return WIN_W'(32'(w) >> WB);
  endfunction

  // Which texels may share a read, compared at the input (registered with the request, so the
  // pass selection below chains single bits): in_join[u][t] (u < t) when texel t is in texel u's
  // line and in the window u's word starts (window k holds words k * WW .. k * WW + WW).
  logic [3:0][3:0] in_join;
  always_comb begin
    logic [WSEL_W-1:0] wu, wt;
    in_join = '0;
    for (int u = 0; u < 4; u++) begin
      for (int t = u + 1; t < 4; t++) begin
        wu = req_addr_i[u][OFF_W-1:2];
        wt = req_addr_i[t][OFF_W-1:2];
        in_join[u][t] = req_addr_i[u][ADDR_W-1:OFF_W] == req_addr_i[t][ADDR_W-1:OFF_W]
                        && (win_of(wt) == win_of(wu)
                            || 32'(wt) == (32'(win_of(wu)) + 1) * WW);
      end
    end
  end

  // ---------------------------------------------------------------- entry: pass selection
  // From the entry register: the request's next pass (sl_*), written into the pass queue.
  logic [3:0][LA_W-1:0]   e_la;
  logic [3:0][1:0]        e_sub;
  logic [3:0][WSEL_W-1:0] e_word;   // word in the line
  logic [3:0]             sl_sel;   // texels of the pass
  logic [NSUB-1:0]        sl_v;     // sub-caches the pass reads
  logic [NSUB-1:0][LA_W-1:0]  sl_la;
  logic [NSUB-1:0][WIN_W-1:0] sl_win;
  logic                   sl_last;  // the request's last pass

  always_comb begin
    logic lead;
    for (int t = 0; t < 4; t++) begin
      e_la[t]   = s0_addr_q[t][ADDR_W-1:OFF_W];
      e_sub[t]  = {s0_row_q[t], e_la[t][0]};
      e_word[t] = s0_addr_q[t][OFF_W-1:2];
    end
    // greedy, in texel order: a texel joins unless its sub-cache's first member (the leader,
    // which chose the line and the window) has another line, or a window the texel's word is
    // not in (window k holds words k * WW .. k * WW + WW); the first texel to do always joins
    for (int t = 0; t < 4; t++) begin
      sl_sel[t] = s0_valid_q && s0_todo_q[t];
      lead      = 1'b0;
      for (int u = 0; u < t; u++) begin
        if (!lead && sl_sel[u] && e_sub[u] == e_sub[t]) begin
          lead = 1'b1;
          if (!s0_join_q[u][t]) sl_sel[t] = 1'b0;
        end
      end
    end
    sl_v   = '0;
    sl_la  = '0;
    sl_win = '0;
    for (int t = 3; t >= 0; t--) begin  // the lowest member of a sub-cache is its leader
      if (sl_sel[t]) begin
        sl_v[e_sub[t]]   = 1'b1;
        sl_la[e_sub[t]]  = e_la[t];
        sl_win[e_sub[t]] = win_of(e_word[t]);
      end
    end
    sl_last = (s0_todo_q & ~sl_sel) == '0;
  end

  // ---------------------------------------------------------------- pass queue
  // The passes selected and not yet in the FIFO: PQ_DEPTH registers used as a queue (pq_q),
  // written at pq_wp_q.  The lookup takes two clocks, a read stage and a decide stage (below):
  // pq_ip_q is the next entry the read stage takes, pq_rp_q the oldest entry, the pass in the
  // decide stage when it holds one (b_valid_q), freed when that pass enters the FIFO (e_fire).
  // When the decide stage cannot let its pass go (the FIFO is full, an MSHR is missing, every way
  // of a missed set is referenced), it drops it and the pass behind it in the read stage, and
  // pq_ip_q goes back to pq_rp_q: the pass is read again from the directory as it then is (a
  // replay: two clocks per retry, and no outcome of the decision steers more than the pointers
  // and the stage valid bits).  A pass moves in while the queue has a free entry, judged from the
  // pointers alone, so neither the selection nor req_ready_o waits on the lookup's outcome in the
  // same clock.  Three entries keep one pass per clock going (one deciding, one being read, one
  // being selected); the fourth makes the pointers plain binary counters.
  localparam int unsigned PQ_DEPTH = 4;
  typedef struct packed {
    logic [NSUB-1:0]            v;     // sub-caches the pass reads
    logic [NSUB-1:0][LA_W-1:0]  la;
    logic [NSUB-1:0][SET_W-1:0] set;
    logic [NSUB-1:0][TAGB-1:0]  tag;   // the line address bits above the low set field
    logic [NSUB-1:0][WIN_W-1:0] win;
    logic [3:0]                 sel;   // texels of the pass
    logic [3:0][1:0]            psub;  // their sub-caches
    logic [3:0][WSEL_W-1:0]     word;  // their words in the line
    logic [TAG_W-1:0]           rtag;  // the request's tag
    logic                       last;  // the request's last pass
  } pq_t;

  pq_t [PQ_DEPTH-1:0]         pq_q;
  logic [2:0]                 pq_wp_q, pq_ip_q, pq_rp_q;  // (one bit above the index: full / empty)
  pq_t                        pq_d;      // the selected pass as it is written
  pq_t                        a_pass;    // the pass the read stage takes (pq_q[pq_ip_q])
  logic                       a_issue;   // there is one
  logic                       b_valid_q; // the decide stage holds a pass (pq_q[pq_rp_q])
  pq_t                        b_pass_q;
  logic                       replay;    // the decide stage drops its pass to read it again
  logic [NSUB-1:0]            lk_v;      // the decide stage's pass, as the lookup uses it
  logic [NSUB-1:0][LA_W-1:0]  lk_la;
  logic [NSUB-1:0][SET_W-1:0] lk_set;
  logic [NSUB-1:0][TAGB-1:0]  lk_tag;
  logic [NSUB-1:0][WIN_W-1:0] lk_win;
  logic [3:0]                 e_sel;
  logic [3:0][1:0]            e_psub;
  logic [3:0][TOFF_W-1:0]     e_toff;
  logic [TAG_W-1:0]           e_tag;
  logic                       e_last;
  logic                       p_load;    // the next pass moves into the queue
  logic                       e_fire;    // the decide stage's pass enters the FIFO

  assign p_load  = rst_ni && s0_valid_q && (pq_wp_q - pq_rp_q) != 3'(PQ_DEPTH);
  assign a_issue = pq_ip_q != pq_wp_q;
  assign a_pass  = pq_q[pq_ip_q[1:0]];
  assign replay  = b_valid_q && !e_fire;

  // The read stage's sets (the directory's read addresses) come from a register of their own,
  // a_set_q = a_pass.set while a_issue, loaded with the entry the read stage takes next: three
  // candidates from registers (the oldest entry for a replay, the one after pq_ip_q, or pq_ip_q
  // again; an entry written in this clock from pq_d), of which the decision picks one.
  logic [NSUB-1:0][SET_W-1:0] a_set_q, set_rp, set_next, set_hold;
  always_comb begin
    logic [2:0] ip1;
    ip1      = pq_ip_q + 3'd1;
    set_rp   = pq_q[pq_rp_q[1:0]].set;
    set_next = (ip1 == pq_wp_q) ? pq_d.set : pq_q[ip1[1:0]].set;
    set_hold = (pq_ip_q == pq_wp_q) ? pq_d.set : pq_q[pq_ip_q[1:0]].set;
  end
  always_ff @(posedge clk_i) begin
    a_set_q <= replay ? set_rp : (a_issue ? set_next : set_hold);
  end

  always_comb begin
    pq_d.v    = sl_v;
    pq_d.la   = sl_la;
    for (int c = 0; c < NSUB; c++) begin
      pq_d.set[c] = set_of(sl_la[c]);
      pq_d.tag[c] = sl_la[c][LA_W-1 -: TAGB];
    end
    pq_d.win  = sl_win;
    pq_d.sel  = sl_sel;
    pq_d.psub = e_sub;
    pq_d.word = e_word;
    pq_d.rtag = s0_tag_q;
    pq_d.last = sl_last;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      pq_wp_q   <= '0;
      pq_ip_q   <= '0;
      pq_rp_q   <= '0;
      b_valid_q <= 1'b0;
    end else begin
      if (p_load) pq_wp_q <= pq_wp_q + 3'd1;
      if (e_fire) pq_rp_q <= pq_rp_q + 3'd1;
      if (replay)       pq_ip_q <= pq_rp_q;  // (pq_rp_q does not move: no e_fire)
      else if (a_issue) pq_ip_q <= pq_ip_q + 3'd1;
      b_valid_q <= a_issue && !replay;
    end
    if (p_load) pq_q[pq_wp_q[1:0]] <= pq_d;
    b_pass_q <= a_pass;
  end

  always_comb begin
    lk_v   = b_pass_q.v;
    lk_la  = b_pass_q.la;
    lk_set = b_pass_q.set;
    lk_tag = b_pass_q.tag;
    lk_win = b_pass_q.win;
    e_sel  = b_pass_q.sel;
    e_psub = b_pass_q.psub;
    // a texel's word in the window its sub-cache reads (computed here, off the selection's path)
    for (int t = 0; t < 4; t++) begin
      e_toff[t] = TOFF_W'(32'(b_pass_q.word[t]) - 32'(b_pass_q.win[b_pass_q.psub[t]]) * WW);
    end
    e_tag  = b_pass_q.rtag;
    e_last = b_pass_q.last;
  end

  // ---------------------------------------------------------------- lookup: tags, victims
  logic [NSUB-1:0]            lk_alloc, lk_blocked;
  logic [NSUB-1:0][WAY_W-1:0] lk_way;     // the hit way or the victim
  logic [NSUB-1:0][MIDX_W-1:0] lk_mshr;   // MSHR of a miss
  logic                       mshr_short; // not enough free MSHRs for the pass's misses
  logic [NSUB-1:0][WAYS-1:0]  way_hit, way_free;
  // the directory's LUT RAM read at the read stage's set (g_dir)
  logic [NSUB-1:0][WAYS-1:0][TAGB-1:0] set_tag;
  logic [NSUB-1:0][WAYS-1:0][RC_W-1:0] set_inc, set_dec;
  logic [NSUB-1:0][PLRU_W-1:0]         set_plru;
  logic [NSUB-1:0][WAYS-1:0]           set_live, set_ag, set_fg, set_bad;

  logic [NSUB-1:0][MIDX_W-1:0] free_idx;  // free MSHRs for the pass's misses (free list, below)
  logic [NSUB-1:0]             free_ok;

  // Commit register (below): the pass that entered in the clock before, whose directory, MSHR
  // and FIFO writes happen in this clock.
  logic                        cm_valid_q;
  pass_t                       e_pass;      // the pass as it enters the FIFO (request FIFO)
  pass_t                       cm_pass_q;   // ... and as it is written there
  logic [NSUB-1:0]             cm_alloc_q;  // (its sub-caches, sets and ways: in cm_pass_q)
  logic [NSUB-1:0][TAGB-1:0]   cm_tag_q;
  logic [NSUB-1:0][LA_W-1:0]   cm_la_q;
  logic [NSUB-1:0][MIDX_W-1:0] cm_mshr_q;
  logic [NSUB-1:0][RC_W-1:0]   cm_inc_q;   // the slot's new reference-taken count
  logic [NSUB-1:0][PLRU_W-1:0] cm_plru_q;  // the set's new pseudo-LRU bits
  logic [NSUB-1:0][WAYS-1:0]   cm_ag_q;    // the set's new ag bits (written on an allocation)
  logic [NSUB-1:0][WAYS-1:0]   cm_live_q;  // ... and live bits

  // Read stage.  The directory at the pass's sets as the decide stage must see it: what the
  // RAMs hold with the commit register's writes (not yet done) forwarded, and what can be
  // compared already: each way's tag against the pass's (hit), its reference counts (idle: no
  // reference), and the pass's sets and tags against those of the pass now deciding, which is in
  // the commit register in the next clock if it enters the FIFO.  The fill's and the head's
  // writes of this clock are not seen (the decide stage sees them a clock later than a one-clock
  // lookup would): a slot whose reference is released in this clock looks referenced (never a
  // victim then), and a line completing in this clock looks pending, so a pass that hits a line
  // just come back with an error answers rsp_err_o = 1 (its quad has a bad line: a new read of
  // it would answer the same) rather than reading it again.
  logic [NSUB-1:0][WAYS-1:0]           a_vld, a_err, a_pnd, a_hit, a_idle;
  logic [NSUB-1:0][WAYS-1:0][RC_W-1:0] a_inc;
  logic [NSUB-1:0][PLRU_W-1:0]         a_plru;
  logic [NSUB-1:0][WAYS-1:0]           a_ag, a_live;
  logic [NSUB-1:0]                     a_seteq, a_tageq;

  always_comb begin
    logic                fw, fw_alloc, live, done_bad;
    logic [TAGB-1:0]     tag;
    for (int c = 0; c < NSUB; c++) begin
      fw        = cm_valid_q && cm_pass_q.used[c] && cm_pass_q.set[c] == a_set_q[c];
      a_plru[c] = fw ? cm_plru_q[c] : set_plru[c];
      a_ag[c]   = (fw && cm_alloc_q[c]) ? cm_ag_q[c] : set_ag[c];
      a_live[c] = (fw && cm_alloc_q[c]) ? cm_live_q[c] : set_live[c];
      for (int w = 0; w < WAYS; w++) begin
        fw_alloc     = fw && cm_alloc_q[c] && cm_pass_q.way[c] == WAY_W'(w);
        live         = set_live[c][w];
        done_bad     = set_ag[c][w] == set_fg[c][w] && set_bad[c][w];  // not pending, bad
        a_vld[c][w]  = fw_alloc || (live && !done_bad);
        a_pnd[c][w]  = fw_alloc || (live && set_ag[c][w] != set_fg[c][w]);
        a_err[c][w]  = !fw_alloc && live && done_bad;
        tag          = fw_alloc ? cm_tag_q[c] : set_tag[c][w];
        a_hit[c][w]  = tag == a_pass.tag[c];  // (a hit when valid too: in the decide stage)
        a_inc[c][w]  = (fw && cm_pass_q.way[c] == WAY_W'(w)) ? cm_inc_q[c] : set_inc[c][w];
        a_idle[c][w] = a_inc[c][w] == set_dec[c][w];
      end
      a_seteq[c] = b_valid_q && lk_v[c] && lk_set[c] == a_set_q[c];
      a_tageq[c] = lk_tag[c] == a_pass.tag[c];
    end
  end

  // Decide stage: the read stage's results, registered every clock (b_valid_q says whether they
  // belong to a pass), with the commit register's writes forwarded once more.
  logic [NSUB-1:0][WAYS-1:0]           b_vld_q, b_err_q, b_pnd_q, b_hit_q, b_idle_q, b_fg_q;
  logic [NSUB-1:0][WAYS-1:0][RC_W-1:0] b_inc_q, b_dec_q;
  logic [NSUB-1:0][PLRU_W-1:0]         b_plru_q;
  logic [NSUB-1:0][WAYS-1:0]           b_ag_q, b_live_q;
  logic [NSUB-1:0]                     b_seteq_q, b_tageq_q;

  always_ff @(posedge clk_i) begin
    b_vld_q   <= a_vld;
    b_err_q   <= a_err;
    b_pnd_q   <= a_pnd;
    b_hit_q   <= a_hit;
    b_idle_q  <= a_idle;
    b_fg_q    <= set_fg;
    b_inc_q   <= a_inc;
    b_dec_q   <= set_dec;
    b_plru_q  <= a_plru;
    b_ag_q    <= a_ag;
    b_live_q  <= a_live;
    b_seteq_q <= a_seteq;
    b_tageq_q <= a_tageq;
  end

  // The directory at the looked-up set as the decision must see it (f_*): a pass in the decide
  // stage was read while the pass now in the commit register was deciding, so that one's writes
  // are forwarded here (the sets and tags compared in the read stage).
  logic [NSUB-1:0][WAYS-1:0]           f_vld, f_err, f_pnd, f_hit, f_idle;
  logic [NSUB-1:0][WAYS-1:0][RC_W-1:0] f_inc;
  logic [NSUB-1:0][PLRU_W-1:0]         f_plru;
  logic [NSUB-1:0][WAYS-1:0]           f_ag, f_live;

  always_comb begin
    logic fw, fw_way, fw_alloc;
    for (int c = 0; c < NSUB; c++) begin
      // (no cm_valid_q: b_seteq_q holds only if this stage held a pass in the clock before, and
      // that pass entered the FIFO, or the replay would have dropped this one)
      fw        = b_seteq_q[c];
      f_plru[c] = fw ? cm_plru_q[c] : b_plru_q[c];
      f_ag[c]   = (fw && cm_alloc_q[c]) ? cm_ag_q[c] : b_ag_q[c];
      f_live[c] = (fw && cm_alloc_q[c]) ? cm_live_q[c] : b_live_q[c];
      for (int w = 0; w < WAYS; w++) begin
        fw_way       = fw && cm_pass_q.way[c] == WAY_W'(w);
        fw_alloc     = fw_way && cm_alloc_q[c];
        f_vld[c][w]  = fw_alloc || b_vld_q[c][w];
        f_pnd[c][w]  = fw_alloc || b_pnd_q[c][w];
        f_err[c][w]  = !fw_alloc && b_err_q[c][w];
        f_hit[c][w]  = fw_alloc ? b_tageq_q[c] : b_vld_q[c][w] && b_hit_q[c][w];
        f_inc[c][w]  = fw_way ? cm_inc_q[c] : b_inc_q[c][w];
        f_idle[c][w] = fw_way ? cm_inc_q[c] == b_dec_q[c][w] : b_idle_q[c][w];
      end
    end
  end

  always_comb begin
    logic [2:0] n_before;  // misses of the pass in the sub-caches before
    for (int c = 0; c < NSUB; c++) begin
      lk_way[c] = '0;
      for (int w = 0; w < WAYS; w++) begin
        way_hit[c][w]  = f_hit[c][w];
        way_free[c][w] = !(f_vld[c][w] || f_err[c][w]) || f_idle[c][w];
        if (way_hit[c][w]) lk_way[c] = WAY_W'(w);
      end
      lk_alloc[c]   = lk_v[c] && !(|way_hit[c]);
      lk_blocked[c] = lk_alloc[c] && !(|way_free[c]);
      if (!(|way_hit[c])) begin
        // an unreferenced invalid way first (the lowest), else pseudo-LRU among the unreferenced
        if (|(way_free[c] & ~f_vld[c])) begin
          for (int w = WAYS - 1; w >= 0; w--) begin
            if (way_free[c][w] && !f_vld[c][w]) lk_way[c] = WAY_W'(w);
          end
        end else begin
          lk_way[c] = plru_pick(f_plru[c], way_free[c]);
        end
      end
    end
    // MSHRs for the misses, in sub-cache order: the k-th miss of the pass takes the k-th free
    // MSHR (free_idx, from registers)
    mshr_short = 1'b0;
    lk_mshr    = '0;
    for (int c = 0; c < NSUB; c++) begin
      n_before = '0;
      for (int d = 0; d < c; d++) n_before = n_before + 3'(lk_alloc[d]);
      lk_mshr[c] = free_idx[n_before[1:0]];
      if (lk_alloc[c] && !free_ok[n_before[1:0]]) mshr_short = 1'b1;
    end
  end

  // The free MSHRs are a queue of indices (fl_q, in the MSHR section below), taken from its
  // head as a pass enters the FIFO: free_idx[k] = fl_q[fl_hd_q + k], from registers; a line's
  // last beat puts its MSHR back at the tail (seen from the next clock).
  logic [2:0] lk_n;  // the pass's misses

  always_comb begin
    lk_n = '0;
    for (int c = 0; c < NSUB; c++) lk_n = lk_n + 3'(lk_alloc[c]);
  end

  assign e_fire      = rst_ni && b_valid_q && (32'(fifo_cnt_q) + 32'(cm_valid_q) < FIFO_DEPTH)
                       && !(|lk_blocked) && !mshr_short;

  // ---------------------------------------------------------------- commit register
  // Loaded every clock (cm_valid_q says whether it holds a pass), so the lookup's outcome
  // drives no enable here; the writes it describes happen in the next clock.
  logic [2:0] cm_texel_hits_q;
  logic       cm_qhit_q;
  logic [2:0] e_texel_hits;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) cm_valid_q <= 1'b0;
    else         cm_valid_q <= e_fire;
    cm_alloc_q      <= lk_alloc;
    cm_tag_q        <= lk_tag;
    cm_la_q         <= lk_la;
    cm_mshr_q       <= lk_mshr;
    for (int c = 0; c < NSUB; c++) begin
      cm_plru_q[c] <= plru_touch(f_plru[c], lk_way[c]);
      // (the victim: not pending, no fill due)
      cm_ag_q[c]   <= with_way(f_ag[c], lk_way[c], !b_fg_q[c][lk_way[c]]);
      cm_live_q[c] <= with_way(f_live[c], lk_way[c], 1'b1);
      cm_inc_q[c]  <= (lk_alloc[c] ? b_dec_q[c][lk_way[c]] : f_inc[c][lk_way[c]]) + RC_W'(1);
    end
    cm_pass_q       <= e_pass;
    cm_texel_hits_q <= e_texel_hits;
    cm_qhit_q       <= e_last && !e_missed_q && !(|lk_alloc);
  end
  assign req_ready_o = rst_ni && !swp && (!s0_valid_q || (p_load && sl_last));

  logic req_fire;
  assign req_fire = req_valid_i && req_ready_o;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      s0_valid_q  <= 1'b0;
      s0_todo_q   <= '0;
      e_missed_q  <= 1'b0;
    end else begin
      if (req_fire) begin
        s0_valid_q  <= 1'b1;
        s0_todo_q   <= 4'hf;
      end else if (p_load) begin  // a pass of a request with more to do
        s0_todo_q   <= s0_todo_q & ~sl_sel;
        if (sl_last) s0_valid_q <= 1'b0;
      end
      if (e_fire) e_missed_q <= !e_last && (e_missed_q || (|lk_alloc));
    end
    if (req_fire) begin
      s0_addr_q <= req_addr_i;
      s0_tag_q  <= req_tag_i;
      s0_row_q  <= in_row;
      s0_join_q <= in_join;
    end
  end

  // ---------------------------------------------------------------- request FIFO
  logic  h_pop, h_ready;

  always_comb begin
    e_pass.used = lk_v;
    e_pass.set  = lk_set;
    e_pass.way  = lk_way;
    e_pass.tsel = e_sel;
    e_pass.win  = lk_win;
    e_pass.tsub = e_psub;
    e_pass.toff = e_toff;
    e_pass.tag  = e_tag;
    e_pass.last = e_last;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      fifo_wp_q  <= '0;
      fifo_rp_q  <= '0;
      fifo_cnt_q <= '0;
    end else begin
      if (cm_valid_q) fifo_wp_q <= fifo_wp_q + FP_W'(1);
      if (h_pop)      fifo_rp_q <= fifo_rp_q + FP_W'(1);
      fifo_cnt_q <= fifo_cnt_q + FC_W'(cm_valid_q) - FC_W'(h_pop);
    end
    if (cm_valid_q) fifo_q[fifo_wp_q] <= cm_pass_q;
  end

  // ---------------------------------------------------------------- head: wait, pop, read
  logic       out_pop;
  logic [NSUB-1:0] hd_err;
  logic [NSUB-1:0] hd_pend, hd_bad;  // the head's slot per sub-cache: pending, bad (g_dir)

  assign out_pop = rsp_valid_o && rsp_ready_i;

  // The head entry hd_q (= fifo_q[fifo_rp_q] while the FIFO holds a pass) and the one behind it,
  // nx_q (= fifo_q[fifo_rp_q + 1] while it holds two), are registers, so the head's readiness
  // (its lines present) and the pop start from flip-flops, not from the block RAM's output (4.3
  // ns clock-to-out on the ECP5).  The block RAM is read every clock two entries ahead of the
  // head after this clock's pop (fifo_rp_q + 2 + h_pop) into fifo_rd_q, which refills nx_q at a
  // pop; a pass entering as the first or second goes straight to its register, and one written
  // at the address read in the same clock (the read sees the old word) is taken from a copy of
  // the commit register (byp_q).  So one pop per clock, from registers.
  pass_t           hd_q, nx_q, fifo_rd_q, byp_q, rd_eff;
  pass_t           hd_pop_d, hd_hold_d, nx_pop_d, nx_hold_d;
  logic            byp_v_q;  // fifo_rd_q was read as byp_q was written there: take byp_q
  logic [FP_W-1:0] rd_addr;
  assign rd_addr = h_pop ? fifo_rp_q + FP_W'(3) : fifo_rp_q + FP_W'(2);

  always_ff @(posedge clk_i) begin
    fifo_rd_q <= fifo_q[rd_addr];
    byp_q     <= cm_pass_q;
    byp_v_q   <= cm_valid_q && fifo_wp_q == rd_addr;
  end

  // the next head and next-behind-head with and without a pop (from registers), then the pop
  // picks
  always_comb begin
    rd_eff    = byp_v_q ? byp_q : fifo_rd_q;
    hd_pop_d  = (fifo_cnt_q >= FC_W'(2)) ? nx_q : cm_pass_q;    // entry rp + 1
    nx_pop_d  = (fifo_cnt_q >= FC_W'(3)) ? rd_eff : cm_pass_q;  // entry rp + 2
    hd_hold_d = (fifo_cnt_q == '0) ? cm_pass_q : hd_q;          // entry rp
    nx_hold_d = (fifo_cnt_q == FC_W'(1)) ? cm_pass_q : nx_q;     // entry rp + 1
  end

  always_ff @(posedge clk_i) begin
    hd_q <= h_pop ? hd_pop_d : hd_hold_d;
    nx_q <= h_pop ? nx_pop_d : nx_hold_d;
  end

  always_comb begin
    h_ready = (fifo_cnt_q != '0);
    for (int c = 0; c < NSUB; c++) begin
      // (the head's slots are live: allocated by this pass or hit as valid by it)
      if (hd_q.used[c] && hd_pend[c]) h_ready = 1'b0;
      hd_err[c] = hd_q.used[c] && !hd_pend[c] && hd_bad[c];
    end
  end

  // room in the output buffer for the result and those of the passes popped before it
  // (out_cnt_q - out_pop + h0_valid_q + h1_valid_q + 1 <= OUT_DEPTH, with the registers' sum
  // compared apart from the late out_pop)
  logic [2:0] out_need;
  assign out_need = out_cnt_q + 3'(h0_valid_q) + 3'(h1_valid_q);
  assign h_pop = rst_ni && h_ready
                 && (out_need < 3'(OUT_DEPTH) || (out_need == 3'(OUT_DEPTH) && out_pop));

  // ---------------------------------------------------------------- data RAMs
  // A sub-cache stores a line as NWIN windows of WW words at RAM address {set, way, window}; a
  // pass reads one window and the word after it (the overlap word, kept in a second RAM at the
  // same address: word (k + 1) * WW of the line for window k), so a horizontal pair w, w + 1 is
  // always in one read.  Each R beat is written where it belongs as it arrives, one RAM per beat
  // lane (the beat's lane of the window; the overlap RAM takes the first 32 bits of a window
  // from its beats, for the window before).  The slot is pending until the last beat, so nothing
  // reads the partial line; a line that fails keeps its partial write, which the error bit makes
  // harmless (the slot is not valid).
  logic [MIDX_W-1:0]  r_idx;
  logic               r_cur, r_ours, r_acc, r_last_beat;
  logic [LA_W-1:0]   r_la;
  logic [1:0]        fill_sub;
  logic [SET_W-1:0]  fill_set;
  logic [WAY_W-1:0]  fill_way;
  logic [BEAT_W-1:0] r_beat;       // the beat's index in the line
  logic [WIN_W-1:0]  r_win;        // its window
  logic [LANE_B-1:0] r_lane;       // its lane in the window
  logic              fill_v, fill_bad;
  // The beat registered (w_*_q): the clock after its arrival it is written into its data RAM
  // and, if it is the line's last, the slot's generation and error bits are written (so no
  // write starts at the R channel's inputs through the MSHR's LUT RAM reads).
  logic              w_acc_q, w_fill_q, w_bad_q;
  logic [1:0]        w_sub_q;
  logic [SET_W-1:0]  w_set_q;
  logic [WAY_W-1:0]  w_way_q;
  logic [BEAT_W-1:0] w_beat_q;
  logic [DATA_W-1:0] w_data_q;
  logic [LA_W-1:0]   w_la_q;
  logic [WW:0][31:0] ram_rd [NSUB];  // window words 0 .. WW-1, then the overlap word
  logic [WW:0][31:0] ram_rd_q [NSUB];  // ... registered (the block RAMs' 4.3 ns clock-to-out)

  function automatic logic [RAM_AW-1:0] ram_addr(input logic [SET_W-1:0] s,
                                                 input logic [WAY_W-1:0] w,
                                                 input logic [WIN_W-1:0] k);
    return RAM_AW'((32'(s) * WAYS + 32'(w)) * NWIN + ((NWIN > 1) ? 32'(k) : 0));
  endfunction

  always_comb begin
    r_win  = WIN_W'(32'(w_beat_q) / NLANE);
    r_lane = LANE_B'(32'(w_beat_q) % NLANE);
  end

  for (genvar c = 0; c < NSUB; c++) begin : g_sub
    logic [RAM_AW-1:0] waddr, raddr;
    logic              wsub, rd;
    logic [WW*32-1:0]  rd_win;      // the window's words
    logic [31:0]       rd_ovl;      // the overlap word
    assign ram_rd[c] = {rd_ovl, rd_win};
    assign wsub  = w_acc_q && w_sub_q == 2'(c);
    assign waddr = ram_addr(w_set_q, w_way_q, r_win);
    assign rd    = 1'b1;  // the head's window, every clock (used the clock after a pop)
    assign raddr = ram_addr(hd_q.set[c], hd_q.way[c], hd_q.win[c]);
    for (genvar l = 0; l < NLANE; l++) begin : g_lane
      cache_sdp_ram #(.DEPTH(RAM_DEPTH), .WIDTH(DATA_W)) u_ram (
        .clk_i   (clk_i),
        .we_i    (wsub && 32'(r_lane) == l),
        .waddr_i (waddr),
        .wdata_i (w_data_q),
        .re_i    (rd),
        .raddr_i (raddr),
        .rdata_o (rd_win[l * DATA_W +: DATA_W])
      );
    end
    if (NWIN > 1) begin : g_ovl
      for (genvar o = 0; o < NOVL; o++) begin : g_lane
        cache_sdp_ram #(.DEPTH(RAM_DEPTH), .WIDTH(OVL_W)) u_ram (
          .clk_i   (clk_i),
          .we_i    (wsub && r_win != '0 && 32'(r_lane) == o),
          .waddr_i (RAM_AW'(waddr - RAM_AW'(1))),  // the window before, same slot
          .wdata_i (w_data_q[OVL_W-1:0]),
          .re_i    (rd),
          .raddr_i (raddr),
          .rdata_o (rd_ovl[o * OVL_W +: OVL_W])
        );
      end
    end else begin : g_no_ovl
      assign rd_ovl = '0;  // a window is the whole line: offset WW is never read
    end
  end

  // ---------------------------------------------------------------- select, merge, output
  logic [3:0][31:0] h1_texel;
  rsp_t             h1_rsp;

  always_comb begin
    for (int t = 0; t < 4; t++) begin
      h1_texel[t] = acc_texel_q[t];
      if (h1_tsel_q[t]) h1_texel[t] = ram_rd_q[h1_tsub_q[t]][h1_toff_q[t]];
    end
    h1_rsp.texel = h1_texel;
    h1_rsp.err   = acc_err_q || h1_err_q;
    h1_rsp.tag   = h1_tag_q;
  end

  logic out_push;
  assign out_push = h1_valid_q && h1_last_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      h0_valid_q  <= 1'b0;
      h1_valid_q  <= 1'b0;
      acc_err_q   <= 1'b0;
      acc_texel_q <= '0;
      out_wp_q    <= '0;
      out_rp_q    <= '0;
      out_cnt_q   <= '0;
    end else begin
      h0_valid_q <= h_pop;
      h1_valid_q <= h0_valid_q;
      if (h1_valid_q) begin
        if (h1_last_q) begin
          acc_err_q   <= 1'b0;
          acc_texel_q <= '0;
        end else begin
          acc_err_q   <= h1_rsp.err;
          acc_texel_q <= h1_texel;
        end
      end
      if (out_push) out_wp_q <= out_wp_q + 2'd1;
      if (out_pop)  out_rp_q <= out_rp_q + 2'd1;
      out_cnt_q <= out_cnt_q + 3'(out_push) - 3'(out_pop);
    end
    // (loaded every clock, like the data RAMs' read: they matter only where h0_valid_q and
    // h1_valid_q say a popped pass is; so the pop, late in its clock, enables none of them)
    h0_last_q  <= hd_q.last;
    h0_err_q   <= |hd_err;
    h0_tsel_q  <= hd_q.tsel;
    h0_tsub_q  <= hd_q.tsub;
    h0_toff_q  <= hd_q.toff;
    h0_tag_q   <= hd_q.tag;
    h1_last_q  <= h0_last_q;
    h1_err_q   <= h0_err_q;
    h1_tsel_q  <= h0_tsel_q;
    h1_tsub_q  <= h0_tsub_q;
    h1_toff_q  <= h0_toff_q;
    h1_tag_q   <= h0_tag_q;
    ram_rd_q   <= ram_rd;
    if (out_push) out_q[out_wp_q] <= h1_rsp;
  end

  assign rsp_valid_o = (out_cnt_q != '0);
  assign rsp_texel_o = out_q[out_rp_q].texel;
  assign rsp_err_o   = out_q[out_rp_q].err;
  assign rsp_tag_o   = out_q[out_rp_q].tag;

  // ---------------------------------------------------------------- R channel, fills

  // (the beat's MSHR r_idx, its index r_beat, r_last_beat and fill_bad: from u_axi)
  always_comb begin
    r_acc       = rst_ni && r_ours && mshr_busy_q[r_idx];
    r_la        = mshr_la_r[mshr_sub_q[r_idx]];
    fill_v      = r_acc && r_last_beat;
    fill_sub    = mshr_sub_q[r_idx];
    {fill_set, fill_way} = mshr_sw_r[mshr_sub_q[r_idx]];
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      w_acc_q  <= 1'b0;
      w_fill_q <= 1'b0;
    end else begin
      w_acc_q  <= r_acc;
      w_fill_q <= fill_v;
    end
    w_bad_q  <= fill_bad;
    w_sub_q  <= fill_sub;
    w_set_q  <= fill_set;
    w_way_q  <= fill_way;
    w_beat_q <= r_beat;
    w_data_q <= m_axi_rdata;
    w_la_q   <= r_la;
  end

  // ---------------------------------------------------------------- directory updates
  // The LUT RAM part (see "Directory" at the state).  Per sub-cache: the commit touches the
  // looked-up set's pseudo-LRU bits and takes a reference to the hit or victim way (an allocation
  // also writes the tag and the set's ag bits); the head releases the reference of each slot its
  // pass reads; a line's last beat writes its set's fg and bad bits (fg = ag: not pending).
  for (genvar c = 0; c < NSUB; c++) begin : g_dir
    logic              take;             // the committing pass reads sub-cache c
    logic              give;             // the head's pass read sub-cache c
    logic              fill;             // a line of sub-cache c completes
    logic [PLRU_W-1:0] plru_mem [SETS];
    logic [WAYS-1:0]   live_mem [SETS];
    logic [WAYS-1:0]   ag_mem   [SETS];
    logic [WAYS-1:0]   fg_mem   [SETS];
    logic [WAYS-1:0]   bad_mem  [SETS];
    logic [WAYS-1:0]   fl_ag, fl_fg, fl_bad, hd_ag, hd_fg, hd_bd;

    assign take = cm_valid_q && cm_pass_q.used[c];  // (cm_valid_q is 0 in reset)
    assign give = h_pop && hd_q.used[c];
    assign fill = w_fill_q && w_sub_q == 2'(c);

    always_ff @(posedge clk_i) begin
      if (take) plru_mem[cm_pass_q.set[c]] <= cm_plru_q[c];
      if (take && cm_alloc_q[c]) ag_mem[cm_pass_q.set[c]] <= cm_ag_q[c];
      // (no commit while the sweep runs: nothing is accepted until it ends)
      if (swp) live_mem[swp_set] <= '0;
      else if (take && cm_alloc_q[c]) live_mem[cm_pass_q.set[c]] <= cm_live_q[c];
      if (fill) begin
        fg_mem[w_set_q]  <= with_way(fl_fg, w_way_q, fl_ag[w_way_q]);
        bad_mem[w_set_q] <= with_way(fl_bad, w_way_q, w_bad_q);
      end
    end
    assign set_plru[c] = plru_mem[a_set_q[c]];
    assign set_live[c] = live_mem[a_set_q[c]];
    assign set_ag[c]   = ag_mem[a_set_q[c]];
    assign set_fg[c]   = fg_mem[a_set_q[c]];
    assign set_bad[c]  = bad_mem[a_set_q[c]];
    assign fl_ag       = ag_mem[w_set_q];
    assign fl_fg       = fg_mem[w_set_q];
    assign fl_bad      = bad_mem[w_set_q];
    assign hd_ag       = ag_mem[hd_q.set[c]];
    assign hd_fg       = fg_mem[hd_q.set[c]];
    assign hd_bd       = bad_mem[hd_q.set[c]];
    assign hd_pend[c]  = hd_ag[hd_q.way[c]] != hd_fg[hd_q.way[c]];
    assign hd_bad[c]   = hd_bd[hd_q.way[c]];

`ifndef SYNTHESIS
    assign vw_live[c] = live_mem;
    assign vw_ag[c]   = ag_mem;
    assign vw_fg[c]   = fg_mem;
    assign vw_bad[c]  = bad_mem;
`endif

    for (genvar w = 0; w < WAYS; w++) begin : g_way
      logic [TAGB-1:0] tag_mem [SETS];
      logic [RC_W-1:0] inc_mem [SETS];
      logic [RC_W-1:0] dec_mem [SETS];
      logic [RC_W-1:0] hd_dec;           // dec of the head's slot

      always_ff @(posedge clk_i) begin
        if (take && cm_pass_q.way[c] == WAY_W'(w)) begin
          if (cm_alloc_q[c]) tag_mem[cm_pass_q.set[c]] <= cm_tag_q[c];
          inc_mem[cm_pass_q.set[c]] <= cm_inc_q[c];
        end
        if (give && hd_q.way[c] == WAY_W'(w)) dec_mem[hd_q.set[c]] <= hd_dec + RC_W'(1);
      end
      assign set_tag[c][w] = tag_mem[a_set_q[c]];
      assign set_inc[c][w] = inc_mem[a_set_q[c]];
      assign set_dec[c][w] = dec_mem[a_set_q[c]];
      assign hd_dec        = dec_mem[hd_q.set[c]];

`ifndef SYNTHESIS
      assign vw_tag[c][w] = tag_mem;
      assign vw_inc[c][w] = inc_mem;
      assign vw_dec[c][w] = dec_mem;
`endif
    end
  end

  // ---------------------------------------------------------------- MSHRs and AXI reads
  // The AR channel (u_axi, AR_REG = 1) is a register loaded from a register of the next read's
  // MSHR (ap_idx) and sub-cache (ap_sub_q), which is loaded from the AR queue's head as it leaves
  // (ar_pop); so no LUT RAM read or multiplexer drives the port, and the line's LUT RAM is read
  // at a registered index.  The misses of one pass join the AR queue in sub-cache order.
  logic              ar_pop;
  logic [1:0]        ap_sub_q;
  logic [NSUB-1:0]   cm_new;  // the committing pass allocates an MSHR in sub-cache c
  assign cm_new = cm_valid_q ? cm_alloc_q : '0;

  cache_axi_read #(
    .ADDR_W(ADDR_W), .DATA_W(DATA_W), .LINE_BYTES(LINE_BYTES), .MSHRS(MSHRS), .ID_W(ID_W),
    .SETS(SETS), .NPUSH(NSUB), .AR_REG(1'b1)
  ) u_axi (
    .clk_i, .rst_ni,
    .alloc_i(cm_new), .alloc_wr_i(cm_new), .alloc_idx_i(cm_mshr_q),
    .la_idx_o(ap_idx), .la_i(mshr_la_ar[ap_sub_q]),
    .arq_pop_o(ar_pop), .arq_head_o(ar_idx), .arq_cnt_o(arq_cnt),
    .r_idx_o(r_idx), .r_cur_o(r_cur), .r_ours_o(r_ours), .r_acc_i(r_acc), .r_beat_o(r_beat),
    .r_last_o(r_last_beat), .r_bad_o(fill_bad),
    .sweep_o(swp), .sweep_set_o(swp_set),
    .m_axi_arid, .m_axi_araddr, .m_axi_arlen, .m_axi_arsize, .m_axi_arburst, .m_axi_arvalid,
    .m_axi_arready, .m_axi_rid, .m_axi_rresp, .m_axi_rlast, .m_axi_rvalid, .m_axi_rready);

  always_ff @(posedge clk_i) begin
    if (ar_pop) ap_sub_q <= mshr_sub_q[ar_idx];
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int m = 0; m < MSHRS; m++) mshr_busy_q[m] <= 1'b0;
    end else begin
      if (r_acc && r_last_beat) mshr_busy_q[r_idx] <= 1'b0;
      for (int c = 0; c < NSUB; c++) begin
        // (a free MSHR: never the one finishing now)
        if (cm_new[c]) mshr_busy_q[cm_mshr_q[c]] <= 1'b1;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    for (int c = 0; c < NSUB; c++) begin
      if (cm_valid_q && cm_alloc_q[c]) mshr_sub_q[cm_mshr_q[c]] <= 2'(c);
    end
  end

  for (genvar c = 0; c < NSUB; c++) begin : g_mshr
    logic [LA_W-1:0]        la_mem [MSHRS];
    logic [SET_W+WAY_W-1:0] sw_mem [MSHRS];
    always_ff @(posedge clk_i) begin
      if (cm_valid_q && cm_alloc_q[c]) begin
        la_mem[cm_mshr_q[c]] <= cm_la_q[c];
        sw_mem[cm_mshr_q[c]] <= {cm_pass_q.set[c], cm_pass_q.way[c]};
      end
    end
    assign mshr_la_ar[c] = la_mem[ap_idx];
    assign mshr_sw_r[c]  = sw_mem[r_idx];
    assign mshr_la_r[c]  = la_mem[r_idx];  // (read only by the simulation's shadow)
`ifndef SYNTHESIS
    assign vw_la[c] = la_mem;
    assign vw_sw[c] = sw_mem;
`endif
  end

  function automatic logic [MIDX_W-1:0] arq_add(input logic [MIDX_W-1:0] p, input int unsigned k);
    int unsigned q;
    q = 32'(p) + k;
    if (q >= MSHRS) q = q - MSHRS;
    return MIDX_W'(q);
  endfunction

  // Free MSHRs, a queue of indices: all of them after a reset; a pass entering the FIFO takes
  // one per miss from the head (they are busy from its commit clock on), a line's last beat
  // returns its MSHR at the tail (one per clock at most).
  logic [MIDX_W-1:0] fl_q [MSHRS];
  logic [MIDX_W-1:0] fl_hd_q, fl_tl_q;
  logic [QCNT_W-1:0] fl_cnt_q;

  always_comb begin
    for (int k = 0; k < NSUB; k++) begin
      free_idx[k] = fl_q[arq_add(fl_hd_q, k)];
      free_ok[k]  = 32'(fl_cnt_q) > k;
    end
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int m = 0; m < MSHRS; m++) fl_q[m] <= MIDX_W'(m);
      fl_hd_q  <= '0;
      fl_tl_q  <= '0;
      fl_cnt_q <= QCNT_W'(MSHRS);
    end else begin
      if (e_fire) fl_hd_q <= arq_add(fl_hd_q, 32'(lk_n));
      if (fill_v) begin
        fl_q[fl_tl_q] <= r_idx;
        fl_tl_q       <= arq_add(fl_tl_q, 1);
      end
      fl_cnt_q <= fl_cnt_q - (e_fire ? QCNT_W'(lk_n) : '0) + QCNT_W'(fill_v);
    end
  end

  // ---------------------------------------------------------------- statistics
  // texels of this pass whose sub-cache lookup hit
  always_comb begin
    e_texel_hits = '0;
    for (int t = 0; t < 4; t++) begin
      e_texel_hits = e_texel_hits + 3'(e_sel[t] && !lk_alloc[e_psub[t]]);
    end
  end

  // A request is counted the clock after its handshake (the handshake is late in its clock);
  // one accepted in a clock with clr_stats_i is not counted, as if counted and then cleared.
  logic st_req_ev_q;
  always_ff @(posedge clk_i) begin
    st_req_ev_q <= rst_ni && req_fire && !clr_stats_i;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni || clr_stats_i) begin
      st_req_q   <= '0;
      st_qhit_q  <= '0;
      st_lk_q    <= '0;
      st_miss_q  <= '0;
      st_thit_q  <= '0;
      st_bytes_q <= '0;
    end else begin
      st_req_q <= st_req_q + 48'(st_req_ev_q);
      if (cm_valid_q) begin
        st_lk_q   <= st_lk_q + 48'($countones(cm_pass_q.used));
        st_miss_q <= st_miss_q + 48'($countones(cm_alloc_q));
        st_thit_q <= st_thit_q + 48'(cm_texel_hits_q);
        if (cm_qhit_q) st_qhit_q <= st_qhit_q + 48'd1;
      end
      if (r_acc) st_bytes_q <= st_bytes_q + 48'(BEAT_BYTES);
    end
  end

  assign stat_requests_o    = st_req_q;
  assign stat_quad_hits_o   = st_qhit_q;
  assign stat_lookups_o     = st_lk_q;
  assign stat_line_misses_o = st_miss_q;
  assign stat_texel_hits_o  = st_thit_q;
  assign stat_bytes_o       = st_bytes_q;

  // The texel address bits 1:0 are 0; w_la_q is read by the bound checks only.
  logic unused;
  assign unused = ^{w_la_q, s0_addr_q[0][1:0], s0_addr_q[1][1:0],
                    s0_addr_q[2][1:0], s0_addr_q[3][1:0]};

endmodule
