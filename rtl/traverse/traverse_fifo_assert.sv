// SPDX-License-Identifier: Apache-2.0
// traverse_fifo_assert: the properties of traverse_fifo, bound into every instance (the `bind` at
// the end of this file), checked by simulation (Verilator --assert) and proven by `make formal`
// (formal/traverse_fifo.sby, formal/pipe_f0.sby; docs/formal.md).  Immediate assertions only, in
// the form the formal flow's front end (Yosys read_slang) accepts.
//
//   no_overflow / no_underflow  the user writes only while not full, reads only while not empty
//                               (obligations of the user: the formal wrapper of the FIFO alone
//                               assumes them, the pipeline wrapper proves them);
//   count_model                 count_o = writes - reads since reset (a counter of its own) and
//                               never above DEPTH; full_o / empty_o agree with it;
//   ram_count / ram_room        the RAM's pointers agree with the count of its entries (modulo
//                               DEPTH: equal pointers when the RAM is full), and with OUT_REG
//                               the RAM holds count_o - 1 (the head is in hd_q);
//   data_order                  a tracked word (a write picked freely in formal, every write that
//                               finds no word tracked in simulation) comes out exactly after the
//                               words ahead of it: rd_data_o is the tracked word when it is at the
//                               head, the RAM holds it at its place while it waits (trk_in_ram:
//                               the invariant that makes the induction step hold).
// The covers (full, empty again after full, a RAM write at its last address: the write pointer
// wraps, a write and a read in one clock, the tracked word read after the FIFO was full) show in
// formal that those states are reachable.
// The RAM's words are read through a hierarchical reference (traverse_fifo.mem_q): an array port
// would be a memory in Yosys, which it cannot pass between modules.
`ifndef SYNTHESIS
module traverse_fifo_assert #(
  parameter int unsigned W       = 8,   // word width (traverse_fifo's W)
  parameter int unsigned DEPTH   = 16,  // entries (traverse_fifo's DEPTH)
  parameter bit          OUT_REG = 0    // traverse_fifo's OUT_REG: the head in a register
) (
  input logic                     clk_i,
  input logic                     rst_ni,
  input logic                     wr_i,
  input logic [W-1:0]             wr_data_i,
  input logic                     rd_i,
  input logic [W-1:0]             rd_data_i,  // traverse_fifo's rd_data_o
  input logic                     full_i,     // full_o
  input logic                     empty_i,    // empty_o
  input logic [$clog2(DEPTH):0]   count_i,    // count_o
  input logic [$clog2(DEPTH)-1:0] wp_i,       // wp_q: the RAM's write pointer
  input logic [$clog2(DEPTH)-1:0] rp_i,       // rp_q: the RAM's read pointer
  input logic [$clog2(DEPTH):0]   m_cnt_i,    // m_cnt: entries in the RAM
  input logic                     m_wr_i      // m_wr: the RAM is written
);

  localparam int unsigned AW = $clog2(DEPTH);

  // ---- the count: writes - reads since reset -------------------------------------------------
  logic [AW+1:0] n_q;   // one bit wider than count_o: an overflow shows
  always_ff @(posedge clk_i) begin
    if (!rst_ni) n_q <= '0;
    else         n_q <= n_q + (AW+2)'(wr_i) - (AW+2)'(rd_i);
  end

  // ---- the tracked word ----------------------------------------------------------------------
  // pick: which write to track.  Formal leaves it undriven (SymbiYosys makes an undriven wire a
  // free input: every write may be the tracked one); simulation tracks whenever it can.
  logic pick;
`ifndef FORMAL
  assign pick = 1'b1;
`endif
  logic          trk_q;      // a word is tracked
  logic [W-1:0]  trk_data_q; // its value
  logic [AW:0]   trk_pos_q;  // words ahead of it
  logic          trk_out;    // it is read in this clock
  logic          trk_start;  // the word written in this clock becomes the tracked one
  assign trk_out   = trk_q && rd_i && trk_pos_q == '0;
  assign trk_start = wr_i && pick && (!trk_q || trk_out);
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      trk_q <= 1'b0;
    end else if (trk_start) begin
      trk_q      <= 1'b1;
      trk_data_q <= wr_data_i;
      trk_pos_q  <= count_i - (AW+1)'(rd_i);
    end else if (trk_out) begin
      trk_q <= 1'b0;
    end else if (trk_q && rd_i) begin
      trk_pos_q <= trk_pos_q - (AW+1)'(1);
    end
  end
  // Where the RAM holds the tracked word while it is not the head (with OUT_REG the head is in
  // hd_q, so the RAM's head is the second word).
  logic [AW-1:0] trk_addr;
  assign trk_addr = rp_i + AW'(trk_pos_q) - AW'(OUT_REG);

  // ---- covers' history -----------------------------------------------------------------------
  logic was_full_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni)     was_full_q <= 1'b0;
    else if (full_i) was_full_q <= 1'b1;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      no_overflow:  assert (!(wr_i && full_i))
        else $error("traverse_fifo: write while full");
      no_underflow: assert (!(rd_i && empty_i))
        else $error("traverse_fifo: read while empty");
      count_model:  assert (n_q == {1'b0, count_i} && count_i <= (AW+1)'(DEPTH))
        else $error("traverse_fifo: count_o %0d, writes - reads %0d", count_i, n_q);
      count_flags:  assert (full_i == (count_i == (AW+1)'(DEPTH)) && empty_i == (count_i == '0))
        else $error("traverse_fifo: full_o / empty_o disagree with count_o");
      ram_count:    assert (AW'(wp_i - rp_i) == AW'(m_cnt_i))  // modulo DEPTH: full = equal
        else $error("traverse_fifo: RAM pointers and count disagree");
      ram_room:     assert (m_cnt_i == (OUT_REG && count_i != '0 ? count_i - (AW+1)'(1)
                                                                 : count_i))
        else $error("traverse_fifo: RAM entries %0d with count_o %0d", m_cnt_i, count_i);
      trk_inside:   assert (!trk_q || trk_pos_q < count_i)
        else $error("traverse_fifo: the tracked word is lost");
      data_order:   assert (!(trk_q && trk_pos_q == '0) || rd_data_i == trk_data_q)
        else $error("traverse_fifo: read %0h, the word due is %0h", rd_data_i, trk_data_q);
      trk_in_ram:   assert (!(trk_q && trk_pos_q != '0) || traverse_fifo.mem_q[trk_addr] == trk_data_q)
        else $error("traverse_fifo: a waiting word changed in the RAM");
      c_full:       cover (full_i);
      c_empty_again: cover (was_full_q && empty_i);
      c_wrap:       cover (m_wr_i && wp_i == AW'(DEPTH - 1));
      c_wr_rd:      cover (wr_i && rd_i && !full_i && !empty_i);
      c_trk_out:    cover (trk_out && trk_pos_q == '0 && was_full_q);
    end
  end

endmodule

bind traverse_fifo traverse_fifo_assert #(.W(W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_assert (
  .clk_i, .rst_ni, .wr_i, .wr_data_i, .rd_i, .rd_data_i(rd_data_o), .full_i(full_o),
  .empty_i(empty_o), .count_i(count_o), .wp_i(wp_q), .rp_i(rp_q), .m_cnt_i(m_cnt),
  .m_wr_i(m_wr));
`endif
