// SPDX-License-Identifier: Apache-2.0
// circ_queue_assert: the properties of circ_queue, bound into every instance (the `bind` at the
// end of this file), checked by simulation (Verilator --assert) and proven by `make formal`
// (formal/circ_queue.sby; docs/formal.md).  Immediate assertions only, in the form the formal
// flow's front end (Yosys read_slang) accepts.
//
//   no_overflow / no_underflow  the user pushes only into the room left after this clock's pops
//                               and pops at most count_o (and at most NPOP) entries;
//   wr_room                     an early write (wr_i) lands only in an entry that is free after
//                               this clock's pops (obligations of the user: the formal wrapper
//                               assumes them);
//   count_model                 count_o = pushes - pops since reset (from DEPTH with INIT_SEQ),
//                               never above DEPTH;
//   ptr_model                   the pointers stay below DEPTH and the tail is the head plus the
//                               count, modulo DEPTH;
//   data_order                  a tracked entry (a push picked freely in formal, every push that
//                               finds none tracked in simulation, the lowest lane first) is
//                               rdata_o[k] when k entries are ahead of it (k < NPOP, ASYNC_RD);
//   peek_order                  with PEEK > 0 peek_o is the tracked entry the clock after one in
//                               which it became entry PEEK of the queue;
//   peek_addr                   with PEEK > 0 the peek port's registered read-address
//                               candidates are the head plus PEEK plus 0 .. NPOP;
//   trk_inside, trk_in_mem      it stays inside the queue, unchanged at its place in the storage
//                               (the induction invariants).
// The tracked entry's value is the one its place holds after its push: the data of the last lane
// that writes there in that clock, else what an early write left there.
// The covers: full, empty again after full, a push at the last entry (the tail wraps), a push
// and a pop in one clock, every lane pushing and NPOP popping in one clock, the tracked entry
// leaving after the queue was full.
// The storage is read through a hierarchical reference (circ_queue.mem_q).
`ifndef SYNTHESIS
module circ_queue_assert #(
  parameter int unsigned WIDTH    = 8,     // circ_queue's parameters
  parameter int unsigned DEPTH    = 4,
  parameter int unsigned NPUSH    = 1,
  parameter int unsigned NPOP     = 1,
  parameter bit          INIT_SEQ = 1'b0,
  parameter bit          ASYNC_RD = 1'b1,
  parameter int unsigned PEEK     = 0,
  parameter int unsigned PTR_W    = 2,     // circ_queue's derived widths
  parameter int unsigned CNT_W    = 3,
  parameter int unsigned POP_W    = 1
) (
  input logic                        clk_i,
  input logic                        rst_ni,
  input logic [NPUSH-1:0]            push_i,
  input logic [NPUSH-1:0]            wr_i,
  input logic [NPUSH-1:0][WIDTH-1:0] wdata_i,
  input logic [POP_W-1:0]            pop_n_i,
  input logic [NPOP-1:0][WIDTH-1:0]  rdata_i,   // circ_queue's rdata_o
  input logic [WIDTH-1:0]            peek_i,    // peek_o
  input logic [CNT_W-1:0]            count_i,   // count_o
  input logic [PTR_W-1:0]            wp_i,      // wp_q: the tail
  input logic [PTR_W-1:0]            rp_i       // rp_q: the head
);

  localparam int unsigned PUSH_W = $clog2(NPUSH + 1);

  // With PEEK > 0: circ_queue's registered read-address candidates (pk_c_q[k], the peek
  // port's address after k pops) equal head + PEEK + k.
  logic pk_c_ok;
  if (PEEK > 0) begin : g_pk_c
    always_comb begin
      pk_c_ok = 1'b1;
      for (int unsigned k = 0; k <= NPOP; k++) begin
        if (32'(circ_queue.g_peek.pk_c_q[k]) != (32'(rp_i) + k + PEEK) % DEPTH) pk_c_ok = 1'b0;
      end
    end
  end else begin : g_no_pk_c
    assign pk_c_ok = 1'b1;
  end
  localparam int unsigned N_W    = CNT_W + 1;   // one bit wider than count_o: an overflow shows

  // ---- lanes: pushes below each lane, the user's obligations -------------------------------
  logic [NPUSH-1:0][PUSH_W-1:0] below;   // lanes below k that push
  logic [PUSH_W-1:0]            n_push;
  logic                         wr_ok;
  int                           left;    // entries that stay after this clock's pops
  always_comb begin
    n_push = '0;
    for (int k = 0; k < NPUSH; k++) begin
      below[k] = n_push;
      if (push_i[k]) n_push = n_push + PUSH_W'(1);
    end
    left  = int'(count_i) - int'(pop_n_i);
    wr_ok = 1'b1;
    for (int k = 0; k < NPUSH; k++) begin
      if (wr_i[k] && left + int'(below[k]) >= int'(DEPTH)) wr_ok = 1'b0;
    end
  end

  // ---- the count: pushes - pops since reset ------------------------------------------------
  logic [N_W-1:0] n_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) n_q <= INIT_SEQ ? N_W'(DEPTH) : '0;
    else         n_q <= n_q + N_W'(n_push) - N_W'(pop_n_i);
  end

  // the tail from the head and the count
  int tail;
  always_comb begin
    tail = int'(rp_i) + int'(count_i);
    if (tail >= int'(DEPTH)) tail = tail - int'(DEPTH);
  end

  // ---- the tracked entry -------------------------------------------------------------------
  // pick: which push to track.  Formal leaves it undriven (SymbiYosys makes an undriven wire a
  // free input); simulation tracks whenever it can.
  logic [NPUSH-1:0] pick;
`ifndef FORMAL
  assign pick = '1;
