// SPDX-License-Identifier: Apache-2.0
// pipe_credit_assert: the properties of pipe_credit, bound into every instance (the `bind` at
// the end of this file), checked by simulation (Verilator --assert) and proven by `make formal`
// (formal/pipe_credit.sby, formal/pipe_f0.sby; docs/formal.md).  Immediate assertions only, in
// the form the formal flow's front end (Yosys read_slang) accepts.
//
//   take_with_room  an item is admitted only with room_o (the caller's obligation: assumed by the
//                   formal wrapper of pipe_credit alone, proven in the pipeline's wiring);
//   give_counted    an item is retired only while the count is not 0 (the caller's obligation);
//   count_model     count_o = takes - gives since reset (a counter of its own, one bit wider);
//   within_limit    count_o + held_i <= LIMIT (holds when the callers keep their obligations
//                   and held_i grows only by items that leave the count: proven in the
//                   pipeline's wiring, formal/pipe_f0_formal.sv).
// Covers: the limit reached (no room), and room again after it.
`ifndef SYNTHESIS
module pipe_credit_assert #(
  parameter int unsigned LIMIT = 16,  // pipe_credit's LIMIT
  parameter int unsigned CW    = 5    // pipe_credit's CW
) (
  input logic          clk_i,
  input logic          rst_ni,
  input logic          take_i,
  input logic          give_i,
  input logic [CW-1:0] held_i,
  input logic          room_i,   // pipe_credit's room_o
  input logic [CW-1:0] count_i   // count_o
);

  logic [CW:0] n_q;   // takes - gives since reset
  always_ff @(posedge clk_i) begin
    if (!rst_ni) n_q <= '0;
    else         n_q <= n_q + (CW+1)'(take_i) - (CW+1)'(give_i);
  end

  logic was_full_q;   // the limit was reached since reset
  always_ff @(posedge clk_i) begin
    if (!rst_ni)      was_full_q <= 1'b0;
    else if (!room_i) was_full_q <= 1'b1;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      take_with_room: assert (!(take_i && !room_i))
        else $error("pipe_credit: item admitted without room");
      give_counted:   assert (!(give_i && count_i == '0))
        else $error("pipe_credit: item retired that was never admitted");
      count_model:    assert (n_q == {1'b0, count_i})
        else $error("pipe_credit: count_o %0d, takes - gives %0d", count_i, n_q);
      within_limit:   assert (({1'b0, count_i} + {1'b0, held_i}) <= (CW + 1)'(LIMIT))
        else $error("pipe_credit: more than LIMIT items");
      c_no_room:      cover (!room_i);
      c_room_again:   cover (was_full_q && room_i && take_i);
    end
  end

endmodule

bind pipe_credit pipe_credit_assert #(.LIMIT(LIMIT), .CW(CW)) u_assert (
  .clk_i, .rst_ni, .take_i, .give_i, .held_i, .room_i(room_o), .count_i(count_o));
`endif
