// SPDX-License-Identifier: Apache-2.0
// f24_cmp: compare a with b; exactly one of lt_o, eq_o, gt_o, un_o is 1 (un_o: an operand is NaN).
// -0 == +0 and subnormal patterns compare as zeros. Latency LAT enabled clocks (1, the default,
// or 2); the result is the same at both.  LAT = 2 adds one plain enabled delay register
// (f24_delay) after the unit's register: its one stage is shorter than the float adder's and
// multiplier's, so a second register inside it would buy no clock speed.
module f24_cmp
  import f24_pkg::*;
#(
  parameter int unsigned LAT = 1  // latency in enabled clocks, 1 (the default) or 2
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,
  input  f24_t b_i,
  output logic lt_o,
  output logic eq_o,
  output logic gt_o,
  output logic un_o
);

  logic        a_zero, b_zero, a_nan, b_nan;
  logic [23:0] ka, kb;  // order-preserving keys: magnitude with the sign folded in
  logic [3:0]  res_d, res_q;  // {lt, eq, gt, un}
  logic [3:0]  res;           // res_q after LAT - 1 delay registers

  if (LAT < 1 || LAT > 2) begin : g_check_lat
    $error("f24_cmp: LAT must be 1 or 2");
  end

  // Map a pattern to an unsigned key whose order is the numeric order: zeros (either sign) give
  // 2^23, a positive magnitude m gives 2^23 + m, a negative one 2^23 - 1 - m (~m in 23 bits).
  function automatic logic [23:0] order_key(input f24_t x, input logic is_zero);
    return is_zero ? 24'h800000 : x[23] ? {1'b0, ~x[22:0]} : {1'b1, x[22:0]};
  endfunction

  always_comb begin
    a_zero = (a_i[22:16] == 7'd0);
    b_zero = (b_i[22:16] == 7'd0);
    a_nan  = (a_i[22:16] == EXP_SPEC) && (a_i[15:0] != 16'd0);
    b_nan  = (b_i[22:16] == EXP_SPEC) && (b_i[15:0] != 16'd0);
    ka     = order_key(a_i, a_zero);
    kb     = order_key(b_i, b_zero);
    res_d  = (a_nan || b_nan) ? 4'b0001
           : (ka < kb)        ? 4'b1000
           : (ka == kb)       ? 4'b0100
           :                    4'b0010;
  end

  always_ff @(posedge clk_i) begin
    if (en_i) res_q <= res_d;
  end

  if (LAT > 1) begin : g_delay
    f24_delay #(.W(4), .N(LAT - 1)) u_delay (
      .clk_i, .en_i, .d_i(res_q), .q_o(res)
    );
  end else begin : g_out
    assign res = res_q;
  end

  assign {lt_o, eq_o, gt_o, un_o} = res;

  // The simulation checks are in f24_cmp_assert.sv (bound into every instance).

endmodule
