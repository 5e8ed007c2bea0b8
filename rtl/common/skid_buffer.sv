// SPDX-License-Identifier: Apache-2.0
// skid_buffer: a one-entry register slice of a valid/ready stream that cuts the ready path only.
//
// ready_o is a flip-flop (!full_q): the consumer's ready_i reaches no logic of the producer in the
// same clock.  While the slice is empty the producer's item passes straight through (valid_o =
// valid_i, data_o = data_i: no clock of latency); an item offered and not taken by the consumer
// is taken into the slice's register at that edge, and the slice then offers it (data_o from the
// register) until the consumer takes it, with ready_o low meanwhile.  The consumer therefore sees
// exactly the sequence of offers it would see without the slice, clock for clock, when the
// producer holds an offer until it is taken; only the producer's handshake comes earlier for an
// item that stalls (it is in the slice then).  At full rate (ready_i high) the stream passes one
// item per clock; a stall costs the producer one clock of ready_o low after the slice empties.
//
// valid_o and data_o are combinational from valid_i and data_i while the slice is empty (the
// producer's paths continue into the consumer), so the slice belongs where the ready path is the
// long one: behind a producer whose valid and data come from registers (a FIFO's head).
// The properties (offer held, items neither lost nor duplicated nor reordered) are in
// skid_buffer_assert.sv, bound into every instance, and proven by `make formal`
// (formal/skid_buffer.sby).
module skid_buffer #(
  parameter int unsigned W = 8   // payload bits (>= 1)
) (
  input  logic         clk_i,
  input  logic         rst_ni,    // synchronous, active low: empties the slice
  input  logic         valid_i,   // the producer's offer (held until taken)
  output logic         ready_o,   // a flip-flop: the slice is empty
  input  logic [W-1:0] data_i,
  output logic         valid_o,   // the consumer's offer: the slice's item, else the producer's
  input  logic         ready_i,
  output logic [W-1:0] data_o
);

  if (W < 1) begin : g_check
    $error("skid_buffer: W must be at least 1");
  end

  logic         full_q;   // the slice holds an item (taken from the producer, not yet given on)
  logic [W-1:0] data_q;   // that item (loaded every clock while empty: no enable from ready_i)

  always_ff @(posedge clk_i) begin
    if (!rst_ni)     full_q <= 1'b0;
    else if (full_q) full_q <= !ready_i;
    else             full_q <= valid_i && !ready_i;
  end

  always_ff @(posedge clk_i) begin
    if (!full_q) data_q <= data_i;
  end

  assign ready_o = !full_q;
  assign valid_o = full_q || valid_i;
  assign data_o  = full_q ? data_q : data_i;

endmodule
