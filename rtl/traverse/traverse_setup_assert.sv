// SPDX-License-Identifier: Apache-2.0
// traverse_setup_assert: the simulation check of traverse_setup, bound into every instance (the
// `bind` at the end of this file; not in synthesis).  Immediate assertions in a clocked block, in
// the form the formal flow's front end (Yosys read_slang) accepts.
//
//   ray_spacing  u and v share the float units a clock apart: no ray in the clock after one.
`ifndef SYNTHESIS
module traverse_setup_assert (
  input logic clk_i,
  input logic rst_ni,
  input logic in_valid_i,
  input logic v0_i   // traverse_setup's v_q[0]: stage T0 holds a ray
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      ray_spacing: assert (!in_valid_i || !v0_i)
        else $error("traverse_setup: rays on two consecutive clocks");
    end
  end

endmodule

bind traverse_setup traverse_setup_assert u_assert (.clk_i, .rst_ni, .in_valid_i, .v0_i(v_q[0]));
`endif