`endif
  logic             trk_q;
  logic [WIDTH-1:0] trk_data_q;
  logic [CNT_W-1:0] trk_ahead_q;   // entries ahead of it
  logic             trk_out;       // it leaves in this clock
  logic             trk_start;     // a push of this clock becomes the tracked entry
  logic [CNT_W-1:0] st_ahead;      // ... with that many ahead after this clock
  logic [WIDTH-1:0] st_data;       // ... and the value its place holds after this clock
  logic [PTR_W-1:0] st_addr;
  logic [NPUSH-1:0][PTR_W-1:0] pos;  // each lane's entry (circ_queue's pos, modelled anew)
  int               b;
  assign trk_out = trk_q && trk_ahead_q < CNT_W'(pop_n_i);
  always_comb begin
    for (int k = 0; k < NPUSH; k++) begin
      b = int'(wp_i) + int'(below[k]);
      if (b >= int'(DEPTH)) b = b - int'(DEPTH);
      pos[k] = PTR_W'(b);
    end
  end
  always_comb begin
    trk_start = 1'b0;
    st_ahead  = '0;
    st_addr   = '0;
    for (int k = NPUSH - 1; k >= 0; k--) begin   // the lowest picked lane wins
      if (push_i[k] && pick[k]) begin
        trk_start = !trk_q || trk_out;
        st_ahead  = CNT_W'(left + int'(below[k]));
        st_addr   = pos[k];
      end
    end
    st_data = circ_queue.mem_q[st_addr];
    for (int j = 0; j < NPUSH; j++) begin
      if (wr_i[j] && pos[j] == st_addr)
        st_data = wdata_i[j];
    end
  end
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      trk_q <= 1'b0;
    end else if (trk_start) begin
      trk_q       <= 1'b1;
      trk_data_q  <= st_data;
      trk_ahead_q <= st_ahead;
    end else if (trk_out) begin
      trk_q <= 1'b0;
    end else if (trk_q) begin
      trk_ahead_q <= trk_ahead_q - CNT_W'(pop_n_i);
    end
  end
  // its place in the storage
  logic [PTR_W-1:0] trk_addr;
  int               t;
  always_comb begin
    t = int'(rp_i) + int'(trk_ahead_q);
    if (t >= int'(DEPTH)) t = t - int'(DEPTH);
    trk_addr = PTR_W'(t);
  end
  // peek_o is due to show it in the next clock
  logic pk_due_q;
  always_ff @(posedge clk_i) begin
    pk_due_q <= rst_ni && PEEK > 0
                && (trk_start ? st_ahead == CNT_W'(PEEK)
                              : trk_q && !trk_out && trk_ahead_q - CNT_W'(pop_n_i) == CNT_W'(PEEK));
  end

  // ---- covers' history ---------------------------------------------------------------------
  logic was_full_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni)                        was_full_q <= 1'b0;
    else if (count_i == CNT_W'(DEPTH))  was_full_q <= 1'b1;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      no_overflow:  assert (left + int'(n_push) <= int'(DEPTH))
        else $error("circ_queue: %0d pushes with %0d entries left", n_push, left);
      no_underflow: assert (int'(pop_n_i) <= int'(NPOP) && int'(pop_n_i) <= int'(count_i))
        else $error("circ_queue: %0d pops with %0d entries", pop_n_i, count_i);
      wr_room:      assert (wr_ok)
        else $error("circ_queue: an early write into an entry in use");
      count_model:  assert (n_q == N_W'(count_i) && count_i <= CNT_W'(DEPTH))
        else $error("circ_queue: count_o %0d, pushes - pops %0d", count_i, n_q);
      ptr_model:    assert (int'(wp_i) < int'(DEPTH) && int'(rp_i) < int'(DEPTH)
                            && int'(wp_i) == tail)
        else $error("circ_queue: head %0d, tail %0d, count %0d", rp_i, wp_i, count_i);
      peek_addr:    assert (pk_c_ok)
        else $error("circ_queue: the peek port's read-address candidates left the head");
      trk_inside:   assert (!trk_q || trk_ahead_q < count_i)
        else $error("circ_queue: the tracked entry is lost");
      trk_in_mem:   assert (!trk_q || circ_queue.mem_q[trk_addr] == trk_data_q)
        else $error("circ_queue: a queued entry changed in the storage");
      data_order:   assert (!ASYNC_RD || !(trk_q && 32'(trk_ahead_q) < NPOP)
                            || rdata_i[trk_ahead_q] == trk_data_q)
        else $error("circ_queue: rdata_o[%0d] is %0h, the entry there %0h", trk_ahead_q,
                    rdata_i[trk_ahead_q], trk_data_q);
      peek_order:   assert (!pk_due_q || peek_i == trk_data_q)
        else $error("circ_queue: peek_o %0h, the entry due %0h", peek_i, trk_data_q);
      c_full:        cover (count_i == CNT_W'(DEPTH));
      c_empty_again: cover (was_full_q && count_i == '0);
      c_wrap:        cover (push_i[0] && int'(wp_i) == int'(DEPTH) - 1);
      c_push_pop:    cover (push_i != '0 && pop_n_i != '0);
      c_all_lanes:   cover (push_i == '1 && pop_n_i == POP_W'(NPOP));
      c_trk_out:     cover (trk_out && was_full_q);
    end
  end

endmodule

bind circ_queue circ_queue_assert #(
  .WIDTH(WIDTH), .DEPTH(DEPTH), .NPUSH(NPUSH), .NPOP(NPOP), .INIT_SEQ(INIT_SEQ),
  .ASYNC_RD(ASYNC_RD), .PEEK(PEEK), .PTR_W(PTR_W), .CNT_W(CNT_W), .POP_W(POP_W)
) u_assert (
  .clk_i, .rst_ni, .push_i, .wr_i, .wdata_i, .pop_n_i, .rdata_i(rdata_o), .peek_i(peek_o),
  .count_i(count_o), .wp_i(wp_q), .rp_i(rp_q));
`endif
