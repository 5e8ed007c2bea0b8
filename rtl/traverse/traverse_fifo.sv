// traverse_fifo: synchronous FIFO of W-bit words, DEPTH entries (a power of two), first-word
// fall-through (the head is visible on rd_data_o while empty_o is 0).  Write and read may happen
// in the same clock (a write needs full_o = 0 even then).  Writing while full and reading while
// empty are errors (asserted), never silently dropped or repeated: the users check full_o /
// empty_o first.
// RAM_STYLE only steers synthesis (Yosys's ram_style attribute on the storage): "auto" lets it
// choose (LUT RAM for the small and shallow ones), "block" asks for block RAM (an ECP5 EBR):
// synthesis reads it synchronously at the next read pointer (rp_q's register moves into the
// RAM) and adds a bypass for a word written to that address in the same clock.  A 16x4 LUT RAM
// costs six LUT4 sites, so a wide FIFO is cheaper in EBRs.  Simulation is the same either way.
module traverse_fifo #(
  parameter int unsigned W     = 8,
  parameter int unsigned DEPTH = 16,      // power of two, >= 2
  /* verilator lint_off UNUSEDPARAM */   // read only by synthesis (an attribute); see above
  parameter string       RAM_STYLE = "auto"
  /* verilator lint_on UNUSEDPARAM */
) (
  input  logic                      clk_i,
  input  logic                      rst_ni,
  input  logic                      wr_i,
  input  logic [W-1:0]              wr_data_i,
  input  logic                      rd_i,
  output logic [W-1:0]              rd_data_o,
  output logic                      full_o,
  output logic                      empty_o,
  output logic [$clog2(DEPTH):0]    count_o
);

  localparam int unsigned AW = $clog2(DEPTH);

  if (DEPTH < 2 || (1 << AW) != DEPTH) begin : g_check_depth
    $error("traverse_fifo: DEPTH must be a power of two >= 2");
  end

  (* ram_style = RAM_STYLE *) logic [W-1:0] mem_q [DEPTH];
  logic [AW-1:0] wp_q, rp_q;
  logic [AW:0]   cnt_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      wp_q  <= '0;
      rp_q  <= '0;
      cnt_q <= '0;
    end else begin
      if (wr_i) wp_q <= wp_q + AW'(1);
      if (rd_i) rp_q <= rp_q + AW'(1);
      cnt_q <= cnt_q + (AW+1)'(wr_i) - (AW+1)'(rd_i);
    end
  end

  always_ff @(posedge clk_i) begin
    if (wr_i) mem_q[wp_q] <= wr_data_i;
  end

  assign rd_data_o = mem_q[rp_q];
  assign full_o    = (cnt_q == (AW+1)'(DEPTH));
  assign empty_o   = (cnt_q == '0);
  assign count_o   = cnt_q;

`ifndef SYNTHESIS
  no_overflow:  assert property (@(posedge clk_i) disable iff (!rst_ni) wr_i |-> !full_o)
    else $error("traverse_fifo: write while full");
  no_underflow: assert property (@(posedge clk_i) disable iff (!rst_ni) rd_i |-> !empty_o)
    else $error("traverse_fifo: read while empty");
`endif

endmodule
