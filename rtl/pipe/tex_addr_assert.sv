// SPDX-License-Identifier: Apache-2.0
// tex_addr_assert: the simulation check of tex_addr, bound into every instance (the `bind` at the
// end of this file; not in synthesis).  Immediate assertions in a clocked block, in the form the
// formal flow's front end (Yosys read_slang) accepts.
//
//   lookup_spacing  the axes share the float units: no lookup on the enabled clock after another
//                   (its v item's).
`ifndef SYNTHESIS
module tex_addr_assert (
  input logic clk_i,
  input logic rst_ni,
  input logic en_i,
  input logic valid_i,
  input logic stage_v1_i   // tex_addr's stage_v[1]: the last enabled clock took a lookup
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      lookup_spacing: assert (!(en_i && valid_i) || !stage_v1_i)
        else $error("tex_addr: lookups on two consecutive enabled clocks");
    end
  end

endmodule

bind tex_addr tex_addr_assert u_assert (.clk_i, .rst_ni, .en_i, .valid_i,
  .stage_v1_i(stage_v[1]));
`endif
