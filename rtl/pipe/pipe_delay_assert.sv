// SPDX-License-Identifier: Apache-2.0
// pipe_delay_assert: the properties of pipe_delay's RAM line (N >= RAM_MIN), bound into every
// instance (the `bind` at the end of this file), checked by simulation (Verilator --assert) and
// proven by `make formal` (formal/pipe_delay.sby; docs/formal.md).  Immediate assertions only, in
// the form the formal flow's front end (Yosys read_slang) accepts.  A reference line of N
// registers (ref_q, what f24_delay builds) runs beside it on the same enable:
//
//   ptr_next   the read pointer is the write pointer's successor modulo N (both < N);
//   same_out   once N enabled clocks have passed since reset, q_o equals the reference's output:
//              the RAM line delays exactly like N registers, stalls included;
//   same_word  the word i + 1 writes back (i = 0 .. N - 1: word wa_q - 1 - i mod N) holds the
//              reference's register i once i + 1 enabled clocks have passed (the invariant that
//              makes the induction step hold; i = N - 1 is the word read into q_o).
// Covers: q_o checked after a stall.
`ifndef SYNTHESIS
module pipe_delay_assert #(
  parameter int unsigned W       = 24,  // pipe_delay's W
  parameter int unsigned N       = 1,   // pipe_delay's N
  parameter int unsigned RAM_MIN = 8    // pipe_delay's RAM_MIN
) (
  input logic         clk_i,
  input logic         rst_ni,
  input logic         en_i,
  input logic [W-1:0] d_i,
  input logic [W-1:0] q_o_i   // pipe_delay's q_o
);

  if (RAM_MIN != 0 && N >= RAM_MIN) begin : g_ram
    localparam int unsigned AW = $clog2(N);
    localparam int unsigned FW = $clog2(N + 1) + 1;

    logic [N-1:0][W-1:0] ref_q;   // ref_q[i]: d_i of i + 1 enabled clocks ago
    logic [FW-1:0]       fill_q;  // enabled clocks since reset, up to N
    logic                stall_q; // the clock before had en_i = 0
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        ref_q[0] <= d_i;
        for (int i = 1; i < N; i++) ref_q[i] <= ref_q[i-1];
      end
      stall_q <= !en_i;
      if (!rst_ni)                         fill_q <= '0;
      else if (en_i && fill_q < FW'(N))    fill_q <= fill_q + FW'(1);
    end

    logic [AW-1:0] wa, ra;
    assign wa = pipe_delay.g_ram.wa_q;
    assign ra = pipe_delay.g_ram.ra_q;

    // the word written i + 1 enabled clocks ago: wa - 1 - i modulo N
    function automatic logic [AW-1:0] back(input logic [AW-1:0] a, input int unsigned i);
      return AW'((int'(a) + 2 * N - 1 - i) % N);
    endfunction

    always_comb begin
      if (rst_ni) begin
        ptr_next: assert (int'(wa) < N && int'(ra) == (int'(wa) + 1) % N)
          else $error("pipe_delay: read pointer %0d, write pointer %0d", ra, wa);
        same_out: assert (fill_q < FW'(N) || q_o_i == ref_q[N-1])
          else $error("pipe_delay: %0h out, %0h due", q_o_i, ref_q[N-1]);
        c_held: cover (fill_q == FW'(N) && stall_q && en_i);
      end
    end
    for (genvar i = 0; i < N; i++) begin : g_word
      always_comb begin
        if (rst_ni) begin
          same_word: assert (fill_q <= FW'(i)
                             || pipe_delay.g_ram.u_ram.mem_q[back(wa, i)] == ref_q[i])
            else $error("pipe_delay: word %0d differs from the reference", back(wa, i));
        end
      end
    end
  end else begin : g_reg
    logic unused;
    assign unused = ^{clk_i, rst_ni, en_i, d_i, q_o_i};
  end

endmodule

bind pipe_delay pipe_delay_assert #(.W(W), .N(N), .RAM_MIN(RAM_MIN)) u_assert (
  .clk_i, .rst_ni, .en_i, .d_i, .q_o_i(q_o));
`endif
