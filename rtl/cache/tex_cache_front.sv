// SPDX-License-Identifier: Apache-2.0
// tex_cache_front: the texture cache's request side (tex_cache.sv, "Pipeline" clocks 0 .. 4):
// the entry register that accepts a quad (with the row bits and which texels may share a read,
// computed at the input), the pass selection that splits it into passes (one line and window
// per sub-cache), and the pass queue from which the two-clock lookup (tex_cache_lookup) reads
// the passes: a_* is the pass of the read stage (its sets a_set_o, from a register of their own,
// its tags), b_valid_o / lk_* / e_* the pass of the decide stage, which leaves the queue when it
// enters the FIFO (e_fire_i) and is otherwise read again (a replay).  See tex_cache.sv for the
// organisation (sub-caches, row bits, windows) and the request stream's rules.  The requests'
// side-band tags do not pass here: tex_cache_data queues them apart (see "request tags" there).
module tex_cache_front #(
  parameter int unsigned ADDR_W   = 32,  // byte address width
  parameter int unsigned OFF_W    = 5,   // log2 line bytes
  parameter int unsigned SET_W    = 5,   // log2 sets
  parameter int unsigned WW       = 2,   // words per data window (a power of two)
  parameter int unsigned PQ_DEPTH = 4,   // pass queue entries (4: binary pointers of 3 bits)
  // derived (tex_cache's values)
  parameter int unsigned LA_W     = ADDR_W - OFF_W,           // line address width
  parameter int unsigned TAGB     = LA_W - 1 - SET_W,         // stored tag bits
  parameter int unsigned WSEL_W   = OFF_W - 2,                // texel within a line
  parameter int unsigned WB       = $clog2(WW),               // log2 words per window
  parameter int unsigned NWIN     = (1 << WSEL_W) / WW,       // windows per line
  parameter int unsigned WIN_W    = (NWIN > 1) ? $clog2(NWIN) : 1,
  parameter int unsigned TOFF_W   = WB + 1                    // word in a read window, 0 .. WW
) (
  input  logic                            clk_i,
  input  logic                            rst_ni,
  input  logic                            swp_i,        // the directory's reset sweep runs
  // requests
  input  logic                            req_valid_i,
  output logic                            req_ready_o,
  input  logic [3:0][ADDR_W-1:0]          req_addr_i,
  // the lookup's read stage: its pass (if a_issue_o), that pass's sets (registered) and tags
  output logic                            a_issue_o,
  output logic [3:0][SET_W-1:0]           a_set_o,
  output logic [3:0][TAGB-1:0]            a_tag_o,
  // the lookup's decide stage: its pass (if b_valid_o)
  output logic                            b_valid_o,
  output logic [3:0]                      lk_v_o,       // sub-caches the pass reads
  output logic [3:0][LA_W-1:0]            lk_la_o,      // their lines,
  output logic [3:0][SET_W-1:0]           lk_set_o,     // ... sets,
  output logic [3:0][TAGB-1:0]            lk_tag_o,     // ... tags
  output logic [3:0][WIN_W-1:0]           lk_win_o,     // ... and windows
  output logic [3:0]                      e_sel_o,      // texels of the pass,
  output logic [3:0][1:0]                 e_psub_o,     // ... their sub-caches
  output logic [3:0][TOFF_W-1:0]          e_toff_o,     // ... and words in the windows
  output logic                            e_last_o,     // the request's last pass
  input  logic                            e_fire_i      // the decide stage's pass enters the FIFO
);

  localparam int unsigned NSUB = 4;  // sub-caches

  if (LA_W != ADDR_W - OFF_W || TAGB != LA_W - 1 - SET_W || WSEL_W != OFF_W - 2
      || WB != $clog2(WW) || (1 << WB) != WW || NWIN != (1 << WSEL_W) / WW
      || WIN_W != ((NWIN > 1) ? $clog2(NWIN) : 1) || TOFF_W != WB + 1) begin : g_check_derived
    $error("tex_cache_front: the derived parameters must keep their defaults");
  end
  if (PQ_DEPTH != 4) begin : g_check_pq
    $error("tex_cache_front: PQ_DEPTH must be 4");
  end

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

  // The line of set s and tag g in a sub-cache of parity par (set_of's inverse given the tag:
  // the low set field is the set XOR the tag's low bits; the line's bit 0 is the parity), 0 when
  // the sub-cache is unused (v = 0, with s and g 0), as the selection writes it.  The pass queue
  // keeps sets and tags only, not the lines besides.
  function automatic logic [LA_W-1:0] la_of(input logic v, input logic par,
                                            input logic [SET_W-1:0] s,
                                            input logic [TAGB-1:0] g);
    logic [LA_W-1:0] la;
    la = '0;
    la[0] = v && par;
    for (int unsigned i = 0; i < SET_W; i++) begin
      la[1 + i] = s[i];
      if (i < TAGB) la[1 + i] = s[i] ^ g[i];
    end
    la[LA_W-1 -: TAGB] = g;
    return la;
  endfunction

  // Entry register (the request being looked up).
  logic                   s0_valid_q;
  logic [3:0][ADDR_W-1:0] s0_addr_q;
  logic [3:0]             s0_todo_q;   // texels not yet sent in a pass
  logic [3:0]             s0_row_q;    // row bit per texel
  logic [3:0][3:0]        s0_join_q;   // [u][t], u < t: texel t may share texel u's read (below)

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
  // The passes selected and not yet in the FIFO: a queue of PQ_DEPTH entries (pq_q, LUT RAM:
  // one write port, read asynchronously for the read stage's pass; their sets in flip-flops,
  // pq_set_q, below), written at pq_wp_q.  The lookup takes two clocks, a read stage and a decide stage (below):
  // pq_ip_q is the next entry the read stage takes, pq_rp_q the oldest entry, the pass in the
  // decide stage when it holds one (b_valid_q), freed when that pass enters the FIFO (e_fire_i).
  // When the decide stage cannot let its pass go (the FIFO is full, an MSHR is missing, every way
  // of a missed set is referenced), it drops it and the pass behind it in the read stage, and
  // pq_ip_q goes back to pq_rp_q: the pass is read again from the directory as it then is (a
  // replay: two clocks per retry, and no outcome of the decision steers more than the pointers
  // and the stage valid bits).  A pass moves in while the queue has a free entry, judged from the
  // pointers alone, so neither the selection nor req_ready_o waits on the lookup's outcome in the
  // same clock.  Four entries keep one pass per clock going (one deciding, one being read, one
  // whose sets are being loaded into the read stage's set register, one being selected), and
  // make the pointers plain binary counters.
  typedef struct packed {
    logic [NSUB-1:0]            v;     // sub-caches the pass reads
    logic [NSUB-1:0][SET_W-1:0] set;   // their lines' sets
    logic [NSUB-1:0][TAGB-1:0]  tag;   // ... and tags, the line address bits above the low set
                                       // field (the line: la_of)
    logic [NSUB-1:0][WIN_W-1:0] win;
    logic [3:0]                 sel;   // texels of the pass
    logic [3:0][1:0]            psub;  // their sub-caches
    logic [3:0][WSEL_W-1:0]     word;  // their words in the line
    logic                       last;  // the request's last pass
  } pq_t;

  pq_t                        pq_q [PQ_DEPTH];
  // The entries' sets are in flip-flops (pq_set_q, a packed array, so not a memory; pq_q's set
  // fields are not read): read from the queue's LUT RAM, a_set_q would become that RAM's
  // registered read port in synthesis, and a directory in block RAM would find no register to
  // take as its read address.
  logic [PQ_DEPTH-1:0][NSUB-1:0][SET_W-1:0] pq_set_q;
  logic [2:0]                 pq_wp_q, pq_ip_q, pq_rp_q;  // (one bit above the index: full / empty)
  pq_t                        pq_d;      // the selected pass as it is written
  pq_t                        a_pass;    // the pass the read stage takes (pq_q[pq_ip_q])
  logic                       b_valid_q; // the decide stage holds a pass (pq_q[pq_rp_q])
  pq_t                        b_pass_q;
  logic                       replay;    // the decide stage drops its pass to read it again
  logic                       replay_q;  // ... in the clock before: the read stage waits
  logic                       p_load;    // the next pass moves into the queue
  logic                       set_ok_q;  // a_set_q holds pq_ip_q's sets (below)

  assign p_load  = rst_ni && s0_valid_q && (pq_wp_q - pq_rp_q) != 3'(PQ_DEPTH);
  assign a_issue_o = pq_ip_q != pq_wp_q && !replay_q && set_ok_q;
  assign a_tag_o   = a_pass.tag;
  // entry k of the queue: its word, with the sets from their flip-flops
  function automatic pq_t pq_entry(input logic [1:0] k);
    pq_t e;
    e     = pq_q[k];
    e.set = pq_set_q[k];
    return e;
  endfunction
  assign a_pass = pq_entry(pq_ip_q[1:0]);
  /* verilator lint_off UNUSEDSIGNAL */  // (read by the bound checks only)
  pq_t pq_oldest;                        // the queue's oldest entry (decide_is_oldest)
  /* verilator lint_on UNUSEDSIGNAL */
  assign pq_oldest = pq_entry(pq_rp_q[1:0]);
  assign replay  = b_valid_q && !e_fire_i;

  // The read stage's sets (the directory's read addresses) come from a register of their own,
  // a_set_q = a_pass.set while a_issue_o, loaded with the entry the read stage takes next: the
  // one after pq_ip_q, or pq_ip_q again.  The lookup's decision does not choose between them: a
  // replay moves pq_ip_q back to the oldest entry and the read stage waits one clock
  // (replay_q), in which a_set_q is loaded with that entry's sets.  So the register's input,
  // which a directory in block RAM takes as its read address (tex_cache DIR_RAM), does not wait
  // on the decision; a replay costs the clock of the wait.
  // The register loads from the queue's entries only (written in an earlier clock), not from the
  // selection (pq_d) as the entry is written, and set_ok_q says it holds pq_ip_q's sets: a pass
  // that enters an empty queue is read two clocks after its selection, not one, and the
  // register's input is two selects of the queue's registers, so the selection's logic ends at
  // the queue's write port (a directory in block RAM takes the register's input as its read
  // address, and its RAMs lie spread over the device: tex_cache DIR_RAM).
  logic [NSUB-1:0][SET_W-1:0] a_set_q, set_next;
  logic [2:0]                 set_ent;   // the entry a_set_q is loaded with
  always_comb begin
    set_ent  = a_issue_o ? pq_ip_q + 3'd1 : pq_ip_q;
    set_next = pq_set_q[set_ent[1:0]];
  end
  always_ff @(posedge clk_i) begin
    a_set_q <= set_next;
    set_ok_q <= rst_ni && set_ent != pq_wp_q;
    if (p_load) pq_set_q[pq_wp_q[1:0]] <= pq_d.set;
  end

  always_comb begin
    pq_d.v    = sl_v;
    for (int c = 0; c < NSUB; c++) begin
      pq_d.set[c] = set_of(sl_la[c]);
      pq_d.tag[c] = sl_la[c][LA_W-1 -: TAGB];
    end
    pq_d.win  = sl_win;
    pq_d.sel  = sl_sel;
    pq_d.psub = e_sub;
    pq_d.word = e_word;
    pq_d.last = sl_last;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      pq_wp_q   <= '0;
      pq_ip_q   <= '0;
      pq_rp_q   <= '0;
      b_valid_q <= 1'b0;
      replay_q  <= 1'b0;
    end else begin
      if (p_load) pq_wp_q <= pq_wp_q + 3'd1;
      if (e_fire_i) pq_rp_q <= pq_rp_q + 3'd1;
      if (replay)       pq_ip_q <= pq_rp_q;  // (pq_rp_q does not move: no e_fire_i)
      else if (a_issue_o) pq_ip_q <= pq_ip_q + 3'd1;
      b_valid_q <= a_issue_o && !replay;
      replay_q  <= replay;
    end
    if (p_load) pq_q[pq_wp_q[1:0]] <= pq_d;
    b_pass_q <= a_pass;
  end

  always_comb begin
    lk_v_o   = b_pass_q.v;
    for (int c = 0; c < NSUB; c++) lk_la_o[c] = la_of(b_pass_q.v[c], c % 2 == 1,
                                                       b_pass_q.set[c], b_pass_q.tag[c]);
    lk_set_o = b_pass_q.set;
    lk_tag_o = b_pass_q.tag;
    lk_win_o = b_pass_q.win;
    e_sel_o  = b_pass_q.sel;
    e_psub_o = b_pass_q.psub;
    // a texel's word in the window its sub-cache reads (computed here, off the selection's path)
    for (int t = 0; t < 4; t++) begin
      e_toff_o[t] = TOFF_W'(32'(b_pass_q.word[t]) - 32'(b_pass_q.win[b_pass_q.psub[t]]) * WW);
    end
    e_last_o = b_pass_q.last;
  end

  // No request while the directory's reset sweep runs (swp_i), nor while the entry register
  // holds a request that is not moving its last pass into the pass queue.
  assign req_ready_o = rst_ni && !swp_i && (!s0_valid_q || (p_load && sl_last));

  logic req_fire;
  assign req_fire = req_valid_i && req_ready_o;

  // ---------------------------------------------------------------- entry register

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      s0_valid_q  <= 1'b0;
      s0_todo_q   <= '0;
    end else begin
      if (req_fire) begin
        s0_valid_q  <= 1'b1;
        s0_todo_q   <= 4'hf;
      end else if (p_load) begin  // a pass of a request with more to do
        s0_todo_q   <= s0_todo_q & ~sl_sel;
        if (sl_last) s0_valid_q <= 1'b0;
      end
    end
    if (req_fire) begin
      s0_addr_q <= req_addr_i;
      s0_row_q  <= in_row;
      s0_join_q <= in_join;
    end
  end


  assign a_set_o   = a_set_q;
  assign b_valid_o = b_valid_q;

  // the texel address bits 1:0 are 0
  logic unused;
  assign unused = ^{s0_addr_q[0][1:0], s0_addr_q[1][1:0], s0_addr_q[2][1:0], s0_addr_q[3][1:0]};

endmodule
