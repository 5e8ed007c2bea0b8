// SPDX-License-Identifier: Apache-2.0
// pipe_delay: a fixed delay of N enabled clocks for a W-bit value, the same as f24_delay #(W, N)
// at its ports (q_o after an enabled edge is the d_i of N - 1 enabled edges before it, so a value
// presented on an enabled edge shows at q_o after N of them; q_o holds while en_i is 0), built
// for long delays of wide values.  With N >= RAM_MIN the line is a circular buffer of N words in
// a cache_sdp_ram (one write port, one synchronous read port; Yosys maps it to ECP5 LUT RAM or
// EBR) instead of N registers of W bits:
//   every enabled edge writes d_i to word wa_q and reads word ra_q = wa_q + 1 (mod N) into the
//   RAM's read register, which is q_o; word wa_q + 1 is the one written N - 1 enabled edges
//   before, and the read and write addresses always differ (N >= 2), so no read-during-write
//   rule is involved.  Both pointers and the read register advance only while en_i is 1, so a
//   stall freezes the line like registers: the read register holds its word and the next enabled
//   edge reads the following one.
// Below RAM_MIN (or RAM_MIN = 0) the line is N registers (f24_delay).  Data have no reset; rst_ni
// (synchronous, active low) only sets the RAM line's pointers (their difference is what matters,
// so the line is correct from any start; the reset keeps them out of X in simulation).
module pipe_delay #(
  parameter int unsigned W       = 24,  // bits of the value
  parameter int unsigned N       = 1,   // delay in enabled clocks, >= 1
  parameter int unsigned RAM_MIN = 8    // the smallest N built as a RAM line (>= 2; 0: never)
) (
  input  logic         clk_i,
  input  logic         rst_ni,  // synchronous, active low: the RAM line's pointers only
  input  logic         en_i,    // clock enable: the line advances only while en_i is 1
  input  logic [W-1:0] d_i,     // value entering the line
  output logic [W-1:0] q_o      // d_i of N enabled clocks before
);

  if (N < 1 || RAM_MIN == 1) begin : g_check
    $error("pipe_delay: N must be at least 1 and RAM_MIN 0 or at least 2");
  end

  if (RAM_MIN != 0 && N >= RAM_MIN) begin : g_ram
    localparam int unsigned AW = $clog2(N);
    localparam logic [AW-1:0] LAST = AW'(N - 1);
    logic [AW-1:0] wa_q, ra_q;  // write and read word; ra_q = wa_q + 1 (mod N)

    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        wa_q <= '0;
        ra_q <= AW'(1);
      end else if (en_i) begin
        wa_q <= (wa_q == LAST) ? '0 : wa_q + AW'(1);
        ra_q <= (ra_q == LAST) ? '0 : ra_q + AW'(1);
      end
    end

    cache_sdp_ram #(.DEPTH(N), .WIDTH(W)) u_ram (
      .clk_i, .we_i(en_i), .waddr_i(wa_q), .wdata_i(d_i), .re_i(en_i), .raddr_i(ra_q),
      .rlane_i(1'b0), .rdata_o(q_o));
  end else begin : g_reg
    /* verilator lint_off UNUSEDSIGNAL */  // registers only: no pointers to reset
    logic unused_rst;
    /* verilator lint_on UNUSEDSIGNAL */
    assign unused_rst = rst_ni;
    f24_delay #(.W(W), .N(N)) u_reg (.clk_i, .en_i, .d_i, .q_o);
  end

endmodule
