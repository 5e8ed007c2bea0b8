// SPDX-License-Identifier: Apache-2.0
// mip_level_assert: the simulation check of mip_level, bound into every instance (the `bind` at
// the end of this file; not in synthesis).  Immediate assertions in a clocked block, in the form
// the formal flow's front end (Yosys read_slang) accepts.
//
//   hit_spacing  the textures share the lod datapath: no hit on the enabled clock after another.
`ifndef SYNTHESIS
module mip_level_assert (
  input logic clk_i,
  input logic rst_ni,
  input logic en_i,
  input logic valid_i,
  input logic hit_v1_i   // mip_level's hit_v[1]: the last enabled clock took a hit
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      hit_spacing: assert (!(en_i && valid_i) || !hit_v1_i)
        else $error("mip_level: hits on two consecutive enabled clocks");
    end
  end

endmodule

bind mip_level mip_level_assert u_assert (.clk_i, .rst_ni, .en_i, .valid_i, .hit_v1_i(hit_v[1]));
`endif
