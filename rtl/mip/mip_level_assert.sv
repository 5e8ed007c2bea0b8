// SPDX-License-Identifier: Apache-2.0
// mip_level_assert: the simulation check of mip_level, bound into every instance (not in
// synthesis): the textures share the lod datapath, so no hit on the enabled clock after another
// (rtl/common/spacing_assert.sv).
`ifndef SYNTHESIS
bind mip_level spacing_assert #(.WHAT("mip_level: hits")) u_assert (.clk_i, .rst_ni, .en_i,
  .valid_i, .taken_i(hit_v[1]));
`endif
