// SPDX-License-Identifier: Apache-2.0
// f24_delay: N plain enabled delay registers of W bits (a float unit's stages beyond its useful
// register placement: a unit instantiated with a LAT deeper than its deepest split passes its
// result through one of these, so the result word is the same at every LAT and only the number of
// enabled clocks changes).  Registers advance only while en_i is 1; no reset (the float units
// have none).  N = 0 is a wire (q_o = d_i), for a unit whose LAT may equal its own depth.
module f24_delay #(
  parameter int unsigned W = 24,  // bits per register
  parameter int unsigned N = 1    // registers in series (0: none)
) (
  input  logic         clk_i,  // clock
  input  logic         en_i,   // clock enable: the registers advance only while en_i is 1
  input  logic [W-1:0] d_i,    // value entering the first register
  output logic [W-1:0] q_o     // d_i of N enabled clocks before
);

  if (N == 0) begin : g_wire
    logic unused_clk_en;  // no register: the clock and its enable are not read
    assign unused_clk_en = clk_i & en_i;
    assign q_o = d_i;
  end else begin : g_regs
    logic [N-1:0][W-1:0] q_q;  // q_q[0]: the first register

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        q_q[0] <= d_i;
        for (int i = 1; i < N; i++) q_q[i] <= q_q[i-1];
      end
    end

    assign q_o = q_q[N-1];
  end

endmodule
