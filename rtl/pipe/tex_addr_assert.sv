// SPDX-License-Identifier: Apache-2.0
// tex_addr_assert: the simulation check of tex_addr, bound into every instance (not in
// synthesis): the axes share the float units (a lookup's v item follows its u item), so no lookup
// on the enabled clock after another (rtl/common/spacing_assert.sv).
`ifndef SYNTHESIS
bind tex_addr spacing_assert #(.WHAT("tex_addr: lookups")) u_assert (.clk_i, .rst_ni, .en_i,
  .valid_i, .taken_i(stage_v[1]));
`endif
