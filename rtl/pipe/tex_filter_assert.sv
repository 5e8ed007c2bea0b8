// SPDX-License-Identifier: Apache-2.0
// tex_filter_assert: the simulation checks of tex_filter, bound into every instance (the `bind`
// at the end of this file; not in synthesis).  Immediate assertions in a clocked block, in the
// form the formal flow's front end (Yosys read_slang) accepts ("disable iff (!rst_ni)" is a
// guard on rst_ni).
//
//   core_aligned  the unit's lookups are all in odd or all in even stages (ph_q = 1: odd), so a
//                 unit that takes its two operations in stages of different parity is never
//                 asked for two in one clock;
//   shared_free   each shared unit gets one operation per clock at most: its two stages never
//                 hold lookups at once (the input conversions: no lookup is taken while one is
//                 in S1).
`ifndef SYNTHESIS
module tex_filter_assert #(
  // tex_filter's stages (its localparams of the same names)
  parameter int unsigned S_D0  = 1,   // row differences
  parameter int unsigned S_M0  = 3,   // times fx
  parameter int unsigned S_A0  = 4,   // top, bot
  parameter int unsigned S_D1  = 8,   // bot - top
  parameter int unsigned S_A1  = 13,  // top + ...
  parameter int unsigned S_OUT = 15   // the output stage
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             ph_i,     // tex_filter's ph_q: enabled-clock parity (1: odd stages)
  input logic             take_i,   // take: a lookup enters S1 at this edge
  input logic [S_OUT:1]   sv_i      // sv: sv[k] a lookup in stage k
);

  // The stages of one parity: bit k set for odd k (odd = 1) or even k (odd = 0).
  function automatic logic [S_OUT:1] stage_parity(input logic odd);
    logic [S_OUT:1] p;
    for (int k = 1; k <= S_OUT; k++) p[k] = ((k % 2) == 1) == odd;
    return p;
  endfunction

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      core_aligned: assert ((sv_i & ~stage_parity(ph_i)) == '0)
        else $error("tex_filter: lookups in stages %b, not all of parity %0d", sv_i, ph_i);
      shared_free: assert (!(take_i && sv_i[1]) && !(sv_i[S_D0] && sv_i[S_D0+1])
                           && !(sv_i[S_M0] && sv_i[S_M0+1]) && !(sv_i[S_A0] && sv_i[S_A0+1])
                           && !(sv_i[S_D1-1] && sv_i[S_A1-1]) && !(sv_i[S_D1] && sv_i[S_A1]))
        else $error("tex_filter: a shared unit asked for two operations in one clock");
    end
  end

endmodule

bind tex_filter tex_filter_assert #(.S_D0(S_D0), .S_M0(S_M0), .S_A0(S_A0), .S_D1(S_D1),
                                    .S_A1(S_A1), .S_OUT(S_OUT)) u_assert (
  .clk_i, .rst_ni, .ph_i(ph_q), .take_i(take), .sv_i(sv));
`endif
