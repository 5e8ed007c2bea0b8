// SPDX-License-Identifier: Apache-2.0
// traverse_fifo: synchronous FIFO of W-bit words, DEPTH entries (a power of two), first-word
// fall-through (the head is visible on rd_data_o while empty_o is 0).  Write and read may happen
// in the same clock (a write needs full_o = 0 even then).  Writing while full and reading while
// empty are errors (asserted), never silently dropped or repeated: the users check full_o /
// empty_o first.  The assertions are in traverse_fifo_assert.sv, bound into every instance
// (simulation checks them, `make formal` proves them: docs/formal.md).
// RAM_STYLE steers synthesis (Yosys's ram_style attribute on the storage): "auto" lets it
// choose (LUT RAM for the small and shallow ones), "block" asks for block RAM (an ECP5 EBR):
// synthesis reads it synchronously at the next read pointer (rp_q's register moves into the
// RAM) and adds a bypass for a word written to that address in the same clock.  A 16x4 LUT RAM
// costs six LUT4 sites, so a wide FIFO is cheaper in EBRs.
// OUT_REG = 1 (the default with "block") puts the head in a fabric register, hd_q: the block
// RAM's 4.3 ns clock-to-out then ends at that register instead of running into the reader's
// logic (in the whole chip, the texture cache's and the MIP unit's inputs from such FIFOs were
// their slowest paths).  The ports behave exactly as without it, clock for clock: hd_q holds the
// head whenever the FIFO is not empty, the RAM the entries behind it (at most DEPTH - 1); a
// write into a FIFO that is empty, or whose only entry leaves in that clock, goes straight to
// hd_q (visible the next clock, as before), and a read refills hd_q from the RAM's head.
module traverse_fifo #(
  parameter int unsigned W     = 8,
  parameter int unsigned DEPTH = 16,      // power of two, >= 2
  parameter string       RAM_STYLE = "auto",  // synthesis: "auto" or "block" (see above)
  parameter bit          OUT_REG = (RAM_STYLE == "block")  // 1: the head in a register
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
  logic [AW:0]   cnt_q;         // entries in the FIFO (OUT_REG: hd_q's included)
  logic          m_wr, m_rd;    // the RAM is written / its head read
  logic [AW:0]   m_cnt;         // entries in the RAM

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      wp_q  <= '0;
      rp_q  <= '0;
      cnt_q <= '0;
    end else begin
      if (m_wr) wp_q <= wp_q + AW'(1);
      if (m_rd) rp_q <= rp_q + AW'(1);
      cnt_q <= cnt_q + (AW+1)'(wr_i) - (AW+1)'(rd_i);
    end
  end

  always_ff @(posedge clk_i) begin
    if (m_wr) mem_q[wp_q] <= wr_data_i;
  end

  if (OUT_REG) begin : g_out_reg
    logic [W-1:0] hd_q;         // the head (meaningful while cnt_q != 0)
    logic         hd_load;      // hd_q takes a new head: it is empty or its entry leaves
    logic         m_any;        // the RAM holds entries
    assign m_cnt   = (cnt_q == '0) ? '0 : cnt_q - (AW+1)'(1);
    assign m_any   = (m_cnt != '0);
    assign hd_load = (cnt_q == '0) || rd_i;
    // The new head is the RAM's head when it has one, else the word written now (if any).
    assign m_rd    = hd_load && m_any;
    assign m_wr    = wr_i && !(hd_load && !m_any);
    always_ff @(posedge clk_i) begin
      if (hd_load) hd_q <= m_any ? mem_q[rp_q] : wr_data_i;
    end
    assign rd_data_o = hd_q;
  end else begin : g_no_out_reg
    assign m_cnt     = cnt_q;
    assign m_wr      = wr_i;
    assign m_rd      = rd_i;
    assign rd_data_o = mem_q[rp_q];
  end

  assign full_o    = (cnt_q == (AW+1)'(DEPTH));
  assign empty_o   = (cnt_q == '0);
  assign count_o   = cnt_q;

endmodule
