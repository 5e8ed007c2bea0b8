// SPDX-License-Identifier: Apache-2.0
// view_calc_assert: the simulation check of view_calc, bound into every instance (not in
// synthesis): x and y share lane TB and the scale multiplier, so no fragment on the enabled clock
// after one (rtl/common/spacing_assert.sv).
`ifndef SYNTHESIS
bind view_calc spacing_assert #(.WHAT("view_calc: fragments")) u_assert (.clk_i, .rst_ni, .en_i,
  .valid_i, .taken_i(stage_v[1]));
`endif
