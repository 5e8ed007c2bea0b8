// SPDX-License-Identifier: Apache-2.0
// tex_cache_assert: the texture cache's simulation checks, bound into every tex_cache (the bind
// at the end of this file; not in synthesis): a shadow of the directory's state bits and of the
// lines held by the data slots and read by the queued passes, the invariants of the directory,
// the reference counts, the MSHRs, the queues and the streams, and the coverage points
// tb/tex_cache reads (u_assert.sim_*); and the tags: every response carries the tag of the
// oldest request not answered (rsp_tag_order, proven by formal/tex_cache.sby with the queue
// checks).  Every check is an immediate assertion in a clocked block (the state before the clock
// edge, as a concurrent assertion samples it); "disable iff (!rst_ni)" is a guard on rst_ni, and
// "a |=> b" a guard on registered copies of the clock before.  The AXI channel checks are
// cache_axi_read_assert's.
module tex_cache_assert #(
  parameter int unsigned ADDR_W     = 32,
  parameter int unsigned TAG_W      = 8,
  parameter int unsigned NSUB       = 4,
  parameter int unsigned SETS       = 32,
  parameter int unsigned WAYS       = 4,
  parameter int unsigned MSHRS      = 16,
  parameter int unsigned FIFO_DEPTH = 64,
  parameter int unsigned OUT_DEPTH  = 4,
  parameter int unsigned PQ_DEPTH   = 4,
  parameter int unsigned TQ_DEPTH   = 128, // tag queue entries (tex_cache_data)
  parameter int unsigned WW         = 2,   // words per data window
  parameter int unsigned LA_W       = 27,  // line address width
  parameter int unsigned SET_W      = 5,
  parameter int unsigned WAY_W      = 2,
  parameter int unsigned TAGB       = 21,  // stored tag bits
  parameter int unsigned RC_W       = 7,   // reference count width
  parameter int unsigned FP_W       = 6,   // FIFO pointer width
  parameter int unsigned FC_W       = 7,   // FIFO count width
  parameter int unsigned QCNT_W     = 5,   // MSHR count width
  parameter int unsigned MIDX_W     = 4,   // MSHR index width
  parameter int unsigned PLRU_W     = 3,
  parameter int unsigned TOFF_W     = 2    // word in a read window
) (
  input logic                               clk_i,
  input logic                               rst_ni,
  input logic                               swp,          // the live bits' reset sweep
  // streams
  input logic                               req_valid_i,
  input logic                               req_ready_o,
  input logic [3:0][ADDR_W-1:0]             req_addr_i,
  input logic [TAG_W-1:0]                   req_tag_i,
  input logic                               rsp_valid_o,
  input logic                               rsp_ready_i,
  input logic [3:0][31:0]                   rsp_texel_o,
  input logic                               rsp_err_o,
  input logic [TAG_W-1:0]                   rsp_tag_o,
  // entry, pass selection, pass queue
  input logic                               p_load,
  input logic [3:0]                         s0_todo_q,
  input logic [3:0]                         sl_sel,
  input logic [NSUB-1:0]                    sl_v,
  input logic [NSUB-1:0][LA_W-1:0]          sl_la,
  input logic [3:0][LA_W-1:0]               e_la,
  input logic [3:0][1:0]                    e_sub,
  input logic [2:0]                         pq_wp_q,
  input logic [2:0]                         pq_ip_q,
  input logic [2:0]                         pq_rp_q,
  input logic                               a_issue,
  input logic [NSUB-1:0][SET_W-1:0]         a_set_q,
  input logic [NSUB-1:0][SET_W-1:0]         a_pass_set,   // the read stage's pass's sets
  input logic                               b_valid_q,
  input logic                               b_is_oldest,  // the decide stage's pass equals
                                                          // the pass queue's oldest entry
  // lookup
  input logic                               e_fire,
  input logic                               e_last,
  input logic [NSUB-1:0]                    lk_v,
  input logic [NSUB-1:0]                    lk_alloc,
  input logic [NSUB-1:0]                    lk_blocked,
  input logic [NSUB-1:0][WAY_W-1:0]         lk_way,
  input logic                               mshr_short,
  input logic [NSUB-1:0][WAYS-1:0]          f_vld,
  input logic [NSUB-1:0][WAYS-1:0]          f_pnd,
  input logic [NSUB-1:0][PLRU_W-1:0]        f_plru,
  input logic [NSUB-1:0]                    fw_idle,      // the committing pass's slot's count
                                                          // says idle at the decision
  // commit register
  input logic                               cm_valid_q,
  input logic [NSUB-1:0]                    cm_alloc_q,
  input logic [NSUB-1:0][MIDX_W-1:0]        cm_mshr_q,
  input logic [2:0]                         cm_n_q,       // the MSHRs it takes, registered
  input logic [NSUB-1:0][LA_W-1:0]          cm_la_q,
  input logic [NSUB-1:0][RC_W-1:0]          cm_inc_q,
  input logic [NSUB-1:0][TAGB-1:0]          cm_tag_q,     // the pass's tags
  input logic [NSUB-1:0]                    cm_used,      // the committing pass's sub-caches
  input logic [NSUB-1:0][SET_W-1:0]         cm_set,       // ... and slots
  input logic [NSUB-1:0][WAY_W-1:0]         cm_way,
  // request FIFO and head
  input logic [FP_W-1:0]                    fifo_wp_q,
  input logic [FP_W-1:0]                    fifo_rp_q,
  input logic [FC_W-1:0]                    fifo_cnt_q,
  input logic                               h_pop,
  input logic [NSUB-1:0]                    hd_err,
  input logic [NSUB-1:0]                    hd_pend,      // the head's slots: pending, bad
  input logic [NSUB-1:0]                    hd_bad,       // (registers loaded a clock ahead)
  input logic [NSUB-1:0]                    hd_used,      // the head pass's sub-caches
  input logic [NSUB-1:0][SET_W-1:0]         hd_set,       // ... slots
  input logic [NSUB-1:0][WAY_W-1:0]         hd_way,
  input logic [3:0]                         hd_tsel,      // ... texels
  input logic [3:0][TOFF_W-1:0]             hd_toff,
  input logic [NSUB-1:0][RC_W-1:0]          hd_rc,        // ... counts its release writes
  input logic                               hd_is_head,   // the head register equals the
                                                          // FIFO's head entry
  input logic                               nx_is_next,   // the next-head register equals
                                                          // the FIFO's second entry
  // output buffer
  input logic                               out_push,
  input logic                               out_pop,
  input logic [2:0]                         out_cnt_q,
  // tag queue (tex_cache_data)
  input logic [$clog2(TQ_DEPTH)-1:0]        tq_wp_q,
  input logic [$clog2(TQ_DEPTH)-1:0]        tq_rp_q,
  // a beat written into the data RAMs (its slot: w_sub_q, w_set_q, w_way_q)
  input logic                               w_acc_q,
  // fills (the registered beat) and R channel
  input logic                               w_fill_q,
  input logic                               w_bad_q,
  input logic [1:0]                         w_sub_q,
  input logic [SET_W-1:0]                   w_set_q,
  input logic [WAY_W-1:0]                   w_way_q,
  input logic [LA_W-1:0]                    w_la_q,
  input logic                               fill_v,
  input logic                               fill_bad,
  input logic                               m_axi_rvalid,
  input logic                               r_cur,        // a beat of the current epoch
  // MSHRs and free list
  input logic                               mshr_busy_q [MSHRS],
  input logic [1:0]                         mshr_sub_q  [MSHRS],
  input logic [QCNT_W-1:0]                  arq_cnt,
  input logic [MIDX_W-1:0]                  fl_hd_q,
  input logic [QCNT_W-1:0]                  fl_cnt_q,
  // the memories (tex_cache's simulation views): directory words per sub-cache and set,
  // tags and reference counts per sub-cache, way and set, MSHR fields per sub-cache and MSHR
  input logic [WAYS-1:0]                    vw_live [NSUB][SETS],
  input logic [WAYS-1:0]                    vw_ag   [NSUB][SETS],
  input logic [WAYS-1:0]                    vw_fg   [NSUB][SETS],
  input logic [WAYS-1:0]                    vw_bad  [NSUB][SETS],
  input logic [TAGB-1:0]                    vw_tag  [NSUB][WAYS][SETS],
  input logic [RC_W-1:0]                    vw_inc  [NSUB][WAYS][SETS],
  input logic [RC_W-1:0]                    vw_dec  [NSUB][WAYS][SETS],
  input logic [LA_W-1:0]                    vw_la   [NSUB][MSHRS],
  input logic [SET_W+WAY_W-1:0]             vw_sw   [NSUB][MSHRS]
);

  // XOR-folded set index of a line (the specification tex_cache's set_of implements).
  function automatic logic [SET_W-1:0] spec_set(input logic [LA_W-1:0] la);
    logic [SET_W-1:0] s;
    s = '0;
    for (int unsigned i = 0; i < SET_W; i++) begin
      if (1 + i < LA_W) s[i] = la[1 + i];
      if (1 + SET_W + i < LA_W) s[i] = s[i] ^ la[1 + SET_W + i];
    end
    return s;
  endfunction

  // The way the pseudo-LRU tree points to when every way is a candidate (node n = 1 .. WAYS-1 is
  // bit n-1, children 2n, 2n+1; 1: the right subtree).
  function automatic logic [WAY_W-1:0] plru_way(input logic [PLRU_W-1:0] b);
    int unsigned n;
    n = 1;
    for (int unsigned l = 0; l < WAY_W; l++) n = 2 * n + (b[n-1] ? 1 : 0);
    return WAY_W'(n - WAYS);
  endfunction

  // ---------------------------------------------------------------- the directory as it is
  // every slot's tag and reference count (meaningful for a live slot only: valid or with the
  // error bit) and its state bits
  logic [TAGB-1:0] dir_tag [NSUB][SETS][WAYS];
  logic [RC_W-1:0] dir_rc  [NSUB][SETS][WAYS];
  logic [RC_W-1:0] dir_inc [NSUB][SETS][WAYS];
  logic [NSUB-1:0][SETS-1:0][WAYS-1:0] valid_v, pend_v, err_v;
  logic [LA_W-1:0]  mshr_la_v  [MSHRS];  // each MSHR's line and slot
  logic [SET_W-1:0] mshr_set_v [MSHRS];
  logic [WAY_W-1:0] mshr_way_v [MSHRS];
  logic [NSUB-1:0]  lk_live, hd_live;    // the committing pass's / the head's slot is live
  logic [NSUB-1:0][RC_W-1:0] dir_dec_hd;  // the head's slot's dec
  logic             hd_state_ok;          // hd_pend, hd_bad equal the head's slots' state bits

  always_comb begin
    for (int c = 0; c < NSUB; c++) begin
      for (int s = 0; s < SETS; s++) begin
        for (int w = 0; w < WAYS; w++) begin
          dir_tag[c][s][w] = vw_tag[c][w][s];
          dir_inc[c][s][w] = vw_inc[c][w][s];
          dir_rc[c][s][w]  = vw_inc[c][w][s] - vw_dec[c][w][s];
          pend_v[c][s][w]  = vw_live[c][s][w] && vw_ag[c][s][w] != vw_fg[c][s][w];
          err_v[c][s][w]   = vw_live[c][s][w] && vw_ag[c][s][w] == vw_fg[c][s][w]
                             && vw_bad[c][s][w];
          valid_v[c][s][w] = vw_live[c][s][w] && !err_v[c][s][w];
        end
      end
    end
    for (int m = 0; m < MSHRS; m++) begin
      mshr_la_v[m]                   = vw_la[mshr_sub_q[m]][m];
      {mshr_set_v[m], mshr_way_v[m]} = vw_sw[mshr_sub_q[m]][m];
    end
    for (int c = 0; c < NSUB; c++) begin
      lk_live[c] = valid_v[c][cm_set[c]][cm_way[c]] || err_v[c][cm_set[c]][cm_way[c]];
      hd_live[c] = valid_v[c][hd_set[c]][hd_way[c]] || err_v[c][hd_set[c]][hd_way[c]];
      dir_dec_hd[c] = vw_dec[c][hd_way[c]][hd_set[c]];
    end
    hd_state_ok = 1'b1;
    for (int c = 0; c < NSUB; c++) begin
      if (hd_used[c]
          && (hd_pend[c] != (vw_ag[c][hd_set[c]][hd_way[c]] != vw_fg[c][hd_set[c]][hd_way[c]])
              || hd_bad[c] != vw_bad[c][hd_set[c]][hd_way[c]])) hd_state_ok = 1'b0;
    end
  end

  // ---------------------------------------------------------------- shadow state
  // Reference: the state bits as flops written directly by the commit and the fill (as they
  // were before the generation bits); the generation bits must agree with them in every clock.
  logic [NSUB-1:0][SETS-1:0][WAYS-1:0] ref_valid_q, ref_pend_q, ref_err_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      ref_valid_q <= '0;
      ref_pend_q  <= '0;
      ref_err_q   <= '0;
    end else begin
      for (int c = 0; c < NSUB; c++) begin
        if (cm_valid_q && cm_alloc_q[c]) begin
          ref_valid_q[c][cm_set[c]][cm_way[c]] <= 1'b1;
          ref_pend_q[c][cm_set[c]][cm_way[c]]  <= 1'b1;
          ref_err_q[c][cm_set[c]][cm_way[c]]   <= 1'b0;
        end
      end
      if (w_fill_q) begin
        ref_pend_q[w_sub_q][w_set_q][w_way_q] <= 1'b0;
        ref_err_q[w_sub_q][w_set_q][w_way_q]  <= w_bad_q;
        if (w_bad_q) ref_valid_q[w_sub_q][w_set_q][w_way_q] <= 1'b0;
      end
    end
  end

  // The line each data slot holds, and the lines each queued pass reads.
  logic [LA_W-1:0] sh_slot_la [NSUB][SETS][WAYS];
  logic [NSUB-1:0][LA_W-1:0] sh_pass_la [FIFO_DEPTH];
  logic [NSUB-1:0] sh_slot_ok [SETS][WAYS];  // the slot has been written since reset

  always_ff @(posedge clk_i) begin
    if (cm_valid_q) sh_pass_la[fifo_wp_q] <= cm_la_q;
    if (!rst_ni) begin
      for (int s = 0; s < SETS; s++) for (int w = 0; w < WAYS; w++) sh_slot_ok[s][w] <= '0;
    end else if (w_fill_q) begin
      sh_slot_la[w_sub_q][w_set_q][w_way_q] <= w_la_q;
      sh_slot_ok[w_set_q][w_way_q][w_sub_q] <= 1'b1;
    end
  end

  // The tag queue: its entries are the requests accepted and not answered.
  localparam int unsigned TQ_W = $clog2(TQ_DEPTH);
  int unsigned     tq_cnt_q;   // requests accepted and not answered
  logic            p_tq_push_q;
  logic [TQ_W-1:0] p_tq_wp_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) tq_cnt_q <= 0;
    else         tq_cnt_q <= tq_cnt_q + 32'(req_valid_i && req_ready_o) - 32'(out_pop);
    p_tq_push_q <= rst_ni && req_valid_i && req_ready_o;
    p_tq_wp_q   <= tq_wp_q;
  end

  // The clock before, for the stream checks ("a |=> b").
  logic                   p_rst_q, p_req_wait_q, p_rsp_wait_q;
  logic [3:0][ADDR_W-1:0] p_req_addr_q;
  logic [TAG_W-1:0]       p_req_tag_q, p_rsp_tag_q;
  logic [3:0][31:0]       p_rsp_texel_q;
  logic                   p_rsp_err_q;
  always_ff @(posedge clk_i) begin
    p_rst_q       <= rst_ni;
    p_req_wait_q  <= req_valid_i && !req_ready_o;
    p_req_addr_q  <= req_addr_i;
    p_req_tag_q   <= req_tag_i;
    p_rsp_wait_q  <= rsp_valid_o && !rsp_ready_i;
    p_rsp_texel_q <= rsp_texel_o;
    p_rsp_err_q   <= rsp_err_o;
    p_rsp_tag_q   <= rsp_tag_o;
  end

  // MSHR bookkeeping.
  logic [QCNT_W-1:0] busy_cnt;
  logic [2:0]        cm_n;  // MSHRs the pass in the commit register takes
  logic              fl_head_ok;  // ... the free list's first cm_n entries, in sub-cache order,
                                  // and cm_n_q counts them
  always_comb begin
    busy_cnt = '0;
    for (int m = 0; m < MSHRS; m++) busy_cnt = busy_cnt + QCNT_W'(mshr_busy_q[m]);
    cm_n       = '0;
    fl_head_ok = 1'b1;
    for (int c = 0; c < NSUB; c++) begin
      if (cm_valid_q && cm_alloc_q[c]) begin
        if (32'(cm_n) >= 32'(fl_cnt_q)
            || cm_mshr_q[c] != tex_cache.u_free.mem_q[(32'(fl_hd_q) + 32'(cm_n)) % MSHRS])
          fl_head_ok = 1'b0;
        cm_n = cm_n + 3'd1;
      end
    end
    if (cm_n_q != cm_n) fl_head_ok = 1'b0;
  end

  // The checks over every MSHR, slot and sub-cache, each folded into one flag (with the first
  // place that fails, for the message), so that each is one labelled assertion (a label inside
  // a loop would name several checks alike, which the formal front end refuses).
  logic lp_fl_ok, lp_pend_ok, lp_tag_ok, lp_victim_ok, lp_rc_ovf_ok, lp_inc_ok, lp_rc_unf_ok,
        lp_line_ok, lp_mshr_ok, lp_uniq_ok, lp_rdcol_ok, lp_relc_ok, lp_htag_ok;
  int   lp_fl_m, lp_victim_c, lp_inc_c, lp_line_c, lp_mshr_m, lp_rdcol_c, lp_relc_c, lp_htag_c;
  int   lp_pend_at [3];
  int   lp_tag_at [2];
  int   lp_uniq_at [2];
  always_comb begin
    lp_fl_ok = 1'b1;
    lp_fl_m  = 0;
    // (the free list's entries read one by one through a hierarchical reference: the whole
    // array as a port would keep the formal front end from inferring that storage)
    for (int j = 0; j < MSHRS; j++) begin
      if (j < 32'(fl_cnt_q) && mshr_busy_q[tex_cache.u_free.mem_q[(32'(fl_hd_q) + j) % MSHRS]]
          && lp_fl_ok) begin
        lp_fl_ok = 1'b0;
        lp_fl_m  = int'(tex_cache.u_free.mem_q[(32'(fl_hd_q) + j) % MSHRS]);
      end
    end
    lp_pend_ok = 1'b1;
    lp_tag_ok  = 1'b1;
    lp_pend_at = '{0, 0, 0};
    lp_tag_at  = '{0, 0};
    for (int c = 0; c < NSUB; c++) begin
      for (int s = 0; s < SETS; s++) begin
        for (int w = 0; w < WAYS; w++) begin
          if (pend_v[c][s][w] && dir_rc[c][s][w] == '0 && lp_pend_ok) begin
            lp_pend_ok = 1'b0;
            lp_pend_at = '{c, s, w};
          end
          for (int v = w + 1; v < WAYS; v++) begin
            if (valid_v[c][s][w] && valid_v[c][s][v] && dir_tag[c][s][w] == dir_tag[c][s][v]
                && lp_tag_ok) begin
              lp_tag_ok = 1'b0;
              lp_tag_at = '{c, s};
            end
          end
        end
      end
    end
    lp_victim_ok = 1'b1;
    lp_rc_ovf_ok = 1'b1;
    lp_inc_ok    = 1'b1;
    lp_rc_unf_ok = 1'b1;
    lp_line_ok   = 1'b1;
    lp_victim_c  = 0;
    lp_inc_c     = 0;
    lp_htag_ok   = 1'b1;
    lp_htag_c    = 0;
    lp_line_c    = 0;
    lp_rdcol_ok  = 1'b1;
    lp_relc_ok   = 1'b1;
    lp_rdcol_c   = 0;
    lp_relc_c    = 0;
    for (int c = 0; c < NSUB; c++) begin
      if (cm_valid_q && cm_alloc_q[c]
          && !((!lk_live[c] || dir_rc[c][cm_set[c]][cm_way[c]] == '0)
               && !pend_v[c][cm_set[c]][cm_way[c]]) && lp_victim_ok) begin
        lp_victim_ok = 1'b0;
        lp_victim_c  = c;
      end
      if (cm_valid_q && cm_used[c] && !cm_alloc_q[c]
          && dir_rc[c][cm_set[c]][cm_way[c]] == '1) lp_rc_ovf_ok = 1'b0;
      if (cm_valid_q && cm_used[c] && !cm_alloc_q[c]
          && cm_inc_q[c] != dir_inc[c][cm_set[c]][cm_way[c]] + RC_W'(1) && lp_inc_ok) begin
        lp_inc_ok = 1'b0;
        lp_inc_c  = c;
      end
      if (cm_valid_q && cm_used[c] && !cm_alloc_q[c]
          && cm_tag_q[c] != dir_tag[c][cm_set[c]][cm_way[c]] && lp_htag_ok) begin
        lp_htag_ok = 1'b0;
        lp_htag_c  = c;
      end
      if (h_pop && hd_used[c] && w_acc_q && w_sub_q == 2'(c) && w_set_q == hd_set[c]
          && w_way_q == hd_way[c] && lp_rdcol_ok) begin
        lp_rdcol_ok = 1'b0;
        lp_rdcol_c  = c;
      end
      if (h_pop && hd_used[c] && hd_rc[c] != dir_dec_hd[c] + RC_W'(1) && lp_relc_ok) begin
        lp_relc_ok = 1'b0;
        lp_relc_c  = c;
      end
      if (h_pop && hd_used[c] && !(hd_live[c] && dir_rc[c][hd_set[c]][hd_way[c]] != '0))
        lp_rc_unf_ok = 1'b0;
      if (h_pop && hd_used[c] && !err_v[c][hd_set[c]][hd_way[c]]
          && !(sh_slot_ok[hd_set[c]][hd_way[c]][c]
               && sh_slot_la[c][hd_set[c]][hd_way[c]] == sh_pass_la[fifo_rp_q][c])
          && lp_line_ok) begin
        lp_line_ok = 1'b0;
        lp_line_c  = c;
      end
    end
    lp_mshr_ok = 1'b1;
    lp_uniq_ok = 1'b1;
    lp_mshr_m  = 0;
    lp_uniq_at = '{0, 0};
    for (int m = 0; m < MSHRS; m++) begin
      if (mshr_busy_q[m]
          && !(pend_v[mshr_sub_q[m]][mshr_set_v[m]][mshr_way_v[m]]
               && valid_v[mshr_sub_q[m]][mshr_set_v[m]][mshr_way_v[m]]
               && dir_tag[mshr_sub_q[m]][mshr_set_v[m]][mshr_way_v[m]]
                  == mshr_la_v[m][LA_W-1 -: TAGB]
               && spec_set(mshr_la_v[m]) == mshr_set_v[m]) && lp_mshr_ok) begin
        lp_mshr_ok = 1'b0;
        lp_mshr_m  = m;
      end
      for (int n = m + 1; n < MSHRS; n++) begin
        if (mshr_busy_q[m] && mshr_busy_q[n] && mshr_sub_q[n] == mshr_sub_q[m]
            && (mshr_la_v[n] == mshr_la_v[m]
                || (mshr_set_v[n] == mshr_set_v[m] && mshr_way_v[n] == mshr_way_v[m]))
            && lp_uniq_ok) begin
          lp_uniq_ok = 1'b0;
          lp_uniq_at = '{m, n};
        end
      end
    end
  end

  // ---------------------------------------------------------------- checks
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      // Streams: payload stable while stalled (the request side is the client's contract).
      if (p_rst_q && p_req_wait_q) begin
        req_stable: assert (req_valid_i && req_addr_i == p_req_addr_q && req_tag_i == p_req_tag_q)
          else $error("tex_cache: request dropped or changed while stalled");
      end
      if (p_rst_q && p_rsp_wait_q) begin
        rsp_stable: assert (rsp_valid_o && rsp_texel_o == p_rsp_texel_q
                            && rsp_err_o == p_rsp_err_q && rsp_tag_o == p_rsp_tag_q)
          else $error("tex_cache: response dropped or changed while stalled");
      end
      req_aligned: assert (!req_valid_i || (req_addr_i[0][1:0] | req_addr_i[1][1:0]
                                            | req_addr_i[2][1:0] | req_addr_i[3][1:0]) == 2'b00)
        else $error("tex_cache: texel address not 4-byte aligned");
      // The head's slots are live (its pending and error bits are read without the live bit).
      head_live: assert (fifo_cnt_q == '0 || (hd_live | ~hd_used) == '1)
        else $error("tex_cache: the head reads a slot that is not live");
      // The head's pending and error bits (registers, loaded a clock ahead) are its slots'.
      // The decision takes the committing pass's slot as referenced without comparing its
      // counts (tex_cache_lookup's f_idle); the counts agree when the decide stage holds a pass.
      fw_referenced: assert (!b_valid_q || fw_idle == '0)
        else $error("tex_cache: the committing pass's slot counts as idle at the decision");
      head_state: assert (fifo_cnt_q == '0 || hd_state_ok)
        else $error("tex_cache: the head's pending / error bits differ from its slots'");
      // FIFOs.
      fifo_no_overflow: assert (!cm_valid_q || fifo_cnt_q < FC_W'(FIFO_DEPTH) || h_pop)
        else $error("tex_cache: request FIFO overflow");
      fifo_no_underflow: assert (!h_pop || fifo_cnt_q != '0)
        else $error("tex_cache: request FIFO underflow");
      fifo_head: assert (fifo_cnt_q == '0 || hd_is_head)
        else $error("tex_cache: head register differs from the FIFO's head entry");
      fifo_next: assert (fifo_cnt_q < FC_W'(2) || nx_is_next)
        else $error("tex_cache: next-head register differs from the FIFO's second entry");
      fifo_count: assert (32'(fifo_cnt_q) <= FIFO_DEPTH
                          && FP_W'(fifo_wp_q - fifo_rp_q) == FP_W'(fifo_cnt_q))
        else $error("tex_cache: request FIFO pointers inconsistent");
      pass_queue_count: assert (3'(pq_wp_q - pq_rp_q) <= 3'(PQ_DEPTH)
                                && 3'(pq_ip_q - pq_rp_q) == 3'(b_valid_q)
                                && 3'(pq_wp_q - pq_ip_q) <= 3'(pq_wp_q - pq_rp_q))
        else $error("tex_cache: pass queue pointers inconsistent");
      decide_is_oldest: assert (!b_valid_q || b_is_oldest)
        else $error("tex_cache: the decide stage's pass is not the queue's oldest");
      read_set: assert (!a_issue || a_set_q == a_pass_set)
        else $error("tex_cache: the read stage's set register differs from its pass");
      out_no_overflow: assert (!out_push || out_cnt_q < 3'(OUT_DEPTH) || out_pop)
        else $error("tex_cache: output buffer overflow");
      out_no_underflow: assert (!out_pop || out_cnt_q != '0)
        else $error("tex_cache: output buffer underflow");
      // The tag queue never overflows, holds an answer's tag, and the answer at the head never
      // uses the RAM's read of an entry written in the clock before (no_rw_check: the read of a
      // word written in the same clock is undefined on the FPGA).
      tag_queue_count: assert (tq_cnt_q < TQ_DEPTH && TQ_W'(tq_wp_q - tq_rp_q) == TQ_W'(tq_cnt_q)
                               && (!rsp_valid_o || tq_cnt_q != 0))
        else $error("tex_cache: tag queue count %0d inconsistent", tq_cnt_q);
      tag_queue_read: assert (!(rsp_valid_o && p_tq_push_q && p_tq_wp_q == tq_rp_q))
        else $error("tex_cache: the answer's tag is read in the clock it is written");
      // MSHRs: the AR queue holds at most the busy MSHRs; the free list holds exactly the MSHRs
      // that are not busy (those the pass in the commit register takes among them, at its head:
      // free_list_head).
      arq_within_busy: assert (arq_cnt <= busy_cnt)
        else $error("tex_cache: AR queue holds more reads than busy MSHRs");
      free_list_count: assert (32'(busy_cnt) + 32'(fl_cnt_q) == MSHRS)
        else $error("tex_cache: free-list count differs from the MSHRs not busy");
      free_list_head: assert (fl_head_ok)
        else $error("tex_cache: the commit register's MSHRs are not the free list's head");
      free_list_not_busy: assert (lp_fl_ok)
        else $error("tex_cache: busy MSHR %0d on the free list", lp_fl_m);
    end
    if (rst_ni && !swp) begin  // (the live bits are cleared once the sweep ends)
      state_bits: assert (valid_v == ref_valid_q && pend_v == ref_pend_q && err_v == ref_err_q)
        else $error("tex_cache: directory state bits differ from their reference");
      // Invariants of every slot: a pending slot is referenced (by its allocator at least);
      // valid tags of a set are unique.
      pending_referenced: assert (lp_pend_ok)
        else $error("tex_cache: sub-cache %0d set %0d way %0d pending but unreferenced",
                    lp_pend_at[0], lp_pend_at[1], lp_pend_at[2]);
      tag_unique: assert (lp_tag_ok)
        else $error("tex_cache: sub-cache %0d set %0d holds a line twice", lp_tag_at[0],
                    lp_tag_at[1]);
      // No eviction of a referenced line: a victim is unreferenced (hence not pending), in the
      // directory as its allocation is written (the commit clock).
      victim_unreferenced: assert (lp_victim_ok)
        else $error("tex_cache: sub-cache %0d evicts a referenced line", lp_victim_c);
      // Reference counts never wrap.
      rc_no_overflow: assert (lp_rc_ovf_ok)
        else $error("tex_cache: reference count overflow");
      // The forwarded view is what the directory holds once the commit is written.
      commit_inc: assert (lp_inc_ok)
        else $error("tex_cache: sub-cache %0d commits a stale reference count", lp_inc_c);
      // A hit's slot holds the pass's tag, so the commit's write of {tag, count} (one word per
      // way) leaves the tag as it was.
      commit_hit_tag: assert (lp_htag_ok)
        else $error("tex_cache: sub-cache %0d commits a hit whose slot holds another tag",
                    lp_htag_c);
      // The data RAMs' read of the head's slot is used (the clock after): no beat is written
      // into that slot in this clock (no_rw_check, as for the tag queue).
      data_read_no_collision: assert (lp_rdcol_ok)
        else $error("tex_cache: sub-cache %0d slot (%0d, %0d) read while a beat is written",
                    lp_rdcol_c, hd_set[lp_rdcol_c], hd_way[lp_rdcol_c]);
      // The release writes the pass's own reference count: dec + 1.
      release_count: assert (lp_relc_ok)
        else $error("tex_cache: sub-cache %0d releases count %0d, dec is %0d", lp_relc_c,
                    hd_rc[lp_relc_c], dir_dec_hd[lp_relc_c]);
      rc_no_underflow: assert (lp_rc_unf_ok)
        else $error("tex_cache: reference count underflow");
      // The slot read at the head holds the line the pass looked up (unless it errored).
      head_reads_its_line: assert (lp_line_ok)
        else $error("tex_cache: head reads sub-cache %0d slot (%0d, %0d): line %h, not %h",
                    lp_line_c, hd_set[lp_line_c], hd_way[lp_line_c],
                    sh_slot_la[lp_line_c][hd_set[lp_line_c]][hd_way[lp_line_c]],
                    sh_pass_la[fifo_rp_q][lp_line_c]);
      // MSHRs: a busy MSHR's slot is valid, pending and tagged with its line; no two busy MSHRs
      // fill one slot.
      mshr_slot_pending: assert (lp_mshr_ok)
        else $error("tex_cache: MSHR %0d does not own a pending slot of its line", lp_mshr_m);
      mshr_unique: assert (lp_uniq_ok)
        else $error("tex_cache: MSHRs %0d and %0d read the same line / slot", lp_uniq_at[0],
                    lp_uniq_at[1]);
    end
  end

  // ---------------------------------------------------------------- responses: tags in order
  // Every response carries the tag of the oldest request not yet answered: none is lost,
  // duplicated or reordered (whatever the lookup, the memory and the data RAMs do).
  // tg_owed_q counts the requests accepted and not yet answered; a tracked request (picked
  // freely in formal, in simulation every request that finds none tracked) keeps its tag and the
  // number of requests ahead of it, and the response given when none is left ahead must carry
  // its tag (rsp_tag_order); a response only while one is owed (rsp_owed), and never more owed
  // than the cache can hold (owed_bound: entry register, pass queue, FIFO with its commit
  // register, output buffer with the two head stages; the tag queue is sized by this bound).
  // Proven by formal/tex_cache.sby (docs/formal.md).
  localparam int unsigned OWED_MAX = 1 + PQ_DEPTH + FIFO_DEPTH + OUT_DEPTH;
  localparam int unsigned OWED_W   = $clog2(OWED_MAX + 1) + 1;  // (one bit to spare)
  wire               tg_pick;     // track this request (free in formal: a net, read once)
`ifndef FORMAL
  assign tg_pick = 1'b1;
`endif
  logic              tg_req, tg_rsp;      // request / response handshakes
  logic [OWED_W-1:0] tg_owed_q;           // requests accepted and not answered
  logic              tg_trk_q;            // a request is tracked
  logic [TAG_W-1:0]  tg_tag_q;            // ... its tag
  logic [OWED_W-1:0] tg_ahead_q;          // ... the requests owed before it
  logic              tg_out;              // ... it is answered in this clock
  logic              tg_start;            // this clock's request becomes the tracked one
  assign tg_req   = req_valid_i && req_ready_o;
  assign tg_rsp   = rsp_valid_o && rsp_ready_i;
  assign tg_out   = tg_trk_q && tg_rsp && tg_ahead_q == '0;
  assign tg_start = tg_req && tg_pick && (!tg_trk_q || tg_out);
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      tg_owed_q <= '0;
      tg_trk_q  <= 1'b0;
    end else begin
      tg_owed_q <= tg_owed_q + OWED_W'(tg_req) - OWED_W'(tg_rsp);
      if (tg_start) begin
        tg_trk_q   <= 1'b1;
        tg_tag_q   <= req_tag_i;
        tg_ahead_q <= tg_owed_q - OWED_W'(tg_rsp);
      end else if (tg_out) begin
        tg_trk_q <= 1'b0;
      end else if (tg_trk_q && tg_rsp) begin
        tg_ahead_q <= tg_ahead_q - OWED_W'(1);
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      rsp_owed: assert (!rsp_valid_o || tg_owed_q != '0)
        else $error("tex_cache: a response with no request owed");
      rsp_tag_order: assert (!tg_out || rsp_tag_o == tg_tag_q)
        else $error("tex_cache: response tag %0h, the oldest request's %0h", rsp_tag_o,
                    tg_tag_q);
      owed_bound: assert (32'(tg_owed_q) <= OWED_MAX && (!tg_trk_q || tg_ahead_q < tg_owed_q))
        else $error("tex_cache: %0d requests owed", tg_owed_q);
    end
  end

  // ---------------------------------------------------------------- coverage points
  // Read by tb/tex_cache (nothing in the design reads them).
  /* verilator lint_off UNUSEDSIGNAL */
  logic sim_merge, sim_victim_wait, sim_mshr_wait, sim_fifo_full, sim_split, sim_stale_beat,
        sim_err_fill, sim_err_pass, sim_victim_redirect, sim_win_split, sim_overlap;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    logic [WAY_W-1:0] free_way;
    sim_merge           = 1'b0;  // a pass enters with a line that is still being read
    sim_victim_redirect = 1'b0;  // a reference made the victim differ from the plain policy
    for (int c = 0; c < NSUB; c++) begin
      if (e_fire && lk_v[c] && !lk_alloc[c] && f_pnd[c][lk_way[c]]) sim_merge = 1'b1;
      free_way = plru_way(f_plru[c]);
      for (int w = WAYS - 1; w >= 0; w--) begin
        if (!f_vld[c][w]) free_way = WAY_W'(w);
      end
      if (e_fire && lk_alloc[c] && free_way != lk_way[c]) sim_victim_redirect = 1'b1;
    end
    // a texel left for a later pass although its line is the one its sub-cache reads (the
    // window does not hold its word); a texel read at the window's overlap word
    sim_win_split = 1'b0;
    sim_overlap   = 1'b0;
    for (int t = 0; t < 4; t++) begin
      if (p_load && s0_todo_q[t] && !sl_sel[t] && sl_v[e_sub[t]] && sl_la[e_sub[t]] == e_la[t])
        sim_win_split = 1'b1;
      if (h_pop && hd_tsel[t] && 32'(hd_toff[t]) == WW) sim_overlap = 1'b1;
    end
  end
  assign sim_victim_wait = rst_ni && b_valid_q && (|lk_blocked);   // every way referenced
  assign sim_mshr_wait   = rst_ni && b_valid_q && mshr_short;
  assign sim_fifo_full   = rst_ni && b_valid_q && fifo_cnt_q == FC_W'(FIFO_DEPTH);
  assign sim_split       = e_fire && !e_last;                        // a request of 2+ passes
  assign sim_stale_beat  = m_axi_rvalid && !r_cur;                   // a read from before a reset
  assign sim_err_fill    = fill_v && fill_bad;
  assign sim_err_pass    = h_pop && (|hd_err);

endmodule

`ifndef SYNTHESIS
bind tex_cache tex_cache_assert #(
  .ADDR_W(ADDR_W), .TAG_W(TAG_W), .NSUB(NSUB), .SETS(SETS), .WAYS(WAYS), .MSHRS(MSHRS),
  .FIFO_DEPTH(FIFO_DEPTH), .OUT_DEPTH(OUT_DEPTH), .PQ_DEPTH(PQ_DEPTH), .TQ_DEPTH(TQ_DEPTH),
  .WW(WW), .LA_W(LA_W),
  .SET_W(SET_W), .WAY_W(WAY_W), .TAGB(TAGB), .RC_W(RC_W), .FP_W(FP_W), .FC_W(FC_W),
  .QCNT_W(QCNT_W), .MIDX_W(MIDX_W), .PLRU_W(PLRU_W), .TOFF_W(TOFF_W)
) u_assert (
  .*,
  // (the request side and the pass queue: u_front; the decide stage: u_lookup)
  .p_load(u_front.p_load), .s0_todo_q(u_front.s0_todo_q), .sl_sel(u_front.sl_sel),
  .sl_v(u_front.sl_v), .sl_la(u_front.sl_la), .e_la(u_front.e_la), .e_sub(u_front.e_sub),
  .pq_wp_q(u_front.pq_wp_q), .pq_ip_q(u_front.pq_ip_q), .pq_rp_q(u_front.pq_rp_q),
  .a_set_q(a_set), .a_pass_set(u_front.a_pass.set), .b_valid_q(b_valid),
  .b_is_oldest(u_front.b_pass_q == u_front.pq_oldest),
  .f_vld(u_lookup.f_vld), .f_pnd(u_lookup.f_pnd), .fw_idle(u_lookup.fw_idle),
  .out_push(u_data.out_push), .out_pop(u_data.out_pop), .out_cnt_q(u_data.out_cnt),
  .tq_wp_q(u_data.tq_wp_q), .tq_rp_q(u_data.tq_rp_q),
  .fl_hd_q(u_free.rp_q), .fl_cnt_q(u_free.cnt_q),
  .cm_used(cm_pass_q.used), .cm_set(cm_pass_q.set), .cm_way(cm_pass_q.way), .cm_inc_q(cm_inc),
  .hd_used(hd_q.used), .hd_set(hd_q.set), .hd_way(hd_q.way), .hd_tsel(hd_q.tsel),
  .hd_toff(hd_q.toff), .hd_rc(hd_q.rc), .fifo_wp_q(u_fifo.wp_q), .fifo_rp_q(u_fifo.rp_q), .fifo_cnt_q(fifo_cnt),
  .hd_is_head(hd_q == u_fifo.mem_q[u_fifo.rp_q]),
  .nx_is_next(nx_q == u_fifo.mem_q[FP_W'(u_fifo.rp_q + FP_W'(1))])
);
`endif
