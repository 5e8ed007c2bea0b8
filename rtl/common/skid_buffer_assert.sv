// SPDX-License-Identifier: Apache-2.0
// skid_buffer_assert: the properties of skid_buffer, bound into every instance (the `bind` at
// the end of this file), checked by simulation (Verilator --assert) and proven by `make formal`
// (formal/skid_buffer.sby; docs/formal.md).  Immediate assertions only, in the form the formal
// flow's front end (Yosys read_slang) accepts.
//
//   in_held      the producer holds an offer not taken (valid_i and data_i unchanged): the
//                producer's obligation (the formal wrapper assumes it);
//   out_held     an offer to the consumer not taken stays offered, with the same data, in the
//                next clock (the slice keeps it whatever the producer does);
//   ready_state  ready_o is low exactly while the skid register holds an item, and it holds one
//                only after a stall of the consumer (then valid_o is high);
//   count_model  items taken from the producer - items given to the consumer = the slice's
//                fill (the skid register, and with REG_OUT the output register: 0 .. 2): none
//                lost, none duplicated.
// The order (an item leaves as the next one given on) is proven by the formal wrapper, which
// numbers the items.  Covers: the slice filled; the producer's next item passed straight on in
// the clock after the slice emptied; a full-rate run (three items in three clocks).
`ifndef SYNTHESIS
module skid_buffer_assert #(
  parameter int unsigned W       = 8,    // skid_buffer's W
  parameter bit          REG_OUT = 1'b0  // skid_buffer's REG_OUT
) (
  input logic         clk_i,
  input logic         rst_ni,
  input logic         valid_i,
  input logic         ready_o,
  input logic [W-1:0] data_i,
  input logic         valid_o,
  input logic         ready_i,
  input logic [W-1:0] data_o,
  input logic         full_q     // skid_buffer's full_q
);

  logic         past_q;     // the clock before was out of reset
  logic         in_wait_q;  // the producer's offer was not taken in the clock before
  logic [W-1:0] in_data_q;
  logic         out_wait_q; // the consumer's offer was not taken in the clock before
  logic [W-1:0] out_data_q;
  logic [1:0]   n_q;        // items taken - items given since reset
  logic [1:0]   run_q;      // consecutive clocks with an item given on, saturating at 3
  logic         full_prev_q; // the skid register held an item in the clock before
  logic [1:0]   fill;        // items in the slice (with REG_OUT valid_o is the output register)
  assign fill = 2'(full_q) + 2'(REG_OUT && valid_o);
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      past_q     <= 1'b0;
      in_wait_q  <= 1'b0;
      out_wait_q <= 1'b0;
      n_q        <= '0;
      run_q      <= '0;
      full_prev_q <= 1'b0;
    end else begin
      full_prev_q <= full_q;
      past_q     <= 1'b1;
      in_wait_q  <= valid_i && !ready_o;
      out_wait_q <= valid_o && !ready_i;
      n_q        <= n_q + 2'(valid_i && ready_o) - 2'(valid_o && ready_i);
      run_q      <= (valid_o && ready_i) ? ((run_q == 2'd3) ? run_q : run_q + 2'd1) : '0;
    end
    in_data_q  <= data_i;
    out_data_q <= data_o;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      in_held:     assert (!(past_q && in_wait_q) || (valid_i && data_i == in_data_q))
        else $error("skid_buffer: the producer dropped or changed an offer not taken");
      out_held:    assert (!(past_q && out_wait_q) || (valid_o && data_o == out_data_q))
        else $error("skid_buffer: an offer not taken was dropped or changed");
      ready_state: assert (ready_o == !full_q && (!full_q || valid_o))
        else $error("skid_buffer: ready_o does not follow the slice's fill");
      count_model: assert (n_q == fill)
        else $error("skid_buffer: items taken - given %0d, slice fill %0d", n_q, fill);
      c_full:      cover (full_q);
      c_refill:    cover (past_q && full_prev_q && !full_q && valid_i && ready_i);
      c_full_rate: cover (run_q == 2'd3);
    end
  end

endmodule

bind skid_buffer skid_buffer_assert #(.W(W), .REG_OUT(REG_OUT)) u_assert (
  .clk_i, .rst_ni, .valid_i, .ready_o, .data_i, .valid_o, .ready_i, .data_o, .full_q);
`endif
