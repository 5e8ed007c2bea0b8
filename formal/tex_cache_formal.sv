// SPDX-License-Identifier: Apache-2.0
// tex_cache_formal: the texture cache (tex_cache) under SymbiYosys (formal/tex_cache.sby), for
// its tag path: every response carries the tag of the oldest request not yet answered, none
// lost, duplicated or reordered (the bound tex_cache_assert's rsp_tag_order, rsp_owed,
// owed_bound), with the request FIFO and output buffer checks (circ_queue_assert, bound into
// u_fifo and u_out) and tex_cache_assert's queue checks that the .sby keeps.
//
// The lookup's outcome, the memory and the data are cut (the .sby script): the hit or victim way
// (lk_way), the all-or-nothing decision's two reasons to wait (lk_blocked, mshr_short), the head
// pass's pending and error bits (hd_pend, hd_bad) and the texels selected from the data RAMs
// (u_data.h1_texel) are free values each clock, so Yosys drops the directory, the MSHRs, the
// AXI read machinery (all but its reset sweep, which holds req_ready_o low) and the data RAMs;
// the checks about those are removed from this model after the front end has listed them
// (simulation checks them).  So the tags are proven for every hit, miss, replay, memory latency
// and error pattern, whatever the data.  Free: the requests (addresses, hence the passes a
// request takes, and tags), the response stream's ready, the AXI inputs.  Assumed: reset in the
// first clock; resets may come again at any time.
//
// Induction invariants (here: they name the cache's internal stages and tex_cache_data's tag
// queue): walking the stages from the output buffer back to the entry register, counting
// requests by their last passes (a request in the entry register counts there), the count is the
// requests owed (inv_count), which is the tag queue's fill (inv_tq_count, with
// tex_cache_assert's count of it); the tracked request's tag is in the tag queue as many entries
// behind its read pointer as requests are ahead of it (inv_tq_tag); the queue's registered read
// is its head entry, except in the clock after a request was written there (inv_tq_read), and
// that request is then in the entry register (inv_tq_push); the FIFO and the output buffer never
// hold more than their room (inv_fifo_room, inv_out_room); the FIFO's registered read is its
// third entry (inv_peek, which refills the register behind the head).
module tex_cache_formal #(
  parameter int unsigned ADDR_W     = 6,   // tex_cache's parameters, small
  parameter int unsigned LINE_BYTES = 8,
  parameter int unsigned DATA_W     = 32,
  parameter int unsigned SETS       = 2,
  parameter int unsigned WAYS       = 2,
  parameter int unsigned MSHRS      = 4,
  parameter int unsigned FIFO_DEPTH = 4,
  parameter int unsigned ID_W       = 3,
  parameter int unsigned TAG_W      = 2
) (
  input logic                   clk_i,
  input logic                   rst_ni,
  input logic                   req_valid_i,
  input logic [3:0][ADDR_W-1:0] req_addr_i,
  input logic [TAG_W-1:0]       req_tag_i,
  input logic                   rsp_ready_i,
  input logic                   m_axi_arready,
  input logic [ID_W-1:0]        m_axi_rid,
  input logic [DATA_W-1:0]      m_axi_rdata,
  input logic [1:0]             m_axi_rresp,
  input logic                   m_axi_rlast,
  input logic                   m_axi_rvalid,
  input logic                   clr_stats_i
);

  localparam int unsigned OUT_DEPTH = 4;   // tex_cache's output buffer and pass queue
  localparam int unsigned PQ_DEPTH  = 4;
  localparam int unsigned FP_W      = $clog2(FIFO_DEPTH);

  logic                   req_ready, rsp_valid, rsp_err, arvalid, rready;
  logic [3:0][31:0]       rsp_texel;
  logic [TAG_W-1:0]       rsp_tag;
  logic [ID_W-1:0]        arid;
  logic [ADDR_W-1:0]      araddr;
  logic [7:0]             arlen;
  logic [2:0]             arsize;
  logic [1:0]             arburst;
  logic [47:0]            st_req, st_qhit, st_lk, st_miss, st_thit, st_bytes;

  tex_cache #(
    .ADDR_W(ADDR_W), .DATA_W(DATA_W), .LINE_BYTES(LINE_BYTES), .SETS(SETS), .WAYS(WAYS),
    .MSHRS(MSHRS), .FIFO_DEPTH(FIFO_DEPTH), .ID_W(ID_W), .TAG_W(TAG_W)
  ) u_dut (
    .clk_i, .rst_ni,
    .req_valid_i, .req_ready_o(req_ready), .req_addr_i, .req_tag_i,
    .rsp_valid_o(rsp_valid), .rsp_ready_i, .rsp_texel_o(rsp_texel), .rsp_err_o(rsp_err),
    .rsp_tag_o(rsp_tag),
    .m_axi_arid(arid), .m_axi_araddr(araddr), .m_axi_arlen(arlen), .m_axi_arsize(arsize),
    .m_axi_arburst(arburst), .m_axi_arvalid(arvalid), .m_axi_arready,
    .m_axi_rid, .m_axi_rdata, .m_axi_rresp, .m_axi_rlast, .m_axi_rvalid, .m_axi_rready(rready),
    .clr_stats_i,
    .stat_requests_o(st_req), .stat_quad_hits_o(st_qhit), .stat_lookups_o(st_lk),
    .stat_line_misses_o(st_miss), .stat_texel_hits_o(st_thit), .stat_bytes_o(st_bytes));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));
  // ---- the stages, oldest first: requests counted by their last passes ---------------------
  // (a pass in the FIFO is a pass_t word: its last bit is bit 0)
  localparam int unsigned TQ_W = $clog2(1 + PQ_DEPTH + FIFO_DEPTH + OUT_DEPTH);  // tex_cache's
  logic trk;
  logic [TAG_W-1:0] trk_tag;
  int   trk_ahead, owed;
  assign trk       = u_dut.u_assert.tg_trk_q;
  assign trk_tag   = u_dut.u_assert.tg_tag_q;
  assign trk_ahead = int'(u_dut.u_assert.tg_ahead_q);
  assign owed      = int'(u_dut.u_assert.tg_owed_q);

  int n_req;      // requests in the stages walked so far
  always_comb begin
    logic [FP_W-1:0] fa;
    logic [2:0]      pa;
    n_req = int'(u_dut.u_data.out_cnt);                             // output buffer (answers)
    if (u_dut.u_data.h1_valid_q && u_dut.u_data.h1_last_q) n_req++; // select stage
    if (u_dut.u_data.h0_valid_q && u_dut.u_data.h0_last_q) n_req++; // head read stage
    for (int i = 0; i < FIFO_DEPTH; i++) begin                      // request FIFO
      fa = FP_W'(u_dut.u_fifo.rp_q + FP_W'(i));
      if (i < int'(u_dut.fifo_cnt) && u_dut.u_fifo.mem_q[fa][0]) n_req++;
    end
    if (u_dut.cm_valid_q && u_dut.cm_pass_q.last) n_req++;         // commit register
    for (int i = 0; i < PQ_DEPTH; i++) begin                        // pass queue
      pa = u_dut.u_front.pq_rp_q + 3'(i);
      if (i < int'(3'(u_dut.u_front.pq_wp_q - u_dut.u_front.pq_rp_q))
          && u_dut.u_front.pq_q[pa[1:0]].last) n_req++;
    end
    if (u_dut.u_front.s0_valid_q) n_req++;                          // entry register
  end

  // the tag queue (tex_cache_data): the tracked request's entry, the head entry
  logic [TQ_W-1:0]  tq_rp, tq_wp, tq_trk_a;
  logic [TAG_W-1:0] tq_trk_tag, tq_head_tag;
  assign tq_rp       = u_dut.u_data.tq_rp_q;
  assign tq_wp       = u_dut.u_data.tq_wp_q;
  assign tq_trk_a    = TQ_W'(tq_rp + TQ_W'(trk_ahead));
  assign tq_trk_tag  = u_dut.u_data.tq_mem[tq_trk_a];
  assign tq_head_tag = u_dut.u_data.tq_mem[tq_rp];

  always_comb begin
    if (rst_ni) begin
      inv_count:     assert (n_req == owed);
      inv_tq_count:  assert (owed == int'(TQ_W'(tq_wp - tq_rp))
                             && owed == int'(u_dut.u_assert.tq_cnt_q));
      inv_tq_tag:    assert (!trk || tq_trk_tag == trk_tag);
      inv_tq_read:   assert (owed == 0 || u_dut.u_data.tq_rd_q == tq_head_tag
                             || (u_dut.u_assert.p_tq_push_q
                                 && u_dut.u_assert.p_tq_wp_q == tq_rp));
      inv_tq_push:   assert (!u_dut.u_assert.p_tq_push_q
                             || (u_dut.u_front.s0_valid_q
                                 && tq_wp == TQ_W'(u_dut.u_assert.p_tq_wp_q + TQ_W'(1))));
      inv_fifo_room: assert (int'(u_dut.fifo_cnt) + int'(u_dut.cm_valid_q) <= FIFO_DEPTH);
      inv_peek:      assert (int'(u_dut.fifo_cnt) < 3
                             || u_dut.rd_eff == u_dut.u_fifo.mem_q[FP_W'(u_dut.u_fifo.rp_q + FP_W'(2))]);
      inv_out_room:  assert (int'(u_dut.u_data.out_cnt) + int'(u_dut.u_data.h0_valid_q)
                             + int'(u_dut.u_data.h1_valid_q) <= OUT_DEPTH);
    end
  end

  // ---- covers -------------------------------------------------------------------------------
  // The tracked request answered after a request of several passes ahead of it was; answered
  // with the FIFO full behind it; answered while the output buffer is full; a response stalled.
  logic split_seen_q;   // a request of several passes entered the FIFO since the reset
  always_ff @(posedge clk_i) begin
    if (!rst_ni) split_seen_q <= 1'b0;
    else if (u_dut.cm_valid_q && !u_dut.cm_pass_q.last) split_seen_q <= 1'b1;
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      c_trk_after_split: cover (u_dut.u_assert.tg_out && split_seen_q);
      c_trk_fifo_full:   cover (u_dut.u_assert.tg_out
                                && int'(u_dut.fifo_cnt) == FIFO_DEPTH);
      c_trk_out_full:    cover (u_dut.u_assert.tg_out && u_dut.u_data.out_cnt == 3'(OUT_DEPTH));
      c_rsp_stall:       cover (rsp_valid && !rsp_ready_i && trk && trk_ahead == 0);
    end
  end

  logic unused;
  assign unused = ^{req_ready, rsp_err, rsp_texel, rsp_tag, arid, araddr, arlen, arsize, arburst,
                    arvalid, rready, st_req, st_qhit, st_lk, st_miss, st_thit, st_bytes};

endmodule
