// SPDX-License-Identifier: Apache-2.0
// traverse_bdiff_assert: the simulation check of traverse_bdiff, bound into every instance (the
// `bind` at the end of this file; not in synthesis).  Immediate assertions in a clocked block.
//
//   same_word_as_add  for every operand set inside the unit's range (0 <= b < 2^16, u a
//                     non-negative f24 below 2^16), the result is the word of
//                     f24_add(f24_from_int(b), -u), computed beside it by those two units (the
//                     operations the unit replaces); sets outside the range are not checked here
//                     (the ring's checker flags them where the ring uses the result).
`ifndef SYNTHESIS
module traverse_bdiff_assert
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned W  = 20,
  parameter int unsigned NB = 1
) (
  input logic                clk_i,
  input logic                en_i,
  input logic signed [W-1:0] b_i [NB],
  input f24_t                u_i,
  input f24_t                y_i [NB]  // y_o
);

  // The range of the operands (traverse_bdiff's header).
  function automatic logic in_range(input logic signed [W-1:0] b, input logic [7:0] se);
    return (b >= 0) && (b < (W'(1) <<< 16)) && (se[6:0] <= 7'd78) && (!se[7] || se[6:0] == 7'd0);
  endfunction

  f24_t        nu1_q;       // -u, one enabled clock later (f24_add's operand)
  logic [2:0]  ok_q [NB];   // ok_q[i][s]: the set in stage s + 1 was inside the range
  logic [1:0]  cnt_q;       // enabled clocks since the start, up to 3 (the pipeline is full)
  f24_t        bf [NB], ref_y [NB];

  initial begin
    cnt_q = '0;
  end

  for (genvar g = 0; g < NB; g++) begin : g_ref
    f24_from_int #(.W(W)) u_ref_int (.clk_i, .en_i, .k_i(b_i[g]), .y_o(bf[g]));
    f24_add u_ref_add (.clk_i, .en_i, .a_i(bf[g]), .b_i(nu1_q), .y_o(ref_y[g]));

    always_ff @(posedge clk_i) begin
      if (en_i) ok_q[g] <= {ok_q[g][1:0], in_range(b_i[g], u_i[23:16])};
    end

    always_ff @(posedge clk_i) begin
      if (cnt_q == 2'd3 && ok_q[g][2]) begin
        same_word_as_add: assert (y_i[g] == ref_y[g])
          else $error("traverse_bdiff: result %h, f24_add(f24_from_int(b), -u) gives %h", y_i[g],
                      ref_y[g]);
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      nu1_q <= f24_neg(u_i);
      if (cnt_q != 2'd3) cnt_q <= cnt_q + 2'd1;
    end
  end

endmodule

bind traverse_bdiff traverse_bdiff_assert #(.W(W), .NB(NB)) u_assert (
  .clk_i, .en_i, .b_i, .u_i, .y_i(y_o));
`endif
