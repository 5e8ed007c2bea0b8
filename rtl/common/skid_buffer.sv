// SPDX-License-Identifier: Apache-2.0
// skid_buffer: a register slice of a valid/ready stream.  ready_o is a flip-flop (!full_q): the
// consumer's ready_i reaches no logic of the producer in the same clock.
//
// REG_OUT = 0 (the ready path cut only): while the slice is empty the producer's item passes
// straight through (valid_o = valid_i, data_o = data_i: no clock of latency); an item offered
// and not taken by the consumer is taken into the slice's register at that edge, and the slice
// then offers it (data_o from the register) until the consumer takes it, with ready_o low
// meanwhile.  The consumer sees exactly the offers it would see without the slice, clock for
// clock, when the producer holds an offer until it is taken; only the producer's handshake comes
// earlier for an item that stalls.  valid_o and data_o are combinational from valid_i and data_i
// while the slice is empty, so the producer's paths continue into the consumer.
//
// REG_OUT = 1 (both directions cut): valid_o and data_o are an output register as well, one
// clock of latency; the second register (the skid) takes the producer's item when the output
// register is stalled, so the stream still passes one item per clock at full rate.
//
// At full rate (ready_i high) both pass one item per clock; after a stall ready_o is low for the
// clock the held item leaves.  The properties (offers held, items neither lost nor duplicated
// nor reordered) are in skid_buffer_assert.sv, bound into every instance, and proven by
// `make formal` (formal/skid_buffer.sby, both modes).
module skid_buffer #(
  parameter int unsigned W       = 8,     // payload bits (>= 1)
  parameter bit          REG_OUT = 1'b0   // 1: valid_o, data_o from a register too (above)
) (
  input  logic         clk_i,
  input  logic         rst_ni,    // synchronous, active low: empties the slice
  input  logic         valid_i,   // the producer's offer (held until taken)
  output logic         ready_o,   // a flip-flop: the skid register is empty
  input  logic [W-1:0] data_i,
  output logic         valid_o,   // the consumer's offer
  input  logic         ready_i,
  output logic [W-1:0] data_o
);

  if (W < 1) begin : g_check
    $error("skid_buffer: W must be at least 1");
  end

  logic         full_q;   // the skid register holds an item (not yet given on)
  logic [W-1:0] data_q;   // that item (loaded every clock while empty: no enable from ready_i)

  assign ready_o = !full_q;

  always_ff @(posedge clk_i) begin
    if (!full_q) data_q <= data_i;
  end

  if (REG_OUT) begin : g_reg
    logic         out_v_q;   // the output register holds an item
    logic [W-1:0] out_q;
    logic         adv;       // the output register loads: it is empty or its item leaves
    assign adv = !out_v_q || ready_i;
    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        out_v_q <= 1'b0;
        full_q  <= 1'b0;
      end else if (adv) begin
        out_v_q <= full_q || valid_i;    // the skid's item first, else the producer's
        full_q  <= 1'b0;
      end else begin
        full_q  <= full_q || valid_i;    // stalled: the producer's item into the skid
      end
    end
    always_ff @(posedge clk_i) begin
      if (adv) out_q <= full_q ? data_q : data_i;
    end
    assign valid_o = out_v_q;
    assign data_o  = out_q;
  end else begin : g_pass
    always_ff @(posedge clk_i) begin
      if (!rst_ni)     full_q <= 1'b0;
      else if (full_q) full_q <= !ready_i;
      else             full_q <= valid_i && !ready_i;
    end
    assign valid_o = full_q || valid_i;
    assign data_o  = full_q ? data_q : data_i;
  end

endmodule
