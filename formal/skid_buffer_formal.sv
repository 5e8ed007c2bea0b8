// SPDX-License-Identifier: Apache-2.0
// skid_buffer_formal: skid_buffer alone under SymbiYosys (formal/skid_buffer.sby).  Its inputs
// are free, except what a producer promises (assumed here, asserted by skid_buffer_assert in
// every real use): an offer not taken is held, data and all; and reset in the first clock.  The
// items are numbered: the producer's data is the count of items taken from it (modulo 2^W), so
// the wrapper's own property
//   order   an item given to the consumer is the next one in the producer's order (data_o = the
//           count of items given on)
// with the bound count_model (none lost, none duplicated) says the stream leaves as it came.
// The induction invariants: the numbers differ by the slice's fill (inv_count), and the slice's
// registers hold the next numbers to give on: with REG_OUT the output register the next one
// and the skid register the one after it, else the skid register the next (inv_data; the
// registers read hierarchically).
module skid_buffer_formal #(
  parameter int unsigned W       = 3,    // payload bits (the numbering wraps modulo 2^W)
  parameter bit          REG_OUT = 1'b0  // skid_buffer's REG_OUT
) (
  input logic clk_i,
  input logic rst_ni,
  input logic valid_i,
  input logic ready_i
);

  logic         ready, valid;
  logic [W-1:0] data_o;
  logic [W-1:0] n_in_q, n_out_q;   // items taken from the producer, given to the consumer

  skid_buffer #(.W(W), .REG_OUT(REG_OUT)) u_dut (
    .clk_i, .rst_ni, .valid_i, .ready_o(ready), .data_i(n_in_q), .valid_o(valid), .ready_i,
    .data_o);

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  logic wait_q;      // the producer's offer was not taken in the clock before
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      n_in_q  <= '0;
      n_out_q <= '0;
      wait_q  <= 1'b0;
    end else begin
      n_in_q  <= n_in_q + W'(valid_i && ready);
      n_out_q <= n_out_q + W'(valid && ready_i);
      wait_q  <= valid_i && !ready;
    end
  end

  always_comb begin
    if (wait_q && rst_ni) assume (valid_i);
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      order:     assert (!valid || data_o == n_out_q);
      inv_count: assert (n_in_q - n_out_q == W'(u_dut.full_q) + W'(REG_OUT && valid));
      inv_data:  assert (!u_dut.full_q || u_dut.data_q == n_out_q + W'(REG_OUT && valid));
    end
  end

endmodule
