// SPDX-License-Identifier: Apache-2.0
// traverse_fifo_formal: traverse_fifo alone under SymbiYosys (formal/traverse_fifo.sby).  Its
// inputs are free, except what a user of the FIFO promises (assumed here, asserted by
// traverse_fifo_assert in every real use): no write while full, no read while empty, and reset
// in the first clock.  The properties are the bound traverse_fifo_assert's, and with FREE_LIST
// (the FIFO as dm_pipeline's free list of slot ids) the wrapper's own:
//   fl_exact   every id 0 .. DEPTH - 1 is exactly once either in the FIFO or held by the user
//              (own_q: ids read and not yet written back), so none is lost or duplicated;
//   fl_total   the FIFO's count plus the ids held is DEPTH (dm_pipeline's slots_conserved).
// In that mode the user holds every id after reset (dm_pipeline's fill after reset writes
// 0 .. DEPTH - 1 in order: one of the orders allowed here), writes back only ids it holds, each
// once, and takes the id at the head with each read.
module traverse_fifo_formal #(
  parameter int unsigned W         = 4,     // word width (the properties do not depend on it)
  parameter int unsigned DEPTH     = 4,     // entries (power of two)
  parameter bit          OUT_REG   = 0,     // 1: the head in a register (RAM_STYLE "block")
  parameter bit          FREE_LIST = 1'b0   // the free-list mode (above; W = log2(DEPTH))
) (
  input logic         clk_i,
  input logic         rst_ni,
  input logic         wr_i,
  input logic [W-1:0] wr_data_i,
  input logic         rd_i
);

  logic [W-1:0]               rd_data;
  logic                       full, empty;
  logic [$clog2(DEPTH):0]     count;

  traverse_fifo #(.W(W), .DEPTH(DEPTH), .OUT_REG(OUT_REG)) u_dut (
    .clk_i, .rst_ni, .wr_i, .wr_data_i, .rd_i, .rd_data_o(rd_data), .full_o(full),
    .empty_o(empty), .count_o(count));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // ---- the free list: the ids the user holds ----------------------------------------------
  localparam int unsigned AW = $clog2(DEPTH);
  logic [DEPTH-1:0] own_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      own_q <= '1;
    end else begin
      if (rd_i && 32'(rd_data) < DEPTH) own_q[rd_data] <= 1'b1;
      if (wr_i && 32'(wr_data_i) < DEPTH) own_q[wr_data_i] <= 1'b0;
    end
  end

  // how often each id is in the FIFO (the head register with OUT_REG, then the RAM's entries)
  logic [DEPTH-1:0][AW+1:0] seen;
  logic                     exact;
  int                       owned, n_ram;
  logic [AW-1:0]            a;
  always_comb begin
    seen  = '0;
    n_ram = int'(count);
    if (OUT_REG && count != '0) begin
      n_ram = n_ram - 1;
      if (32'(rd_data) < DEPTH) seen[rd_data] = seen[rd_data] + (AW+2)'(1);
    end
    for (int j = 0; j < DEPTH; j++) begin
      a = u_dut.rp_q + AW'(j);
      if (j < n_ram && 32'(u_dut.mem_q[a]) < DEPTH)
        seen[u_dut.mem_q[a]] = seen[u_dut.mem_q[a]] + (AW+2)'(1);
    end
    exact = 1'b1;
    owned = 0;
    for (int i = 0; i < DEPTH; i++) begin
      if (seen[i] + (AW+2)'(own_q[i]) != (AW+2)'(1)) exact = 1'b0;
      owned = owned + int'(own_q[i]);
    end
  end

  always_comb begin
    assume (!(wr_i && full));
    assume (!(rd_i && empty));
    if (FREE_LIST) begin
      assume (!wr_i || (32'(wr_data_i) < DEPTH && own_q[wr_data_i]));
      if (started_q) assume (rst_ni);   // (a later reset would drop the ids held)
    end
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      fl_exact: assert (!FREE_LIST || exact);
      fl_total: assert (!FREE_LIST || int'(count) + owned == int'(DEPTH));
    end
  end

endmodule
