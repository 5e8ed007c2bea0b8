// SPDX-License-Identifier: Apache-2.0
// cache_axi_read_formal: cache_axi_read under SymbiYosys (formal/cache_axi_read.sby) between a
// model of its cache and a model of an AXI slave.  The properties are the bound
// cache_axi_read_assert's (AR stable, one AR per allocation, no beat accepted without a read
// out, the beat count and rlast, an error marks its line), circ_queue_assert's (the AR queue) and
// the wrapper's own: ar_line (the AR carries its MSHR's line address) and the induction
// invariants below.
//
// The cache (as height_cache and tex_cache use the module): busy_q marks the MSHRs allocated and
// not yet answered; it allocates only MSHRs not busy, one per lane (alloc_free), gives each a
// line address (la_q, written at the allocation, read back on la_i), frees an MSHR at its line's
// last accepted beat and accepts a beat when r_ours_o names a busy MSHR (r_acc_i, as tex_cache).
// EARLY_WR (height_cache, one lane): the index is written (alloc_wr_i) in any clock with a free
// MSHR, the allocation comes with a write; else alloc_wr_i = alloc_i (tex_cache).
// The AXI slave: arready free; after an AR it returns exactly BEATS beats with the arid it got
// (any interleaving with other reads, any rresp), rlast on the last of them and on no other, no
// beat for an MSHR without a read out; rready is 1, so a beat is never held.  Reset comes in
// the first clock, and with RESETS at any time after that as long as cache_axi_read's
// requirement holds (a read returns before 2^EPOCH_W - 1 further resets; one epoch bit here: no
// read from before the last reset is still out when the next one starts): the reads out at a
// reset go on returning their beats with their old arid (stale reads), while the cache, reset,
// allocates the MSHRs again.  The wrapper's stale_ignored: a stale read's beat is never taken
// for the current epoch's (r_cur_o low), so it touches nothing.
//
// Induction invariants (the shadow in u_dut.u_assert against the cache and the slave):
//   inv_busy    busy = pend | out, never both;
//   inv_queue   every pend MSHR's index is exactly once in the AR queue's entries or the AR
//               registers (AR_REG), no other index is there;
//   inv_slave   the slave's reads out are the shadow's, with the beats it sent = the beats the
//               shadow and cache_axi_read counted, its errors = theirs, its arid's epoch the
//               current one; an MSHR without a read out has a clear count and error bit;
//   inv_stale   a stale read's epoch is not the current one (in reset too).
module cache_axi_read_formal #(
  parameter int unsigned MSHRS    = 3,     // line reads in flight
  parameter int unsigned NPUSH    = 1,     // allocations per clock
  parameter bit          AR_REG   = 1'b0,  // cache_axi_read's AR_REG
  parameter bit          EARLY_WR = 1'b1,  // see above (NPUSH = 1 only)
  parameter bit          RESETS   = 1'b0,  // resets after the first clock too (see above)
  parameter int unsigned DATA_W   = 16,    // with LINE_BYTES: BEATS = 2
  parameter int unsigned LINE_BYTES = 4,
  parameter int unsigned ADDR_W   = 5,     // line address: 3 bits
  // derived (not to be overridden)
  parameter int unsigned MIDX_W   = (MSHRS > 1) ? $clog2(MSHRS) : 1,
  parameter int unsigned ID_W     = MIDX_W + 1,   // one epoch bit
  parameter int unsigned OFF_W    = $clog2(LINE_BYTES),
  parameter int unsigned LA_W     = ADDR_W - OFF_W,
  parameter int unsigned BEATS    = LINE_BYTES * 8 / DATA_W,
  parameter int unsigned BEAT_W   = (BEATS > 1) ? $clog2(BEATS) : 1
) (
  input logic                         clk_i,
  input logic                         rst_ni,
  input logic [NPUSH-1:0]             alloc_i,
  input logic [NPUSH-1:0]             alloc_wr_free_i,  // alloc_wr_i when EARLY_WR
  input logic [NPUSH-1:0][MIDX_W-1:0] alloc_idx_i,
  input logic [NPUSH-1:0][LA_W-1:0]   alloc_la_i,       // the allocated MSHR's line
  input logic                         m_axi_arready,
  input logic [ID_W-1:0]              m_axi_rid,
  input logic [1:0]                   m_axi_rresp,
  input logic                         m_axi_rlast,
  input logic                         m_axi_rvalid
);

  localparam int unsigned EPOCH_W = ID_W - MIDX_W;

  logic [NPUSH-1:0]  alloc_wr;
  logic [MIDX_W-1:0] la_idx, r_idx;
  logic [LA_W-1:0]   la;
  logic              r_cur, r_ours, r_acc, r_last, r_bad;
  logic [BEAT_W-1:0] r_beat;
  logic [ID_W-1:0]   arid;
  logic [ADDR_W-1:0] araddr;
  logic              arvalid, rready;
  logic [MSHRS-1:0]  busy_q;
  logic [MSHRS-1:0][LA_W-1:0] la_q;

  assign alloc_wr = (EARLY_WR && NPUSH == 1) ? alloc_wr_free_i : alloc_i;
  assign la       = la_q[la_idx];
  assign r_acc    = r_ours && busy_q[r_idx];

  cache_axi_read #(
    .ADDR_W(ADDR_W), .DATA_W(DATA_W), .LINE_BYTES(LINE_BYTES), .MSHRS(MSHRS), .ID_W(ID_W),
    .SETS(2), .NPUSH(NPUSH), .AR_REG(AR_REG)
  ) u_dut (
    .clk_i, .rst_ni,
    .alloc_i, .alloc_wr_i(alloc_wr), .alloc_idx_i,
    .la_idx_o(la_idx), .la_i(la),
    .arq_pop_o(), .arq_head_o(), .arq_cnt_o(),
    .r_idx_o(r_idx), .r_cur_o(r_cur), .r_ours_o(r_ours), .r_acc_i(r_acc), .r_beat_o(r_beat),
    .r_last_o(r_last), .r_bad_o(r_bad),
    .sweep_o(), .sweep_set_o(),
    .m_axi_arid(arid), .m_axi_araddr(araddr), .m_axi_arlen(), .m_axi_arsize(),
    .m_axi_arburst(), .m_axi_arvalid(arvalid), .m_axi_arready,
    .m_axi_rid, .m_axi_rresp, .m_axi_rlast, .m_axi_rvalid, .m_axi_rready(rready));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // ---- the cache ---------------------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      busy_q <= '0;
    end else begin
      if (r_acc && r_last) busy_q[r_idx] <= 1'b0;
      for (int k = 0; k < NPUSH; k++) begin
        if (alloc_i[k]) busy_q[alloc_idx_i[k]] <= 1'b1;
      end
    end
    for (int k = 0; k < NPUSH; k++) begin
      if (alloc_i[k]) la_q[alloc_idx_i[k]] <= alloc_la_i[k];
    end
  end

  logic alloc_ok;
  always_comb begin
    alloc_ok = 1'b1;
    for (int k = 0; k < NPUSH; k++) begin
      if (alloc_i[k]) begin
        if (32'(alloc_idx_i[k]) >= MSHRS || busy_q[alloc_idx_i[k]]) alloc_ok = 1'b0;
        for (int j = 0; j < k; j++) begin
          if (alloc_i[j] && alloc_idx_i[j] == alloc_idx_i[k]) alloc_ok = 1'b0;
        end
      end
    end
  end

  // ---- the slave ---------------------------------------------------------------------------
  // sl_*: the reads of the current epoch; st_*: with RESETS, the reads that were out at the
  // last reset, whose beats still come (with the arid's old epoch).
  logic [MSHRS-1:0]              sl_out_q, sl_err_q, st_out_q;
  logic [MSHRS-1:0][BEAT_W-1:0]  sl_n_q, st_n_q;    // beats sent
  logic [MSHRS-1:0][EPOCH_W-1:0] sl_ep_q, st_ep_q;  // the epoch of the arid
  logic [MSHRS-1:0]              n_out, n_err, n_st_out;
  logic [MSHRS-1:0][BEAT_W-1:0]  n_n, n_st_n;
  logic [MIDX_W-1:0]             rid_idx;
  logic [EPOCH_W-1:0]            rid_ep;
  logic                          rb_cur, rb_stale;  // the beat is of a current / a stale read
  logic                          p_rst_q;           // rst_ni in the clock before
  assign rid_idx  = m_axi_rid[MIDX_W-1:0];
  assign rid_ep   = m_axi_rid[ID_W-1:MIDX_W];
  assign rb_cur   = 32'(rid_idx) < MSHRS && sl_out_q[rid_idx] && rid_ep == sl_ep_q[rid_idx];
  assign rb_stale = 32'(rid_idx) < MSHRS && st_out_q[rid_idx] && rid_ep == st_ep_q[rid_idx];

  always_comb begin
    n_out    = sl_out_q;
    n_err    = sl_err_q;
    n_n      = sl_n_q;
    n_st_out = st_out_q;
    n_st_n   = st_n_q;
    if (m_axi_rvalid && rready) begin
      if (rb_cur) begin
        n_n[rid_idx]   = m_axi_rlast ? '0 : sl_n_q[rid_idx] + BEAT_W'(1);
        n_err[rid_idx] = !m_axi_rlast && (sl_err_q[rid_idx] || m_axi_rresp[1]);
        if (m_axi_rlast) n_out[rid_idx] = 1'b0;
      end else if (rb_stale) begin
        n_st_n[rid_idx] = m_axi_rlast ? '0 : st_n_q[rid_idx] + BEAT_W'(1);
        if (m_axi_rlast) n_st_out[rid_idx] = 1'b0;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    p_rst_q <= rst_ni;
    if (!started_q) begin
      sl_out_q <= '0;
      sl_err_q <= '0;
      sl_n_q   <= '0;
      st_out_q <= '0;
      st_n_q   <= '0;
    end else if (!rst_ni) begin
      // a reset: the reads out become stale (each index had none stale: see the assumptions)
      for (int m = 0; m < MSHRS; m++) begin
        st_out_q[m] <= n_out[m] || n_st_out[m];
        st_n_q[m]   <= n_out[m] ? n_n[m] : n_st_n[m];
        if (n_out[m]) st_ep_q[m] <= sl_ep_q[m];
      end
      sl_out_q <= '0;
      sl_err_q <= '0;
      sl_n_q   <= '0;
    end else begin
      sl_out_q <= n_out;
      sl_err_q <= n_err;
      sl_n_q   <= n_n;
      st_out_q <= n_st_out;
      st_n_q   <= n_st_n;
      if (arvalid && m_axi_arready) begin
        sl_out_q[arid[MIDX_W-1:0]] <= 1'b1;
        sl_ep_q[arid[MIDX_W-1:0]]  <= arid[ID_W-1:MIDX_W];
      end
    end
  end

  always_comb begin
    // RESETS: a reset may start when no read of the epoch before is out (a read returns before
    // 2^EPOCH_W - 1 = 1 further reset: cache_axi_read's requirement)
    if (started_q && (!RESETS || (p_rst_q && st_out_q != '0))) assume (rst_ni);
    assume (alloc_ok);
    if (EARLY_WR && NPUSH == 1) begin
      assume (!alloc_i[0] || alloc_wr[0]);
      assume (!alloc_wr[0] || busy_q != {MSHRS{1'b1}});
    end
    if (m_axi_rvalid) begin
      assume (rb_cur || rb_stale);
      assume (m_axi_rlast == (rb_cur ? sl_n_q[rid_idx] == BEAT_W'(BEATS - 1)
                                     : st_n_q[rid_idx] == BEAT_W'(BEATS - 1)));
    end
  end

  // ---- the AR queue and registers: where each index is ------------------------------------
  localparam int unsigned CNT_W = $clog2(MSHRS + 1);
  logic [MSHRS-1:0][CNT_W:0] seen;
  logic                      q_exact;
  int                        e;
  logic                      reg_v [2];
  logic [MIDX_W-1:0]         reg_idx [2];
  if (AR_REG) begin : g_regs
    assign reg_v[0]   = u_dut.g_ar_reg.ap_v_q;
    assign reg_idx[0] = u_dut.g_ar_reg.ap_idx_q;
    assign reg_v[1]   = u_dut.g_ar_reg.ar_v_q;
    assign reg_idx[1] = u_dut.g_ar_reg.ar_id_q[MIDX_W-1:0];
  end else begin : g_no_regs
    assign reg_v[0]   = 1'b0;
    assign reg_idx[0] = '0;
    assign reg_v[1]   = 1'b0;
    assign reg_idx[1] = '0;
  end

  always_comb begin
    seen = '0;
    for (int j = 0; j < MSHRS; j++) begin
      e = int'(u_dut.u_arq.rp_q) + j;
      if (e >= int'(MSHRS)) e = e - int'(MSHRS);
      if (j < int'(u_dut.u_arq.cnt_q) && int'(u_dut.u_arq.mem_q[e]) < int'(MSHRS))
        seen[u_dut.u_arq.mem_q[e]] = seen[u_dut.u_arq.mem_q[e]] + (CNT_W+1)'(1);
    end
    for (int r = 0; r < 2; r++) begin
      if (reg_v[r] && int'(reg_idx[r]) < int'(MSHRS))
        seen[reg_idx[r]] = seen[reg_idx[r]] + (CNT_W+1)'(1);
    end
    q_exact = 1'b1;
    for (int m = 0; m < MSHRS; m++) begin
      if (seen[m] != (CNT_W+1)'(u_dut.u_assert.pend_q[m])) q_exact = 1'b0;
    end
    for (int j = 0; j < MSHRS; j++) begin
      e = int'(u_dut.u_arq.rp_q) + j;
      if (e >= int'(MSHRS)) e = e - int'(MSHRS);
      if (j < int'(u_dut.u_arq.cnt_q) && int'(u_dut.u_arq.mem_q[e]) >= int'(MSHRS)) q_exact = 1'b0;
    end
    for (int r = 0; r < 2; r++) begin
      if (reg_v[r] && int'(reg_idx[r]) >= int'(MSHRS)) q_exact = 1'b0;
    end
  end

  // the slave's reads against the shadow and the module's counts
  logic s_exact;
  always_comb begin
    s_exact = (sl_out_q == u_dut.u_assert.out_q) && (sl_err_q == u_dut.u_assert.err_q)
              && (sl_n_q == u_dut.u_assert.nbeat_q);
    for (int m = 0; m < MSHRS; m++) begin
      if (u_dut.beat_q[m] != sl_n_q[m] || u_dut.rerr_q[m] != sl_err_q[m]) s_exact = 1'b0;
      if (sl_out_q[m] && sl_ep_q[m] != u_dut.epoch_q) s_exact = 1'b0;
      if (!sl_out_q[m] && (sl_n_q[m] != '0 || sl_err_q[m])) s_exact = 1'b0;
    end
  end

  // the stale reads' epoch is not the current one (checked in reset too: it is what a reset
  // leaves behind)
  logic st_exact;
  always_comb begin
    st_exact = 1'b1;
    for (int m = 0; m < MSHRS; m++) begin
      if (st_out_q[m] && st_ep_q[m] == u_dut.epoch_q) st_exact = 1'b0;
      if (!st_out_q[m] && st_n_q[m] != '0) st_exact = 1'b0;
    end
  end

  // the AR registers carry the epoch and their MSHR's line (AR_REG)
  logic ar_reg_ok;
  if (AR_REG) begin : g_reg_ok
    assign ar_reg_ok = !u_dut.g_ar_reg.ar_v_q
                       || (u_dut.g_ar_reg.ar_id_q[ID_W-1:MIDX_W] == u_dut.epoch_q
                           && u_dut.g_ar_reg.ar_addr_q
                              == {la_q[u_dut.g_ar_reg.ar_id_q[MIDX_W-1:0]], {OFF_W{1'b0}}});
  end else begin : g_no_reg_ok
    assign ar_reg_ok = 1'b1;
  end

  always_ff @(posedge clk_i) begin
    if (started_q) begin
      inv_stale: assert (st_exact && u_dut.in_rst_q == !p_rst_q);
    end
    if (rst_ni) begin
      inv_busy:  assert (busy_q == (u_dut.u_assert.pend_q | u_dut.u_assert.out_q)
                         && (u_dut.u_assert.pend_q & u_dut.u_assert.out_q) == '0);
      inv_queue: assert (q_exact && ar_reg_ok);
      inv_slave: assert (s_exact);
      ar_line:   assert (!arvalid || araddr == {la_q[arid[MIDX_W-1:0]], {OFF_W{1'b0}}});
      rready_one: assert (rready);
      stale_ignored: assert (!(m_axi_rvalid && rb_stale) || !r_cur);
    end
  end

  // ---- covers ------------------------------------------------------------------------------
  logic err_seen_q, reuse_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      err_seen_q <= 1'b0;
      reuse_q    <= 1'b0;
    end else begin
      if (r_acc && r_last && r_bad) err_seen_q <= 1'b1;
      if (r_acc && r_last && !r_bad && err_seen_q) reuse_q <= 1'b1;
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      c_all_busy:   cover (busy_q == {MSHRS{1'b1}});
      c_ar_held:    cover (arvalid && !m_axi_arready && (sl_out_q != '0));
      c_interleave: cover (r_acc && !r_last && sl_n_q[r_idx] == '0 && (sl_out_q & ~(MSHRS'(1) << r_idx)) != '0
                           && sl_n_q != '0);
      c_err_line:   cover (r_acc && r_last && r_bad);
      c_after_err:  cover (reuse_q && busy_q == {MSHRS{1'b1}});
      c_all_lanes:  cover (alloc_i == {NPUSH{1'b1}});
      c_stale_beat: cover (m_axi_rvalid && rb_stale && sl_out_q[rid_idx]);
    end
  end

endmodule
