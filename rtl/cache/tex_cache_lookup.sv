// SPDX-License-Identifier: Apache-2.0
// tex_cache_lookup: the texture cache's two-clock directory lookup (tex_cache.sv, "Pipeline"
// clocks 2 and 3), per sub-cache: the read stage compares the directory's words at the pass's
// sets (set_*_i, read at a_set_i) with the pass's tags, with the commit register's writes
// (cm_*_i, not yet done) forwarded; the decide stage, from registers, forwards the commit
// register once more and decides hit or miss, the hit way or the victim (an unreferenced
// invalid way first, else tree pseudo-LRU among the unreferenced ways), and the MSHRs of the
// misses (the k-th miss of the pass takes free_idx_i[k]).  lk_blocked_o: a miss finds every way
// referenced; mshr_short_o: too few free MSHRs.  f_*_o and b_*_o: the directory at the decided
// slots as the commit register needs it.
module tex_cache_lookup #(
  parameter int unsigned WAYS   = 4,   // ways per set (power of two, >= 2)
  parameter int unsigned SET_W  = 5,   // log2 sets
  parameter int unsigned TAGB   = 21,  // stored tag bits
  parameter int unsigned RC_W   = 7,   // reference count width
  parameter int unsigned MIDX_W = 4,   // MSHR index width
  // derived
  parameter int unsigned WAY_W  = $clog2(WAYS),
  parameter int unsigned PLRU_W = WAYS - 1
) (
  input  logic                                 clk_i,
  // the read stage's pass: its sets (the directory's read address) and tags
  input  logic [3:0][SET_W-1:0]                a_set_i,
  input  logic [3:0][TAGB-1:0]                 a_tag_i,
  // the directory at a_set_i (tex_cache's LUT RAM)
  input  logic [3:0][WAYS-1:0][TAGB-1:0]       set_tag_i,
  input  logic [3:0][WAYS-1:0][RC_W-1:0]       set_inc_i,
  input  logic [3:0][WAYS-1:0][RC_W-1:0]       set_dec_i,
  input  logic [3:0][PLRU_W-1:0]               set_plru_i,
  input  logic [3:0][WAYS-1:0]                 set_live_i,
  input  logic [3:0][WAYS-1:0]                 set_ag_i,
  input  logic [3:0][WAYS-1:0]                 set_fg_i,
  input  logic [3:0][WAYS-1:0]                 set_bad_i,
  // the decide stage's pass (if b_valid_i): its sub-caches, sets and tags
  input  logic                                 b_valid_i,
  input  logic [3:0]                           lk_v_i,
  input  logic [3:0][SET_W-1:0]                lk_set_i,
  input  logic [3:0][TAGB-1:0]                 lk_tag_i,
  // the commit register (the pass that entered the FIFO in the clock before): its writes
  input  logic                                 cm_valid_i,
  input  logic [3:0]                           cm_used_i,
  input  logic [3:0][SET_W-1:0]                cm_set_i,
  input  logic [3:0][WAY_W-1:0]                cm_way_i,
  input  logic [3:0]                           cm_alloc_i,
  input  logic [3:0][TAGB-1:0]                 cm_tag_i,
  input  logic [3:0][RC_W-1:0]                 cm_inc_i,
  input  logic [3:0][PLRU_W-1:0]               cm_plru_i,
  input  logic [3:0][WAYS-1:0]                 cm_ag_i,
  input  logic [3:0][WAYS-1:0]                 cm_live_i,
  // the free MSHRs, in the order the misses take them
  input  logic [3:0][MIDX_W-1:0]               free_idx_i,
  input  logic [3:0]                           free_ok_i,
  // the decision
  output logic [3:0]                           lk_alloc_o,    // a miss (an allocation)
  output logic [3:0]                           lk_blocked_o,  // a miss with no free way
  output logic [3:0][WAY_W-1:0]                lk_way_o,      // the hit way or the victim
  output logic [3:0][MIDX_W-1:0]               lk_mshr_o,     // the MSHR of a miss
  output logic                                 mshr_short_o,  // too few free MSHRs
  // the directory at the decided set, as the commit register writes it
  output logic [3:0][PLRU_W-1:0]               f_plru_o,
  output logic [3:0][WAYS-1:0]                 f_ag_o,
  output logic [3:0][WAYS-1:0]                 f_live_o,
  output logic [3:0][WAYS-1:0][RC_W-1:0]       f_inc_o,
  output logic [3:0][WAYS-1:0]                 b_fg_o,
  output logic [3:0][WAYS-1:0][RC_W-1:0]       b_dec_o
);

  localparam int unsigned NSUB = 4;  // sub-caches

  if (WAYS < 2 || (1 << WAY_W) != WAYS || PLRU_W != WAYS - 1) begin : g_check_ways
    $error("tex_cache_lookup: WAYS must be a power of two >= 2 (WAY_W, PLRU_W derived)");
  end

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
    logic                fw, fw_alloc, live, done_bad, cm_hit;
    for (int c = 0; c < NSUB; c++) begin
      fw        = cm_valid_i && cm_used_i[c] && cm_set_i[c] == a_set_i[c];
      // (the forwarded tag compared once per sub-cache, not multiplexed into every way's compare)
      cm_hit    = cm_tag_i[c] == a_tag_i[c];
      a_plru[c] = fw ? cm_plru_i[c] : set_plru_i[c];
      a_ag[c]   = (fw && cm_alloc_i[c]) ? cm_ag_i[c] : set_ag_i[c];
      a_live[c] = (fw && cm_alloc_i[c]) ? cm_live_i[c] : set_live_i[c];
      for (int w = 0; w < WAYS; w++) begin
        fw_alloc     = fw && cm_alloc_i[c] && cm_way_i[c] == WAY_W'(w);
        live         = set_live_i[c][w];
        done_bad     = set_ag_i[c][w] == set_fg_i[c][w] && set_bad_i[c][w];  // not pending, bad
        a_vld[c][w]  = fw_alloc || (live && !done_bad);
        a_pnd[c][w]  = fw_alloc || (live && set_ag_i[c][w] != set_fg_i[c][w]);
        a_err[c][w]  = !fw_alloc && live && done_bad;
        // (a hit when valid too: in the decide stage)
        a_hit[c][w]  = fw_alloc ? cm_hit : set_tag_i[c][w] == a_tag_i[c];
        a_inc[c][w]  = (fw && cm_way_i[c] == WAY_W'(w)) ? cm_inc_i[c] : set_inc_i[c][w];
        a_idle[c][w] = a_inc[c][w] == set_dec_i[c][w];
      end
      a_seteq[c] = b_valid_i && lk_v_i[c] && lk_set_i[c] == a_set_i[c];
      a_tageq[c] = lk_tag_i[c] == a_tag_i[c];
    end
  end

  // Decide stage: the read stage's results, registered every clock (b_valid_i says whether they
  // belong to a pass), with the commit register's writes forwarded once more.
  logic [NSUB-1:0][WAYS-1:0]           b_vld_q, b_err_q, b_pnd_q, b_hit_q, b_idle_q;
  logic [NSUB-1:0][WAYS-1:0][RC_W-1:0] b_inc_q;
  logic [NSUB-1:0][PLRU_W-1:0]         b_plru_q;
  logic [NSUB-1:0][WAYS-1:0]           b_ag_q, b_live_q;
  logic [NSUB-1:0]                     b_seteq_q, b_tageq_q;

  always_ff @(posedge clk_i) begin
    b_vld_q   <= a_vld;
    b_err_q   <= a_err;
    b_pnd_q   <= a_pnd;
    b_hit_q   <= a_hit;
    b_idle_q  <= a_idle;
    b_fg_o    <= set_fg_i;
    b_inc_q   <= a_inc;
    b_dec_o   <= set_dec_i;
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

  always_comb begin
    logic fw, fw_way, fw_alloc;
    for (int c = 0; c < NSUB; c++) begin
      // (no cm_valid_i: b_seteq_q holds only if this stage held a pass in the clock before, and
      // that pass entered the FIFO, or the replay would have dropped this one)
      fw        = b_seteq_q[c];
      f_plru_o[c] = fw ? cm_plru_i[c] : b_plru_q[c];
      f_ag_o[c]   = (fw && cm_alloc_i[c]) ? cm_ag_i[c] : b_ag_q[c];
      f_live_o[c] = (fw && cm_alloc_i[c]) ? cm_live_i[c] : b_live_q[c];
      for (int w = 0; w < WAYS; w++) begin
        fw_way       = fw && cm_way_i[c] == WAY_W'(w);
        fw_alloc     = fw_way && cm_alloc_i[c];
        f_vld[c][w]  = fw_alloc || b_vld_q[c][w];
        f_pnd[c][w]  = fw_alloc || b_pnd_q[c][w];
        f_err[c][w]  = !fw_alloc && b_err_q[c][w];
        f_hit[c][w]  = fw_alloc ? b_tageq_q[c] : b_vld_q[c][w] && b_hit_q[c][w];
        f_inc_o[c][w]  = fw_way ? cm_inc_i[c] : b_inc_q[c][w];
        // (the committing pass's slot is referenced by it: never idle; tex_cache_assert checks
        // that its count says so, fw_idle)
        f_idle[c][w] = !fw_way && b_idle_q[c][w];
      end
    end
  end

  logic [NSUB-1:0][WAYS-1:0] way_hit, way_free;

  always_comb begin
    logic [2:0] n_before;  // misses of the pass in the sub-caches before
    for (int c = 0; c < NSUB; c++) begin
      lk_way_o[c] = '0;
      for (int w = 0; w < WAYS; w++) begin
        way_hit[c][w]  = f_hit[c][w];
        way_free[c][w] = !(f_vld[c][w] || f_err[c][w]) || f_idle[c][w];
        if (way_hit[c][w]) lk_way_o[c] = WAY_W'(w);
      end
      lk_alloc_o[c]   = lk_v_i[c] && !(|way_hit[c]);
      lk_blocked_o[c] = lk_alloc_o[c] && !(|way_free[c]);
      if (!(|way_hit[c])) begin
        // an unreferenced invalid way first (the lowest), else pseudo-LRU among the unreferenced
        if (|(way_free[c] & ~f_vld[c])) begin
          for (int w = WAYS - 1; w >= 0; w--) begin
            if (way_free[c][w] && !f_vld[c][w]) lk_way_o[c] = WAY_W'(w);
          end
        end else begin
          lk_way_o[c] = plru_pick(f_plru_o[c], way_free[c]);
        end
      end
    end
    // MSHRs for the misses, in sub-cache order: the k-th miss of the pass takes the k-th free
    // MSHR (free_idx_i, from registers)
    mshr_short_o = 1'b0;
    lk_mshr_o    = '0;
    for (int c = 0; c < NSUB; c++) begin
      n_before = '0;
      for (int d = 0; d < c; d++) n_before = n_before + 3'(lk_alloc_o[d]);
      lk_mshr_o[c] = free_idx_i[n_before[1:0]];
      if (lk_alloc_o[c] && !free_ok_i[n_before[1:0]]) mshr_short_o = 1'b1;
    end
  end

`ifndef SYNTHESIS
  // The committing pass's slot as the forwarded count would judge it: idle (inc == dec), which
  // its own reference rules out (the decision takes it as referenced without the compare).
  /* verilator lint_off UNUSEDSIGNAL */  // (read by the bound checks only)
  logic [NSUB-1:0] fw_idle;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    for (int c = 0; c < NSUB; c++) begin
      fw_idle[c] = b_seteq_q[c] && cm_inc_i[c] == b_dec_o[c][cm_way_i[c]];
    end
  end
`endif

  // f_pnd (a slot pending at the decision) is read by the bound checks' coverage only.
  logic unused;
  assign unused = ^f_pnd;

endmodule
