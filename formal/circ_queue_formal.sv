// SPDX-License-Identifier: Apache-2.0
// circ_queue_formal: circ_queue alone under SymbiYosys (formal/circ_queue.sby).  Its inputs are
// free, except what a user of the queue promises (assumed here, asserted by circ_queue_assert in
// every real use): pushes only into the room left after this clock's pops, at most count_o (and
// NPOP) pops, early writes only into free entries, and reset in the first clock.  The
// properties are the bound circ_queue_assert's, and with INIT_SEQ (the queue as a free list of
// the indices 0 .. DEPTH - 1) the wrapper's own:
//   fl_exact   every index is exactly once either in the queue or taken by the user (own_q: the
//              indices popped and not yet pushed back), so none is lost or duplicated;
//   fl_total   count_o plus the indices taken is DEPTH.
// In that mode the user pushes back only indices it holds, each once (assumed), with the data
// written at the push (wr_i = push_i, as the caches' free list).
module circ_queue_formal #(
  parameter int unsigned WIDTH    = 3,     // entry width
  parameter int unsigned DEPTH    = 4,     // entries
  parameter int unsigned NPUSH    = 1,     // pushes per clock at most
  parameter int unsigned NPOP     = 1,     // pops per clock at most
  parameter bit          INIT_SEQ = 1'b0,  // the free-list mode (above)
  parameter bit          ASYNC_RD = 1'b1,  // rdata_o read asynchronously
  parameter int unsigned PEEK     = 0,     // peek_o: entry PEEK, registered
  parameter bit          EARLY_WR = 1'b1,  // 1: wr_i free (early writes); 0: wr_i = push_i
  // derived (not to be overridden)
  parameter int unsigned CNT_W    = $clog2(DEPTH + 1),
  parameter int unsigned POP_W    = $clog2(NPOP + 1)
) (
  input logic                        clk_i,
  input logic                        rst_ni,
  input logic [NPUSH-1:0]            push_i,
  input logic [NPUSH-1:0]            wr_free_i,   // wr_i when EARLY_WR
  input logic [NPUSH-1:0][WIDTH-1:0] wdata_i,
  input logic [POP_W-1:0]            pop_n_i
);

  logic [NPUSH-1:0]           wr;
  logic [NPOP-1:0][WIDTH-1:0] rdata;
  logic [WIDTH-1:0]           peek;
  logic [CNT_W-1:0]           count;
  assign wr = (EARLY_WR && !INIT_SEQ) ? wr_free_i : push_i;

  circ_queue #(.WIDTH(WIDTH), .DEPTH(DEPTH), .NPUSH(NPUSH), .NPOP(NPOP), .INIT_SEQ(INIT_SEQ),
               .ASYNC_RD(ASYNC_RD), .PEEK(PEEK)) u_dut (
    .clk_i, .rst_ni, .push_i, .wr_i(wr), .wdata_i, .pop_n_i, .rdata_o(rdata), .peek_o(peek),
    .count_o(count));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // ---- the user's promises -----------------------------------------------------------------
  int n_push, left;
  logic wr_ok;
  always_comb begin
    n_push = 0;
    left   = int'(count) - int'(pop_n_i);
    wr_ok  = 1'b1;
    for (int k = 0; k < NPUSH; k++) begin
      if (wr[k] && left + n_push >= int'(DEPTH)) wr_ok = 1'b0;
      if (push_i[k]) n_push = n_push + 1;
    end
  end

  // ---- the free list: indices the user holds -----------------------------------------------
  logic [DEPTH-1:0] own_q, own_d;
  logic             push_owned;   // every pushed index is held, in range, pushed once
  always_comb begin
    own_d      = own_q;
    push_owned = 1'b1;
    for (int j = 0; j < NPOP; j++) begin
      if (j < int'(pop_n_i) && int'(rdata[j]) < int'(DEPTH)) own_d[rdata[j]] = 1'b1;
    end
    for (int k = 0; k < NPUSH; k++) begin
      if (push_i[k]) begin
        if (int'(wdata_i[k]) >= int'(DEPTH) || !own_q[wdata_i[k]]) push_owned = 1'b0;
        for (int m = 0; m < k; m++) begin
          if (push_i[m] && wdata_i[m] == wdata_i[k]) push_owned = 1'b0;
        end
        if (int'(wdata_i[k]) < int'(DEPTH)) own_d[wdata_i[k]] = 1'b0;
      end
    end
  end
  always_ff @(posedge clk_i) begin
    if (!rst_ni) own_q <= '0;
    else         own_q <= own_d;
  end

  // how often each index is in the queue (entries head .. head + count - 1)
  logic [DEPTH-1:0][CNT_W:0] seen;
  logic                      exact;
  int                        owned, e;
  always_comb begin
    seen = '0;
    for (int j = 0; j < DEPTH; j++) begin
      e = int'(u_dut.rp_q) + j;
      if (e >= int'(DEPTH)) e = e - int'(DEPTH);
      if (j < int'(count) && int'(u_dut.mem_q[e]) < int'(DEPTH))
        seen[u_dut.mem_q[e]] = seen[u_dut.mem_q[e]] + (CNT_W+1)'(1);
    end
    exact = 1'b1;
    owned = 0;
    for (int i = 0; i < DEPTH; i++) begin
      if (seen[i] + (CNT_W+1)'(own_q[i]) != (CNT_W+1)'(1)) exact = 1'b0;
      owned = owned + int'(own_q[i]);
    end
  end

  always_comb begin
    assume (left >= 0 && int'(pop_n_i) <= int'(NPOP));
    assume (left + n_push <= int'(DEPTH));
    assume (wr_ok);
    if (INIT_SEQ) assume (push_owned);
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      fl_exact: assert (!INIT_SEQ || exact);
      fl_total: assert (!INIT_SEQ || int'(count) + owned == int'(DEPTH));
    end
  end

endmodule
