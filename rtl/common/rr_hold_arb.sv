// SPDX-License-Identifier: Apache-2.0
// rr_hold_arb: round-robin choice among N requesters of one valid/ready stream, the grant held
// while the granted request waits (a valid, once shown, keeps its payload until the handshake).
//
//   gnt_o    the first requester at or after the priority pointer, or the held one; combinational
//            in req_i (never in ready_i);
//   valid_o  req_i[gnt_o]: the stream's valid;
//   the pointer moves past the granted requester at each handshake (valid_o && ready_i); a
//   valid_o not taken holds the grant for the next clock.
module rr_hold_arb #(
  parameter int unsigned N     = 2,                              // requesters (>= 1)
  parameter int unsigned SEL_W = (N > 1) ? $clog2(N) : 1         // derived: index width
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic [N-1:0]     req_i,     // requester k has a valid item
  input  logic             ready_i,   // the consumer takes the granted item
  output logic [SEL_W-1:0] gnt_o,
  output logic             valid_o
);

  logic [SEL_W-1:0] prio_q, hold_sel_q;
  logic             hold_q;

  always_comb begin
    gnt_o = prio_q;
    if (hold_q) begin
      gnt_o = hold_sel_q;
    end else begin
      for (int k = N - 1; k >= 0; k--) begin
        automatic logic [SEL_W-1:0] m = SEL_W'((int'(prio_q) + k) % N);
        if (req_i[m]) gnt_o = m;
      end
    end
  end
  assign valid_o = req_i[gnt_o];

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      prio_q     <= '0;
      hold_q     <= 1'b0;
      hold_sel_q <= '0;
    end else begin
      hold_q     <= valid_o && !ready_i;
      hold_sel_q <= gnt_o;
      if (valid_o && ready_i) prio_q <= (int'(gnt_o) == N - 1) ? '0 : gnt_o + 1'b1;
    end
  end

endmodule
