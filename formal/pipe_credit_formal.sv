// SPDX-License-Identifier: Apache-2.0
// pipe_credit_formal: pipe_credit alone under SymbiYosys (formal/pipe_credit.sby), as
// dm_pipeline's back-end credits use it (u_req_credit, u_out_credit: held_i = 0, the count spans
// the FIFO too).  Its inputs are free, except what the caller promises (assumed here, asserted by
// pipe_credit_assert in every real use): admit only with room_o, retire only a counted item, and
// reset in the first clock.  The use with held_i (FIFO #0's fill) is proven in
// formal/pipe_f0_formal.sv.
module pipe_credit_formal #(
  parameter int unsigned LIMIT = 16   // items allowed (REQ_DEPTH 16, OUT_DEPTH 64 in dm_pipeline)
) (
  input logic clk_i,
  input logic rst_ni,
  input logic take_i,
  input logic give_i
);

  localparam int unsigned CW = $clog2(LIMIT) + 1;

  logic          room;
  logic [CW-1:0] count;

  pipe_credit #(.LIMIT(LIMIT), .CW(CW)) u_dut (
    .clk_i, .rst_ni, .take_i, .give_i, .held_i('0), .room_o(room), .count_o(count));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  always_comb begin
    assume (!(take_i && !room));
    assume (!(give_i && count == '0));
  end

endmodule
