// SPDX-License-Identifier: Apache-2.0
// mip_level_assert: the simulation checks of mip_level, bound into every instance (not in
// synthesis; rtl/common/spacing_assert.sv): the textures share the lod datapath, so no hit on the
// enabled clock after another (spacing); one adder serves Pl and the two lods, so no hit GAP or
// GAP + 1 enabled clocks after another (share_gap), and so the adder's operand select never
// has Pl's operands and a lod job in one clock (share_free).
`ifndef SYNTHESIS
bind mip_level spacing_assert #(.WHAT("mip_level: hits")) u_assert (.clk_i, .rst_ni, .en_i,
  .valid_i, .taken_i(hit_v[1]));
bind mip_level spacing_assert #(.WHAT("mip_level: hits"),
  .RULE("mip_gap or mip_gap + 1 enabled clocks apart (the shared adder)")) u_share_gap (.clk_i,
  .rst_ni, .en_i, .valid_i, .taken_i(hit_v[GAP] || hit_v[GAP + 1]));
bind mip_level spacing_assert #(.WHAT("mip_level: the adder's operand select"),
  .RULE("has Pl's operands and a lod job in one clock")) u_share_free (.clk_i, .rst_ni, .en_i,
  .valid_i(hit_v[S_PL]), .taken_i(v6 || nrm_pend_q));
`endif
