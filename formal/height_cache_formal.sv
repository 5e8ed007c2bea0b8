// SPDX-License-Identifier: Apache-2.0
// height_cache_formal: height_cache under SymbiYosys (formal/height_cache.sby), small (2 sets of
// 2 ways, 4-byte lines read in 2 beats, 2 MSHRs), with free lookups (the client's 16-bit
// lookups aligned: its obligation) and a model of an AXI slave: arready free; after an AR it
// returns exactly BEATS beats with the arid it got (any interleaving, any rresp, any data),
// rlast on the last of them only, no beat for an MSHR without a read out; rready is 1.  Reset
// comes in the first clock only.  The properties are the bound height_cache_assert's (among
// them the merge rule: mshr_unique, merge_no_alloc; the MSHRs' return to the free pool:
// fill_state_once), cache_axi_read_assert's and circ_queue_assert's, and the wrapper's own:
//   mshr_read   an MSHR is in MSHR_WAIT exactly while its read is pend or out in
//               cache_axi_read's shadow (so a beat is accepted only for a waiting MSHR, and
//               its line's last beat ends the wait once);
//   err_marks   the line's last beat leaves its MSHR in MSHR_ERR exactly when a beat of the line
//               carried an error, else in MSHR_FILL;
//   ar_line     the AR carries its MSHR's line address;
// and the induction invariants: inv_queue (the AR queue holds exactly the pend MSHRs' indices),
// inv_slave (the slave's reads are the shadow's, beats and errors counted alike), inv_dir (no
// busy MSHR's line, nor the line of the miss waiting in stage 3, is valid in the directory),
// inv_rw (a busy MSHR's copy of its set's replacement word, valid bits and round-robin pointer,
// is the set's word in the RAM, and so are stage 2's copy for a lookup that may allocate and
// stage 3's for its miss) and inv_fill (a fill's valid bits and pointer are its set's).
module height_cache_formal #(
  parameter int unsigned ADDR_W     = 5,   // lines: 3 bits (2 sets, tag 2 bits)
  parameter int unsigned DATA_W     = 16,
  parameter int unsigned LINE_BYTES = 4,   // 2 beats
  parameter int unsigned SETS       = 2,
  parameter int unsigned WAYS       = 2,
  parameter int unsigned MSHRS      = 2,
  parameter int unsigned ERR_HOLD   = 1,
  // derived (not to be overridden)
  parameter int unsigned MIDX_W     = (MSHRS > 1) ? $clog2(MSHRS) : 1,
  parameter int unsigned ID_W       = MIDX_W + 1,   // one epoch bit
  parameter int unsigned OFF_W      = $clog2(LINE_BYTES),
  parameter int unsigned SET_W      = $clog2(SETS),
  parameter int unsigned LA_W       = ADDR_W - OFF_W,
  parameter int unsigned BEATS      = LINE_BYTES * 8 / DATA_W,
  parameter int unsigned BEAT_W     = (BEATS > 1) ? $clog2(BEATS) : 1
) (
  input logic              clk_i,
  input logic              rst_ni,
  input logic              lk_valid_i,
  input logic [ADDR_W-1:0] lk_addr_i,
  input logic              lk_wide_i,
  input logic              m_axi_arready,
  input logic [ID_W-1:0]   m_axi_rid,
  input logic [DATA_W-1:0] m_axi_rdata,
  input logic [1:0]        m_axi_rresp,
  input logic              m_axi_rlast,
  input logic              m_axi_rvalid,
  input logic              clr_stats_i
);

  import cache_pkg::*;

  localparam int unsigned EPOCH_W = ID_W - MIDX_W;
  localparam int unsigned TAG_W   = LA_W - SET_W;
  localparam int unsigned WAY_W   = (WAYS > 1) ? $clog2(WAYS) : 1;  // (as height_cache's)
  localparam logic [$clog2(ERR_HOLD + 1)-1:0] ERRC1 = 1;

  logic              rs_valid, rs_hit, rs_err;
  logic [15:0]       rs_data;
  logic [ID_W-1:0]   arid;
  logic [ADDR_W-1:0] araddr;
  logic              arvalid, rready;

  height_cache #(
    .ADDR_W(ADDR_W), .DATA_W(DATA_W), .LINE_BYTES(LINE_BYTES), .SETS(SETS), .WAYS(WAYS),
    .MSHRS(MSHRS), .ID_W(ID_W), .ERR_HOLD(ERR_HOLD)
  ) u_dut (
    .clk_i, .rst_ni, .lk_valid_i, .lk_addr_i, .lk_wide_i,
    .rs_valid_o(rs_valid), .rs_hit_o(rs_hit), .rs_err_o(rs_err), .rs_data_o(rs_data),
    .m_axi_arid(arid), .m_axi_araddr(araddr), .m_axi_arlen(), .m_axi_arsize(),
    .m_axi_arburst(), .m_axi_arvalid(arvalid), .m_axi_arready,
    .m_axi_rid, .m_axi_rdata, .m_axi_rresp, .m_axi_rlast, .m_axi_rvalid,
    .m_axi_rready(rready),
    .clr_stats_i, .stat_hits_o(), .stat_misses_o(), .stat_bytes_o(), .stat_lines_o());

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // ---- the slave ---------------------------------------------------------------------------
  logic [MSHRS-1:0]              sl_out_q, sl_err_q;
  logic [MSHRS-1:0][BEAT_W-1:0]  sl_n_q;     // beats sent
  logic [MSHRS-1:0][EPOCH_W-1:0] sl_ep_q;    // the epoch of the arid
  logic [MIDX_W-1:0]             rid_idx;
  assign rid_idx = m_axi_rid[MIDX_W-1:0];

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      sl_out_q <= '0;
      sl_err_q <= '0;
      sl_n_q   <= '0;
    end else begin
      if (m_axi_rvalid && rready) begin
        sl_n_q[rid_idx]   <= m_axi_rlast ? '0 : sl_n_q[rid_idx] + BEAT_W'(1);
        sl_err_q[rid_idx] <= !m_axi_rlast && (sl_err_q[rid_idx] || m_axi_rresp[1]);
        if (m_axi_rlast) sl_out_q[rid_idx] <= 1'b0;
      end
      if (arvalid && m_axi_arready) begin
        sl_out_q[arid[MIDX_W-1:0]] <= 1'b1;
        sl_ep_q[arid[MIDX_W-1:0]]  <= arid[ID_W-1:MIDX_W];
      end
    end
  end

  always_comb begin
    if (started_q) assume (rst_ni);
    assume (!(lk_valid_i && lk_wide_i && lk_addr_i[0]));
    if (m_axi_rvalid) begin
      assume (32'(rid_idx) < MSHRS && sl_out_q[rid_idx]);
      assume (m_axi_rid[ID_W-1:MIDX_W] == sl_ep_q[rid_idx]);
      assume (m_axi_rlast == (sl_n_q[rid_idx] == BEAT_W'(BEATS - 1)));
    end
  end

  // ---- the MSHRs against the AXI shadow and the slave ---------------------------------------
  localparam int unsigned CNT_W = $clog2(MSHRS + 1);
  logic [MSHRS-1:0]          pend, out, waiting;
  logic [MSHRS-1:0][CNT_W:0] seen;
  logic                      q_exact, s_exact;
  int                        e;
  assign pend = u_dut.u_axi.u_assert.pend_q;
  assign out  = u_dut.u_axi.u_assert.out_q;
  always_comb begin
    for (int m = 0; m < MSHRS; m++) waiting[m] = u_dut.mshr_state_q[m] == MSHR_WAIT;
  end

  always_comb begin
    seen    = '0;
    q_exact = 1'b1;
    for (int j = 0; j < MSHRS; j++) begin
      e = int'(u_dut.u_axi.u_arq.rp_q) + j;
      if (e >= int'(MSHRS)) e = e - int'(MSHRS);
      if (j < int'(u_dut.u_axi.u_arq.cnt_q)) begin
        if (int'(u_dut.u_axi.u_arq.mem_q[e]) < int'(MSHRS))
          seen[u_dut.u_axi.u_arq.mem_q[e]] = seen[u_dut.u_axi.u_arq.mem_q[e]] + (CNT_W+1)'(1);
        else q_exact = 1'b0;
      end
    end
    for (int m = 0; m < MSHRS; m++) begin
      if (seen[m] != (CNT_W+1)'(pend[m])) q_exact = 1'b0;
    end
    s_exact = (sl_out_q == out) && (sl_err_q == u_dut.u_axi.u_assert.err_q)
              && (sl_n_q == u_dut.u_axi.u_assert.nbeat_q);
    for (int m = 0; m < MSHRS; m++) begin
      if (u_dut.u_axi.beat_q[m] != sl_n_q[m] || u_dut.u_axi.rerr_q[m] != sl_err_q[m])
        s_exact = 1'b0;
      if (sl_out_q[m] && sl_ep_q[m] != u_dut.u_axi.epoch_q) s_exact = 1'b0;
      if (!sl_out_q[m] && (sl_n_q[m] != '0 || sl_err_q[m])) s_exact = 1'b0;
    end
  end

  // ---- the directory: valid lines are in no busy MSHR --------------------------------------
  logic [WAYS-1:0][SETS-1:0][TAG_W-1:0] tags;   // the tag RAMs
  for (genvar w = 0; w < WAYS; w++) begin : g_tags
    for (genvar s = 0; s < SETS; s++) begin : g_set
      assign tags[w][s] = u_dut.g_way[w].u_tags.mem_q[s][0];
    end
  end

  logic [SETS-1:0][WAYS+WAY_W-1:0] vword;  // the valid-bit RAM: {pointer, valid bits} per set
  for (genvar s = 0; s < SETS; s++) begin : g_vword
    assign vword[s] = u_dut.u_valid.mem_q[s][0];
  end

  // Line `la` is valid in the directory.
  function automatic logic cached(input logic [LA_W-1:0] la);
    cached = 1'b0;
    for (int w = 0; w < WAYS; w++) begin
      if (vword[la[SET_W-1:0]][w] && tags[w][la[SET_W-1:0]] == la[LA_W-1:SET_W]) cached = 1'b1;
    end
  endfunction

  logic dir_ok, rw_ok, fill_ok;
  always_comb begin
    dir_ok = 1'b1;
    rw_ok  = 1'b1;
    for (int i = 0; i < MSHRS; i++) begin
      if (u_dut.mshr_state_q[i] != MSHR_FREE) begin
        if (cached(u_dut.mshr_la_q[i])) dir_ok = 1'b0;
        if (u_dut.mshr_rw_q[i] != vword[u_dut.mshr_la_q[i][SET_W-1:0]]) rw_ok = 1'b0;
      end
    end
    if (u_dut.s2_valid_q && !u_dut.s2_conflict_q
        && u_dut.s2_rw_q != vword[u_dut.s2_la[SET_W-1:0]])
      rw_ok = 1'b0;
    if (u_dut.s3_miss_q) begin
      if (cached(u_dut.s3_la_q)) dir_ok = 1'b0;
      if (u_dut.s3_rw_q != vword[u_dut.s3_la_q[SET_W-1:0]]) rw_ok = 1'b0;
    end
    fill_ok = !u_dut.fill_q || {u_dut.fill_ptr, u_dut.fill_vbits} == vword[u_dut.fill_set];
  end

  // the last beat of a line and its error, a clock later
  logic             p_last_q, p_bad_q;
  logic [MIDX_W-1:0] p_idx_q;
  always_ff @(posedge clk_i) begin
    p_last_q <= rst_ni && u_dut.r_acc && u_dut.r_last_beat;
    p_bad_q  <= sl_err_q[rid_idx] || m_axi_rresp[1];
    p_idx_q  <= u_dut.r_idx;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      mshr_read: assert (waiting == (pend | out) && (pend & out) == '0);
      err_marks: assert (!p_last_q || u_dut.mshr_state_q[p_idx_q]
                                      == (p_bad_q ? MSHR_ERR : MSHR_FILL));
      ar_line:   assert (!arvalid || araddr == {u_dut.mshr_la_q[arid[MIDX_W-1:0]], {OFF_W{1'b0}}});
      inv_queue: assert (q_exact);
      inv_slave: assert (s_exact);
      inv_dir:   assert (dir_ok);
      inv_rw:    assert (rw_ok);
      inv_fill:  assert (fill_ok);
    end
  end

  // ---- covers ------------------------------------------------------------------------------
  logic filled_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni)           filled_q <= 1'b0;
    else if (u_dut.fill_q) filled_q <= 1'b1;
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      c_merge:     cover (u_dut.s2_valid_q && !u_dut.s2_hit && (|u_dut.mshr_match)
                          && (waiting & u_dut.mshr_match) != '0);
      c_all_busy:  cover (u_dut.mshr_busy == '1 && u_dut.s3_miss_q);
      c_hit:       cover (rs_valid && rs_hit && filled_q);
      c_err:       cover (rs_valid && rs_err);
      c_err_freed: cover (u_dut.mshr_state_q[0] == MSHR_ERR && u_dut.mshr_errc_q[0] == ERRC1);
    end
  end

endmodule
