// SPDX-License-Identifier: Apache-2.0
// circ_queue: a circular queue (FIFO) of DEPTH entries of WIDTH bits, with up to NPUSH entries
// joining and up to NPOP leaving per clock.
//   Push: lane k (push_i[k]) joins after the lanes below it that push in the same clock.
//     wr_i[k] writes lane k's data into the entry it would take, with push_i[k] or without: a
//     user that knows the queue has room may write early and let only the pointer and the count
//     wait for push_i (with wr_i = push_i the queue is an ordinary one).
//   Pop: pop_n_i entries leave at the head (at most count_o).  rdata_o[k] is entry head + k
//     (k < NPOP; valid while k < count_o), read from the storage without a register.
//   count_o: the entries held (the count after reset: 0, or DEPTH with INIT_SEQ).
//   PEEK > 0 (one push lane): peek_o is entry PEEK of the queue as it is after this clock (its
//     head after this clock's pop, plus PEEK), registered: the storage's one synchronous read
//     port (block RAM), with an entry written in the same clock at that place taken from a
//     register of the written data.  ASYNC_RD = 0 leaves out the asynchronous ports (rdata_o
//     is then 0), so that block RAM can hold the storage.
// No overflow or underflow check: the user keeps push and pop within the count (the users'
// bound checks watch their counts).  Reset (rst_ni low, synchronous) empties the queue; with
// INIT_SEQ = 1 it fills it instead, entry i holding the index i (a free list of DEPTH indices).
// The storage has a write port per push lane and NPOP asynchronous read ports; RAM_STYLE is its
// ram_style attribute ("block": block RAM).
module circ_queue #(
  parameter int unsigned WIDTH     = 8,     // entry width
  parameter int unsigned DEPTH     = 4,     // entries (>= 1; any value, not only powers of two)
  parameter int unsigned NPUSH     = 1,     // entries joining per clock at most (<= DEPTH)
  parameter int unsigned NPOP      = 1,     // entries leaving per clock at most (<= DEPTH)
  parameter bit          INIT_SEQ  = 1'b0,  // reset fills the queue with 0 .. DEPTH - 1
  parameter bit          ASYNC_RD  = 1'b1,  // rdata_o: asynchronous reads of the storage
  parameter int unsigned PEEK      = 0,     // peek_o: registered entry PEEK (0: none; <= DEPTH)
  /* verilator lint_off UNUSEDPARAM */  // (an attribute: read by synthesis only)
  parameter string       RAM_STYLE = "auto",  // the storage's ram_style ("block": block RAM)
  /* verilator lint_on UNUSEDPARAM */
  // derived (not to be overridden)
  parameter int unsigned PTR_W     = (DEPTH > 1) ? $clog2(DEPTH) : 1,
  parameter int unsigned CNT_W     = $clog2(DEPTH + 1),
  parameter int unsigned POP_W     = $clog2(NPOP + 1)
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  input  logic [NPUSH-1:0]            push_i,   // lane k joins
  input  logic [NPUSH-1:0]            wr_i,     // lane k's data is written (see above)
  input  logic [NPUSH-1:0][WIDTH-1:0] wdata_i,
  input  logic [POP_W-1:0]            pop_n_i,  // entries leaving at the head
  output logic [NPOP-1:0][WIDTH-1:0]  rdata_o,  // entries head .. head + NPOP - 1
  output logic [WIDTH-1:0]            peek_o,   // entry PEEK after this clock, registered
  output logic [CNT_W-1:0]            count_o
);

  localparam int unsigned PUSH_W = $clog2(NPUSH + 1);

  if (DEPTH < 1 || NPUSH < 1 || NPUSH > DEPTH || NPOP < 1 || NPOP > DEPTH
      || (INIT_SEQ && WIDTH < $clog2(DEPTH))) begin : g_check
    $error("circ_queue: DEPTH >= 1, 1 <= NPUSH, NPOP <= DEPTH (INIT_SEQ: WIDTH >= log2 DEPTH)");
  end
  if (PEEK > DEPTH || (PEEK > 0 && NPUSH != 1)) begin : g_check_peek
    $error("circ_queue: PEEK <= DEPTH, and PEEK needs NPUSH = 1");
  end
  if (PTR_W != ((DEPTH > 1) ? $clog2(DEPTH) : 1) || CNT_W != $clog2(DEPTH + 1) || POP_W != $clog2(NPOP + 1))
  begin : g_check_derived
    $error("circ_queue: the derived parameters must keep their defaults");
  end

  // p + k modulo DEPTH (k <= DEPTH)
  function automatic logic [PTR_W-1:0] ptr_add(input logic [PTR_W-1:0] p, input int unsigned k);
    int unsigned q;
    q = 32'(p) + k;
    if (q >= DEPTH) q = q - DEPTH;
    return PTR_W'(q);
  endfunction

  logic [PTR_W-1:0]             wp_q, rp_q;  // tail (next free entry), head
  logic [CNT_W-1:0]             cnt_q;
  logic [NPUSH-1:0][PTR_W-1:0]  pos;         // each push lane's entry
  logic [PUSH_W-1:0]            n_push;      // lanes joining

  always_comb begin
    n_push = '0;
    for (int k = 0; k < NPUSH; k++) begin
      pos[k] = ptr_add(wp_q, 32'(n_push));
      if (push_i[k]) n_push = n_push + PUSH_W'(1);
    end
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      wp_q  <= '0;
      rp_q  <= '0;
      cnt_q <= INIT_SEQ ? CNT_W'(DEPTH) : '0;
    end else begin
      wp_q  <= ptr_add(wp_q, 32'(n_push));
      rp_q  <= ptr_add(rp_q, 32'(pop_n_i));
      cnt_q <= cnt_q + CNT_W'(n_push) - CNT_W'(pop_n_i);
    end
  end

  (* ram_style = RAM_STYLE *) logic [WIDTH-1:0] mem_q [DEPTH];

  if (NPUSH == 1) begin : g_wr_one
    always_ff @(posedge clk_i) begin
      if (!rst_ni && INIT_SEQ) begin
        for (int i = 0; i < DEPTH; i++) mem_q[i] <= WIDTH'(i);
      end else begin
        if (wr_i[0]) mem_q[pos[0]] <= wdata_i[0];
      end
    end
  end else begin : g_wr_multi
    // Several push lanes.  The lanes' writes are gathered by their offset j from the tail first
    // (lane k writes entry wp_q + j, j the lanes below it that push; of two lanes at one offset
    // the higher wins, as in a loop over the lanes), then each entry takes the offset that
    // lands on it (the tail's one-hot position says which): the same writes as
    // mem_q[pos[k]] <= wdata_i[k] per lane without a pointer decode per lane.  When NPUSH
    // divides DEPTH, entry e is only ever written by the offset j = e - wp_q (mod NPUSH), so
    // the data are first turned to the entries' banks (e mod NPUSH) and each entry has one
    // data source, only its enable looks at the offsets (the 16-entry, 4-lane AR queue of
    // tex_cache synthesised as a module of its own: ~290 LUT4 against ~930 for the per-lane
    // writes; inside the flattened cache the difference is smaller).
    localparam bit BANKED = (DEPTH % NPUSH) == 0;
    logic [NPUSH-1:0]            off_v;  // offset j is written
    logic [NPUSH-1:0][WIDTH-1:0] off_d;  // ... with this data
    logic [NPUSH-1:0][WIDTH-1:0] bank_d; // the data for the entries e with e mod NPUSH = b
    logic [DEPTH-1:0]            at_wp;  // entry e is the tail
    logic                        unused_pos;
    assign unused_pos = ^pos;  // (pos: the single-lane write and PEEK only)
    always_comb begin
      logic [PUSH_W-1:0] n;
      off_v = '0;
      off_d = '0;
      n     = '0;
      for (int k = 0; k < NPUSH; k++) begin
        for (int j = 0; j <= k; j++) begin
          if (wr_i[k] && 32'(n) == j) begin
            off_v[j] = 1'b1;
            off_d[j] = wdata_i[k];
          end
        end
        if (push_i[k]) n = n + PUSH_W'(1);
      end
      for (int e = 0; e < DEPTH; e++) at_wp[e] = (32'(wp_q) == e);
      bank_d = '0;
      for (int b = 0; b < NPUSH; b++) begin
        for (int j = 0; j < NPUSH; j++) begin
          if ((32'(wp_q) + j) % NPUSH == b) bank_d[b] = off_d[j];
        end
      end
    end
    always_ff @(posedge clk_i) begin
      if (!rst_ni && INIT_SEQ) begin
        for (int i = 0; i < DEPTH; i++) mem_q[i] <= WIDTH'(i);
      end else begin
        for (int e = 0; e < DEPTH; e++) begin
          for (int j = 0; j < NPUSH; j++) begin
            // entry e is offset j from the tail (j < NPUSH <= DEPTH: one j per entry)
            if (off_v[j] && at_wp[(e + DEPTH - j) % DEPTH]) begin
              mem_q[e] <= BANKED ? bank_d[e % NPUSH] : off_d[j];
            end
          end
        end
      end
    end
  end

  if (ASYNC_RD && NPOP > 1 && DEPTH % NPOP == 0) begin : g_rd_banked
    // Several pops, NPOP dividing DEPTH: entries head .. head + NPOP - 1 lie in distinct banks
    // (e mod NPOP), so each bank reads its one entry among them (DEPTH / NPOP candidates) and
    // the ports take the banks turned by the head's bank: the same words as
    // mem_q[head + k] per port with narrower multiplexers.
    localparam int unsigned NROW = DEPTH / NPOP;
    logic [NPOP-1:0][WIDTH-1:0] bank_rd;
    always_comb begin
      int unsigned hb, hr, r;
      hb = 32'(rp_q) % NPOP;
      hr = 32'(rp_q) / NPOP;
      for (int unsigned b = 0; b < NPOP; b++) begin
        r = (b < hb) ? ((hr + 1) % NROW) : hr;
        bank_rd[b] = '0;
        for (int unsigned i = 0; i < NROW; i++) begin
          if (r == i) bank_rd[b] = mem_q[i * NPOP + b];
        end
      end
      for (int unsigned k = 0; k < NPOP; k++) rdata_o[k] = bank_rd[(hb + k) % NPOP];
    end
  end else if (ASYNC_RD) begin : g_rd
    for (genvar k = 0; k < NPOP; k++) begin : g_port
      assign rdata_o[k] = mem_q[ptr_add(rp_q, k)];
    end
  end else begin : g_no_rd
    assign rdata_o = '0;
  end

  if (PEEK > 0) begin : g_peek
    logic [PTR_W-1:0] pk_addr;   // entry PEEK after this clock's pop
    logic [WIDTH-1:0] pk_rd_q;   // the storage read there
    logic [WIDTH-1:0] pk_fw_q;   // the data written in that clock
    logic             pk_fwv_q;  // ... at that entry: take pk_fw_q
    // The candidates rp_q + PEEK + k (k = 0 .. NPOP pops) are registers moving with rp_q, so
    // pop_n_i, late in the clock, only picks one (no adder between it and the read address).
    logic [NPOP:0][PTR_W-1:0] pk_c_q;
    always_ff @(posedge clk_i) begin
      for (int unsigned k = 0; k <= NPOP; k++) begin
        if (!rst_ni) pk_c_q[k] <= ptr_add(ptr_add(PTR_W'(0), k), PEEK);
        else         pk_c_q[k] <= ptr_add(pk_c_q[k], 32'(pop_n_i));
      end
    end
    always_comb begin
      pk_addr = pk_c_q[0];
      for (int unsigned k = 1; k <= NPOP; k++) begin
        if (32'(pop_n_i) == k) pk_addr = pk_c_q[k];
      end
    end
    always_ff @(posedge clk_i) begin
      pk_rd_q  <= mem_q[pk_addr];
      pk_fw_q  <= wdata_i[0];
      pk_fwv_q <= wr_i[0] && pos[0] == pk_addr;
    end
    assign peek_o = pk_fwv_q ? pk_fw_q : pk_rd_q;
  end else begin : g_no_peek
    assign peek_o = '0;
  end

  assign count_o = cnt_q;

endmodule
