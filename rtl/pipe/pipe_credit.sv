// SPDX-License-Identifier: Apache-2.0
// pipe_credit: the admission controller in front of a stage that cannot stall.
//
// The fixed-latency units of dm_pipeline (view_calc, mip_level, tex_addr, tex_filter,
// shade_unit) have no back-pressure: whatever enters comes out LATENCY clocks later and must
// find room in the FIFO behind.  pipe_credit counts the items admitted and not yet retired
// (take_i / give_i) and grants room while that count plus held_i (items already counted
// elsewhere, e.g. a FIFO's fill level, 0 if none) is below LIMIT:
//
//   room_o = count + held_i < LIMIT
//
// Used as the paper's controller that keeps FIFO #0 from overflowing (count = fragments inside
// view_calc, held_i = FIFO #0's fill, LIMIT = its depth) and for the texture-request and shaded
// pixel FIFOs (held_i = 0: the count spans the FIFO too).  The caller admits only with room_o
// and retires each item once: asserted by pipe_credit_assert.sv, bound into every instance
// (simulation checks it, `make formal` proves it in the pipeline's wiring: docs/formal.md).
module pipe_credit #(
  parameter int unsigned LIMIT = 16,                 // items allowed (in flight + held), >= 1
  parameter int unsigned CW    = $clog2(LIMIT) + 1   // width of count_o and held_i
) (
  input  logic          clk_i,
  input  logic          rst_ni,
  input  logic          take_i,   // an item is admitted this clock (only with room_o)
  input  logic          give_i,   // an item leaves the counted region this clock
  input  logic [CW-1:0] held_i,   // items counted elsewhere against the same LIMIT
  output logic          room_o,   // one more item may be admitted this clock
  output logic [CW-1:0] count_o   // items admitted and not yet retired
);

  if (LIMIT < 1 || CW < $clog2(LIMIT + 1)) begin : g_check
    $error("pipe_credit: LIMIT must be >= 1 and CW wide enough to hold LIMIT");
  end

  logic [CW-1:0] cnt_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) cnt_q <= '0;
    else         cnt_q <= cnt_q + CW'(take_i) - CW'(give_i);
  end

  // count + held never exceeds LIMIT (the caller admits only with room), so CW + 1 bits hold it.
  assign room_o  = ({1'b0, cnt_q} + {1'b0, held_i}) < (CW + 1)'(LIMIT);
  assign count_o = cnt_q;

endmodule
