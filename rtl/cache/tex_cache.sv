// SPDX-License-Identifier: Apache-2.0
// tex_cache: the unified texture / normal-map cache of Park et al. 2013, Fig. 6.  It serves the
// bilinear filter one 2x2 texel quad per clock, in request order, and hides the memory latency by
// prefetching in the style of Igehy, Eldridge and Proudfoot ("Prefetching in a texture cache
// architecture", 1998): tags are checked when a request enters, misses go to memory at once, the
// request waits in an in-order FIFO, and its texels are read from the data RAMs at the FIFO head
// once its lines are there.
//
// Files: tex_cache_front (entry register, pass selection, pass queue), tex_cache_lookup (the
// lookup's read and decide stages), tex_cache_data (data RAMs, texel select, output buffer, the
// requests' tag queue), cache_axi_read (AR queue and channel, reset epoch, R beat counts, reset
// sweep); here the directory, the commit register, the request FIFO and its head, the MSHRs and
// the statistics.
// The simulation checks and coverage points are in tex_cache_assert (bound into tex_cache).
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
// adding R flips most reliably (see "row bits" in tex_cache_front; for R = 2^k it is bit k).
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
// The live bits (allocated since the reset), the pseudo-LRU bits and the generation and error
// bits that give each slot's valid, pending and error state are LUT RAM, one memory per
// sub-cache; the tags and the reference counts two memories per sub-cache and way ({tag, inc}
// and dec), LUT RAM by default, block RAM with DIR_RAM "block"; each memory is written from one
// place (see "Directory" at the state); the lines are in block RAM
// (cache_sdp_ram), per sub-cache one RAM per DATA_W lane of a window and one for the overlap
// words, SETS * WAYS * NWIN deep (address {set, way, window}; see "data RAMs" in tex_cache_data).
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
//   clock 2   the read stage's set register is loaded with the pass's sets from the queue's
//             registers (never from the selection: a pass behind another is loaded while
//             that one is read, so one pass per clock; tex_cache_front).
//   clock 3   lookup, read stage: the next pass in the queue reads the directory at its sets in
//             the four sub-caches (tags, reference counts, pseudo-LRU and state bits) and
//             compares each way's tag with its own.
//   clock 4   lookup, decide stage: hit or miss per sub-cache; a miss picks a victim way and an
//             MSHR.  All or nothing: the pass cannot go while the FIFO is full, while an MSHR is
//             missing for one of its misses, or while every way of a missed set is referenced;
//             then, after a clock's wait, it and the pass behind it are read again (a replay,
//             see tex_cache_front: the wait keeps the decision off the read address).  The
//             queue's room is judged from its pointers, so the lookup's outcome steers no enable
//             of the entry register or of the queue's entries in its own clock (only the
//             queue's pointers and the stage valid bits).
//   clock 5   commit: the pass's directory writes (tags, references, pseudo-LRU, valid and
//             pending bits), its MSHRs and line reads, and its push into the request FIFO
//             (FIFO_DEPTH passes) happen from the commit register, so no write waits on the
//             lookup's outcome in its own clock; the next passes' lookups see them forwarded.
//   clock 6   head: when the lines of the head pass are present (no pending fill), the pass
//             leaves the FIFO and reads the data RAMs (one window per sub-cache).  Its slots'
//             pending and error bits are registers, loaded the clock before for the pass that
//             is head now (see "head"), so the pop starts from flip-flops.
//   clock 7   the data RAMs' words are registered (their 4.3 ns clock-to-out on the ECP5).
//   clock 8   the texels are selected (and merged with earlier passes of the request).
//   clock 9   rsp_valid_o (a 4-entry output buffer).
// So a request that hits answers 9 clocks after its handshake; full throughput is one pass per
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
  /* verilator lint_off UNUSEDPARAM */  // (an attribute: read by synthesis only)
  parameter string       DIR_RAM    = "auto",  // ram_style of the tags and reference counts
                                           // ("auto": Yosys's choice, LUT RAM; "block": block
                                           // RAM, 2 x 4 x WAYS RAMs of SETS words; see
                                           // "Directory")
  /* verilator lint_on UNUSEDPARAM */
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
  localparam int unsigned PQ_DEPTH   = 4;                        // pass queue entries
  // Request tags (tex_cache_data's tag queue, a power of two): room for every request accepted
  // and not yet answered, at most one in the entry register, PQ_DEPTH in the pass queue,
  // FIFO_DEPTH in the commit register and the FIFO, OUT_DEPTH in the answer path.
  localparam int unsigned TQ_DEPTH   = 1 << $clog2(1 + PQ_DEPTH + FIFO_DEPTH + OUT_DEPTH);
  // data RAM windows (see "data RAMs" in tex_cache_data)
  localparam int unsigned LWORDS     = LINE_BYTES / 4;           // words per line
  localparam int unsigned WW         = (WIN_WORDS < LWORDS) ? WIN_WORDS : LWORDS;
  localparam int unsigned NWIN       = LWORDS / WW;              // windows per line
  localparam int unsigned WB         = $clog2(WW);               // log2 words per window
  localparam int unsigned WIN_W      = (NWIN > 1) ? $clog2(NWIN) : 1;
  localparam int unsigned TOFF_W     = WB + 1;                   // word in a read window, 0 .. WW

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

  // Slot (s, w) of a sub-cache as its state memories (g_dir) hold it after this clock's writes:
  // {pending, bad} from the words ag, fg, bad read at s now, with the commit's ag word aw (when
  // aw_v, at set aw_set) and the fill of slot (f_set, f_way) (when f_v: fg = f_ag, bad = f_bad)
  // applied.
  function automatic logic [1:0] slot_next(
      input logic [WAYS-1:0] ag, input logic [WAYS-1:0] fg, input logic [WAYS-1:0] bd,
      input logic [SET_W-1:0] s, input logic [WAY_W-1:0] w,
      input logic aw_v, input logic [SET_W-1:0] aw_set, input logic [WAYS-1:0] aw,
      input logic f_v, input logic [SET_W-1:0] f_set, input logic [WAY_W-1:0] f_way,
      input logic f_ag, input logic f_bad);
    logic a, f, b, fl;
    fl = f_v && f_set == s && f_way == w;
    a  = (aw_v && aw_set == s) ? aw[w] : ag[w];
    f  = fl ? f_ag : fg[w];
    b  = fl ? f_bad : bd[w];
    return {a != f, b};
  endfunction

  // ---------------------------------------------------------------- state
  // Directory (g_dir below), each memory written from one place:
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
  //  - the tags (per sub-cache and way, in one memory with inc), which count only with the valid
  //    bit.  Every reference writes its slot's tag with its count (a hit's slot already holds the
  //    pass's tag), so the two need no separate write enables;
  //  - the reference count rc = inc - dec (modulo 2^RC_W) of a slot: the passes in the FIFO that
  //    read it.  inc counts at the commit (per sub-cache and way), dec at the head (likewise).  An
  //    allocation writes inc = dec + 1 (its own reference), so the pair is exact from the slot's
  //    first allocation since the reset on; a slot that is not live is unreferenced (free) whatever
  //    the two hold.  The passes release their references in the order they took them, so a
  //    pass's release sets dec to the inc its own reference made: the pass carries that value
  //    through the FIFO (pass_t.rc), and the release writes it without reading dec;
  //  - the pseudo-LRU bits of a set (per sub-cache).  The lookup uses them only when every way of
  //    the set is live (a way that is not live is free and invalid, so it is taken first), so each
  //    way has been allocated, and touched, since the reset; a touch writes every node on the
  //    way's path, so every node of the tree has been written since the reset.
  // (The state bits were flops written by both the commit and the fill, 3 x NSUB x SETS x WAYS
  // of them read through wide multiplexers; in LUT RAM each memory has one writer.)
  // The memories are read at the lookup's registered set (a_set, tex_cache_front), so a block RAM
  // takes that register's input as its read address; its read then misses the write of the same
  // edge, which Yosys's mapping forwards (the RAM is declared with an asynchronous read behind
  // the register, so the RTL's behaviour is that of the LUT RAM): the same words in the same
  // clocks with DIR_RAM "auto" (Yosys's choice: LUT RAM) or "block" (2 x NSUB x WAYS block RAMs,
  // 32 with the defaults).  The register's input is a read of the pass queue's registers, not
  // the pass selection (tex_cache_front), since the RAMs lie spread over the device
  // (docs/synthesis.md has the routes).
  logic              swp;          // the live bits are being cleared (after a reset; u_axi)
  logic [SET_W-1:0]  swp_set;      // the set cleared in this clock

  logic                   e_missed_q;  // an earlier pass of the request in the lookup missed

  // Request FIFO (one entry per pass).
  typedef struct packed {
    logic [NSUB-1:0]             used;  // sub-cache read by the pass
    logic [NSUB-1:0][SET_W-1:0]  set;
    logic [NSUB-1:0][WAY_W-1:0]  way;
    logic [3:0]                  tsel;  // texels served by the pass
    logic [NSUB-1:0][WIN_W-1:0]  win;   // the window each sub-cache reads
    logic [3:0][1:0]             tsub;  // their sub-cache
    logic [3:0][TOFF_W-1:0]      toff;  // their word in that window (0 .. WW)
    logic [NSUB-1:0][RC_W-1:0]   rc;    // each slot's inc after the pass's reference: the dec
                                        // its release writes (see "Directory" at the state)
    logic                        last;  // the request's last pass
  } pass_t;

  logic [FC_W-1:0]   fifo_cnt;     // passes in the FIFO (u_fifo)

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
  // MSHRs' lines and slots per sub-cache and MSHR (g_mshr).  These copies stay here, not in
  // tex_cache_assert.sv: the memories are declared per sub-cache and way inside generate blocks,
  // and the bind (one port connection per signal) can only name a signal of tex_cache's own scope;
  // the assigns into them (in g_dir and g_mshr below) are the other three blocks that remain.
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

  // ---------------------------------------------------------------- entry, passes, pass queue
  // (tex_cache_front) The request's passes, as the lookup's read stage (a_*) and decide stage
  // (b_valid, lk_*, e_*) take them.
  logic                       a_issue;     // the read stage has a pass
  logic [NSUB-1:0][SET_W-1:0] a_set;       // its sets (registered: the directory's read address)
  logic [NSUB-1:0][TAGB-1:0]  a_tag;       // its tags
  logic                       b_valid;     // the decide stage holds a pass
  logic [NSUB-1:0]            lk_v;        // the decide stage's pass, as the lookup uses it
  logic [NSUB-1:0][LA_W-1:0]  lk_la;
  logic [NSUB-1:0][SET_W-1:0] lk_set;
  logic [NSUB-1:0][TAGB-1:0]  lk_tag;
  logic [NSUB-1:0][WIN_W-1:0] lk_win;
  logic [3:0]                 e_sel;
  logic [3:0][1:0]            e_psub;
  logic [3:0][TOFF_W-1:0]     e_toff;
  logic                       e_last;
  logic                       e_fire;      // the decide stage's pass enters the FIFO

  tex_cache_front #(
    .ADDR_W(ADDR_W), .OFF_W(OFF_W), .SET_W(SET_W), .WW(WW), .PQ_DEPTH(PQ_DEPTH)
  ) u_front (
    .clk_i, .rst_ni, .swp_i(swp),
    .req_valid_i, .req_ready_o, .req_addr_i,
    .a_issue_o(a_issue), .a_set_o(a_set), .a_tag_o(a_tag),
    .b_valid_o(b_valid), .lk_v_o(lk_v), .lk_la_o(lk_la), .lk_set_o(lk_set), .lk_tag_o(lk_tag),
    .lk_win_o(lk_win), .e_sel_o(e_sel), .e_psub_o(e_psub), .e_toff_o(e_toff),
    .e_last_o(e_last), .e_fire_i(e_fire));

  // ---------------------------------------------------------------- lookup: tags, victims
  logic [NSUB-1:0]            lk_alloc, lk_blocked;
  logic [NSUB-1:0][WAY_W-1:0] lk_way;     // the hit way or the victim
  logic [NSUB-1:0][MIDX_W-1:0] lk_mshr;   // MSHR of a miss
  logic                       mshr_short; // not enough free MSHRs for the pass's misses
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
  pass_t                       e_pass;      // the pass as it enters the FIFO (request FIFO),
                                            // its rc the slots' counts before its references
  pass_t                       cm_pass_q;   // ... registered
  pass_t                       cm_pass;     // ... as it is written there: rc = cm_inc
  logic [NSUB-1:0]             cm_alloc_q;  // (its sub-caches, sets and ways: in cm_pass_q)
  logic [NSUB-1:0][TAGB-1:0]   cm_tag_q;
  logic [NSUB-1:0][LA_W-1:0]   cm_la_q;
  logic [NSUB-1:0][MIDX_W-1:0] cm_mshr_q;
  logic [NSUB-1:0][RC_W-1:0]   cm_inc;     // the slot's new reference-taken count
  logic [NSUB-1:0][PLRU_W-1:0] cm_plru_q;  // the set's new pseudo-LRU bits
  logic [NSUB-1:0][WAYS-1:0]   cm_ag_q;    // the set's new ag bits (written on an allocation)
  logic [NSUB-1:0][WAYS-1:0]   cm_live_q;  // ... and live bits

  // Read and decide stages (tex_cache_lookup): hit or miss per sub-cache, the way, the MSHRs.
  logic [NSUB-1:0][PLRU_W-1:0]         f_plru;  // the directory at the decided sets, forwarded
  logic [NSUB-1:0][WAYS-1:0]           f_ag, f_live, b_fg;
  logic [NSUB-1:0][WAYS-1:0][RC_W-1:0] f_inc, b_dec;

  tex_cache_lookup #(
    .WAYS(WAYS), .SET_W(SET_W), .TAGB(TAGB), .RC_W(RC_W), .MIDX_W(MIDX_W)
  ) u_lookup (
    .clk_i,
    .a_set_i(a_set), .a_tag_i(a_tag),
    .set_tag_i(set_tag), .set_inc_i(set_inc), .set_dec_i(set_dec), .set_plru_i(set_plru),
    .set_live_i(set_live), .set_ag_i(set_ag), .set_fg_i(set_fg), .set_bad_i(set_bad),
    .b_valid_i(b_valid), .lk_v_i(lk_v), .lk_set_i(lk_set), .lk_tag_i(lk_tag),
    .cm_valid_i(cm_valid_q), .cm_used_i(cm_pass_q.used), .cm_set_i(cm_pass_q.set),
    .cm_way_i(cm_pass_q.way), .cm_alloc_i(cm_alloc_q), .cm_tag_i(cm_tag_q), .cm_inc_i(cm_inc),
    .cm_plru_i(cm_plru_q), .cm_ag_i(cm_ag_q), .cm_live_i(cm_live_q),
    .free_idx_i(free_idx), .free_ok_i(free_ok),
    .lk_alloc_o(lk_alloc), .lk_blocked_o(lk_blocked), .lk_way_o(lk_way), .lk_mshr_o(lk_mshr),
    .mshr_short_o(mshr_short), .f_plru_o(f_plru), .f_ag_o(f_ag), .f_live_o(f_live),
    .f_inc_o(f_inc), .b_fg_o(b_fg), .b_dec_o(b_dec));

  // The free MSHRs are a queue of indices (u_free, in the MSHR section below), taken from its
  // head by the pass in the commit register (its misses' MSHRs leave the queue in its commit
  // clock, so no count of the deciding pass's misses reaches the queue's pointers): the deciding
  // pass's k-th miss takes entry head + (the commit register's MSHRs) + k, from registers; a
  // line's last beat puts its MSHR back at the tail (seen from the next clock).

  assign e_fire      = rst_ni && b_valid && (32'(fifo_cnt) + 32'(cm_valid_q) < FIFO_DEPTH)
                       && !(|lk_blocked) && !mshr_short;

  // ---------------------------------------------------------------- commit register
  // Loaded every clock (cm_valid_q says whether it holds a pass), so the lookup's outcome
  // drives no enable here; the writes it describes happen in the next clock.
  logic [2:0] cm_texel_hits_q;
  logic       cm_qhit_q;
  logic [2:0] e_texel_hits;
  // The slots' reference-taken counts before the pass's reference (e_ref) and after it
  // (cm_inc = + 1, a clock later: the increment's carry chain is not behind the way's choice).
  logic [NSUB-1:0][RC_W-1:0] e_ref;

  always_comb begin
    for (int c = 0; c < NSUB; c++) begin
      e_ref[c]  = lk_alloc[c] ? b_dec[c][lk_way[c]] : f_inc[c][lk_way[c]];
      cm_inc[c] = cm_pass_q.rc[c] + RC_W'(1);
    end
    cm_pass    = cm_pass_q;
    cm_pass.rc = cm_inc;
  end

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
      cm_ag_q[c]   <= with_way(f_ag[c], lk_way[c], !b_fg[c][lk_way[c]]);
      cm_live_q[c] <= with_way(f_live[c], lk_way[c], 1'b1);
    end
    cm_pass_q       <= e_pass;
    cm_texel_hits_q <= e_texel_hits;
    cm_qhit_q       <= e_last && !e_missed_q && !(|lk_alloc);
  end
  always_ff @(posedge clk_i) begin
    if (!rst_ni)     e_missed_q <= 1'b0;
    else if (e_fire) e_missed_q <= !e_last && (e_missed_q || (|lk_alloc));
  end

  logic req_fire;
  assign req_fire = req_valid_i && req_ready_o;

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
    e_pass.rc   = e_ref;
    e_pass.last = e_last;
  end

  // The FIFO's storage is block RAM, read only through its registered port (two entries behind
  // the head after this clock's pop; below); as LUT RAM it took 128 16x4 RAMs.
  pass_t rd_eff;  // entry head + 2 after the last clock's pop (valid with 3 or more entries)

  circ_queue #(
    .WIDTH($bits(pass_t)), .DEPTH(FIFO_DEPTH), .NPUSH(1), .NPOP(1), .ASYNC_RD(1'b0), .PEEK(2),
    .RAM_STYLE("block")
  ) u_fifo (
    .clk_i, .rst_ni, .push_i(cm_valid_q), .wr_i(cm_valid_q), .wdata_i(cm_pass),
    .pop_n_i(h_pop), .rdata_o(), .peek_o(rd_eff), .count_o(fifo_cnt));

  // ---------------------------------------------------------------- head: wait, pop, read
  logic [NSUB-1:0] hd_err;
  logic [NSUB-1:0] hd_pend, hd_bad;  // the head's slot per sub-cache: pending, bad (g_dir)
  // The pop decides from flip-flops only: hd_pend and hd_bad are registers loaded one clock
  // ahead with the state of the slots of the pass that is head in the next clock (g_dir reads
  // it at the sets of nx_q and cm_pass, with this clock's directory writes applied; for hd_q
  // it applies the fill to the registers themselves), so no LUT RAM read lies between the head
  // register and the FIFO's pointers.  The next head: nx_q (a pop with two or more entries),
  // cm_pass (a pop with one, or an empty FIFO), else hd_q.
  logic            hs_nx, hs_cm;     // the next head is nx_q, cm_pass (else hd_q)

  // The head entry hd_q (= the FIFO's head while it holds a pass) and the one behind it, nx_q
  // (= the entry after the head while it holds two), are registers, so the head's readiness (its
  // lines present) and the pop start from flip-flops, not from the block RAM's output (4.3 ns
  // clock-to-out on the ECP5).  The block RAM is read every clock two entries behind the head
  // after this clock's pop (u_fifo's peek port, rd_eff), which refills nx_q at a pop; a pass
  // entering as the first or second goes straight to its register, and one written at the
  // address read in the same clock (the read sees the old word) is taken from a copy of the
  // commit register (in u_fifo).  So one pop per clock, from registers.
  pass_t           hd_q, nx_q;
  pass_t           hd_pop_d, hd_hold_d, nx_pop_d, nx_hold_d;

  // the next head and next-behind-head with and without a pop (from registers), then the pop
  // picks
  always_comb begin
    hd_pop_d  = (fifo_cnt >= FC_W'(2)) ? nx_q : cm_pass;      // entry rp + 1
    nx_pop_d  = (fifo_cnt >= FC_W'(3)) ? rd_eff : cm_pass;    // entry rp + 2
    hd_hold_d = (fifo_cnt == '0) ? cm_pass : hd_q;            // entry rp
    nx_hold_d = (fifo_cnt == FC_W'(1)) ? cm_pass : nx_q;       // entry rp + 1
  end

  always_ff @(posedge clk_i) begin
    hd_q <= h_pop ? hd_pop_d : hd_hold_d;
    nx_q <= h_pop ? nx_pop_d : nx_hold_d;
  end

  assign hs_nx = h_pop && fifo_cnt >= FC_W'(2);
  assign hs_cm = h_pop ? fifo_cnt < FC_W'(2) : fifo_cnt == '0;

  always_comb begin
    h_ready = (fifo_cnt != '0);
    for (int c = 0; c < NSUB; c++) begin
      // (the head's slots are live: allocated by this pass or hit as valid by it)
      if (hd_q.used[c] && hd_pend[c]) h_ready = 1'b0;
      hd_err[c] = hd_q.used[c] && !hd_pend[c] && hd_bad[c];
    end
  end

  logic out_room;  // the output buffer has room for the head pass's answer (u_data)
  assign h_pop = rst_ni && h_ready && out_room;

  // ---------------------------------------------------------------- R channel
  logic [MIDX_W-1:0]  r_idx;
  logic               r_cur, r_ours, r_acc, r_last_beat;
  logic [LA_W-1:0]   r_la;
  logic [1:0]        fill_sub;
  logic [SET_W-1:0]  fill_set;
  logic [WAY_W-1:0]  fill_way;
  logic [BEAT_W-1:0] r_beat;       // the beat's index in the line
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

  // ---------------------------------------------------------------- data RAMs, answers
  // (tex_cache_data) The head's windows are read every clock; the answer is selected two clocks
  // after a pop, merged with the request's earlier passes and buffered for the response stream.
  tex_cache_data #(
    .DATA_W(DATA_W), .TAG_W(TAG_W), .SETS(SETS), .WAYS(WAYS), .WW(WW), .NWIN(NWIN),
    .BEAT_W(BEAT_W), .OUT_DEPTH(OUT_DEPTH), .TQ_DEPTH(TQ_DEPTH)
  ) u_data (
    .clk_i, .rst_ni,
    .tq_push_i(req_fire), .tq_tag_i(req_tag_i),
    .w_acc_i(w_acc_q), .w_sub_i(w_sub_q), .w_set_i(w_set_q), .w_way_i(w_way_q),
    .w_beat_i(w_beat_q), .w_data_i(w_data_q),
    .hd_set_i(hd_q.set), .hd_way_i(hd_q.way), .hd_win_i(hd_q.win), .hd_tsel_i(hd_q.tsel),
    .hd_tsub_i(hd_q.tsub), .hd_toff_i(hd_q.toff), .hd_last_i(hd_q.last),
    .hd_err_i(|hd_err), .h_pop_i(h_pop), .out_room_o(out_room),
    .rsp_valid_o, .rsp_ready_i, .rsp_texel_o, .rsp_err_o, .rsp_tag_o);

  // ---------------------------------------------------------------- directory updates
  // The RAM part (see "Directory" at the state).  Per sub-cache: the commit touches the
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
    logic [WAYS-1:0]   fl_ag, fl_fg, fl_bad;
    logic [1:0]        sn_hd, sn_nx, sn_cm;  // {pending, bad} of the candidates' slots next

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
    assign set_plru[c] = plru_mem[a_set[c]];
    assign set_live[c] = live_mem[a_set[c]];
    assign set_ag[c]   = ag_mem[a_set[c]];
    assign set_fg[c]   = fg_mem[a_set[c]];
    assign set_bad[c]  = bad_mem[a_set[c]];
    assign fl_ag       = ag_mem[w_set_q];
    assign fl_fg       = fg_mem[w_set_q];
    assign fl_bad      = bad_mem[w_set_q];
    // the next head's slot (hd_pend, hd_bad: see "head").  The head held: its slot is
    // referenced by its pass, so no allocation takes it and only the slot's own fill changes
    // it (fg = ag: not pending; bad from the fill), so the registers are updated in place
    // rather than read again at hd_q's set (three LUT RAM read ports fewer per sub-cache;
    // tex_cache_assert's hd_state_ok checks them against the memories).  The other
    // candidates are read at their sets.
    assign sn_hd = (fill && w_set_q == hd_q.set[c] && w_way_q == hd_q.way[c])
                   ? {1'b0, w_bad_q} : {hd_pend[c], hd_bad[c]};
    assign sn_nx = slot_next(ag_mem[nx_q.set[c]], fg_mem[nx_q.set[c]], bad_mem[nx_q.set[c]],
                             nx_q.set[c], nx_q.way[c], take && cm_alloc_q[c], cm_pass_q.set[c],
                             cm_ag_q[c], fill, w_set_q, w_way_q, fl_ag[w_way_q], w_bad_q);
    assign sn_cm = slot_next(ag_mem[cm_pass_q.set[c]], fg_mem[cm_pass_q.set[c]],
                             bad_mem[cm_pass_q.set[c]], cm_pass_q.set[c], cm_pass_q.way[c],
                             take && cm_alloc_q[c], cm_pass_q.set[c], cm_ag_q[c], fill, w_set_q,
                             w_way_q, fl_ag[w_way_q], w_bad_q);
    always_ff @(posedge clk_i) begin
      {hd_pend[c], hd_bad[c]} <= hs_nx ? sn_nx : (hs_cm ? sn_cm : sn_hd);
    end

`ifndef SYNTHESIS  // the memories' copies for tex_cache_assert (see vw_live)
    assign vw_live[c] = live_mem;
    assign vw_ag[c]   = ag_mem;
    assign vw_fg[c]   = fg_mem;
    assign vw_bad[c]  = bad_mem;
`endif

    for (genvar w = 0; w < WAYS; w++) begin : g_way
      (* ram_style = DIR_RAM *) logic [TAGB+RC_W-1:0] ti_mem  [SETS];  // {tag, inc}
      (* ram_style = DIR_RAM *) logic [RC_W-1:0]      dec_mem [SETS];

      // (the tag is written with every reference: a hit's slot holds the pass's tag already,
      // tex_cache_assert's commit_hit_tag, so tag and count share one write and one memory)
      always_ff @(posedge clk_i) begin
        if (take && cm_pass_q.way[c] == WAY_W'(w))
          ti_mem[cm_pass_q.set[c]] <= {cm_tag_q[c], cm_inc[c]};
        if (give && hd_q.way[c] == WAY_W'(w)) dec_mem[hd_q.set[c]] <= hd_q.rc[c];
      end
      assign {set_tag[c][w], set_inc[c][w]} = ti_mem[a_set[c]];
      assign set_dec[c][w] = dec_mem[a_set[c]];

`ifndef SYNTHESIS  // the memories' copies for tex_cache_assert (see vw_live; read word by
                   // word: a memory with a ram_style attribute cannot be copied whole in the
                   // formal front end)
      for (genvar s = 0; s < SETS; s++) begin : g_vw
        assign {vw_tag[c][w][s], vw_inc[c][w][s]} = ti_mem[s];
        assign vw_dec[c][w][s] = dec_mem[s];
      end
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
`ifndef SYNTHESIS  // the memories' copies for tex_cache_assert (see vw_live)
    assign vw_la[c] = la_mem;
    assign vw_sw[c] = sw_mem;
`endif
  end

  // Free MSHRs, a queue of indices: all of them after a reset; the pass in the commit register
  // takes one per miss from the head (they are busy from that clock on), a line's last beat
  // returns its MSHR at the tail (one per clock at most).  The deciding pass's misses take the
  // entries after the commit register's (head + cm_n_q + k): FL_RD entries are read.
  localparam int unsigned FL_RD = (2 * NSUB < MSHRS) ? 2 * NSUB : MSHRS;
  localparam int unsigned FLP_W = $clog2(FL_RD + 1);
  logic [QCNT_W-1:0]             fl_cnt;  // free MSHRs, the commit register's among them
  logic [FL_RD-1:0][MIDX_W-1:0]  fl_rd;   // entries head .. head + FL_RD - 1
  logic [2:0]                    cm_n_q;  // MSHRs the commit register's pass takes ($countones
                                          // of cm_new, registered with it)

  always_ff @(posedge clk_i) begin
    if (!rst_ni) cm_n_q <= '0;
    else         cm_n_q <= e_fire ? 3'($countones(lk_alloc)) : 3'd0;
  end

  circ_queue #(
    .WIDTH(MIDX_W), .DEPTH(MSHRS), .NPUSH(1), .NPOP(FL_RD), .INIT_SEQ(1'b1)
  ) u_free (
    .clk_i, .rst_ni, .push_i(fill_v), .wr_i(fill_v), .wdata_i(r_idx),
    .pop_n_i(FLP_W'(cm_n_q)), .rdata_o(fl_rd), .peek_o(), .count_o(fl_cnt));

  // (from registers: the lookup's short-of-MSHRs test takes free_ok as a thermometer)
  always_comb begin
    for (int k = 0; k < NSUB; k++) begin
      free_ok[k]  = 32'(fl_cnt) > 32'(cm_n_q) + k;
      // (an entry past FL_RD is never free_ok: cm_n_q + k < fl_cnt <= MSHRS)
      free_idx[k] = '0;
      for (int j = 0; j < FL_RD; j++) if (32'(cm_n_q) + k == j) free_idx[k] = fl_rd[j];
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

  // w_la_q is read by the bound checks only.
  logic unused;
  assign unused = ^w_la_q;

endmodule
