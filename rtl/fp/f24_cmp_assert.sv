// SPDX-License-Identifier: Apache-2.0
// f24_cmp_assert: the simulation check of f24_cmp, bound into every instance (the `bind` at the
// end of this file; not in synthesis).  Immediate assertions in a clocked block, in the form the
// formal flow's front end (Yosys read_slang) accepts.
//
//   one_relation  exactly one of {lt, eq, gt, un} holds in the result register once it has been
//                 loaded (the unit has no reset, FLOAT24.md ports: a tracker of its own, starting
//                 from 0, records the first enabled clock).
`ifndef SYNTHESIS
module f24_cmp_assert (
  input logic       clk_i,
  input logic       en_i,
  input logic [3:0] res_i   // f24_cmp's res_q: {lt, eq, gt, un}
);

  /* verilator lint_off PROCASSINIT */
  logic loaded_q = 1'b0;   // the result register has been loaded
  /* verilator lint_on PROCASSINIT */
  always_ff @(posedge clk_i) if (en_i) loaded_q <= 1'b1;

  always_ff @(posedge clk_i) begin
    one_relation: assert (!loaded_q || $onehot(res_i))
      else $error("f24_cmp: {lt, eq, gt, un} = %b, not exactly one relation", res_i);
  end

endmodule

bind f24_cmp f24_cmp_assert u_assert (.clk_i, .en_i, .res_i(res_q));
`endif
