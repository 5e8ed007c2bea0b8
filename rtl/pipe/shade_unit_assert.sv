// SPDX-License-Identifier: Apache-2.0
// shade_unit_assert: the simulation checks of shade_unit, bound into every instance (the `bind`
// at the end of this file; not in synthesis).  Immediate assertions in a clocked block, in the
// form the formal flow's front end (Yosys read_slang) accepts ("disable iff (!rst_ni)" is a
// guard on rst_ni).
//
//   pixel_spacing  at least 4 enabled clocks between two pixels, so the hold registers are free
//                  when one comes;
//   core_aligned   the core's pixels are all in stages k with k mod 4 = ph_q, so a unit whose
//                  operations are in stages that differ pairwise by amounts not divisible by 4
//                  never gets two in one clock;
//   phase_replica  every phase replica (ps_q) is ph_q, one-hot;
//   unit_once      every float unit with more than one operation gets one pixel per clock at
//                  most (the stages it works on its operands in: the table below).
`ifndef SYNTHESIS
module shade_unit_assert
  import shade_pkg::*;
#(
  parameter int unsigned NPS = 16   // shade_unit's NPS: operand selects with a phase replica
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic                  en_i,
  input logic                  valid_i,
  input logic [3:1]            stage_v_i,  // shade_unit's stage_v[3:1]
  input logic                  hv_i,       // hv_q: a pixel waits in the hold registers
  input logic [SHADE_LAT-3:1]  cv_i,       // cv_q: core stage valid bits
  input logic [1:0]            ph_i,       // ph_q: enabled clocks modulo 4
  input logic [3:0]            ps_i [NPS]  // ps_q: the phase replicas
);

  localparam int unsigned CS = SHADE_LAT - 3;   // core stages S1 .. S56

  // The core stages k with k mod 4 = r.
  function automatic logic [CS:1] stage_phase(input logic [1:0] r);
    logic [CS:1] m;
    for (int k = 1; k <= CS; k++) m[k] = (k % 4) == int'(r);
    return m;
  endfunction

  // A shared unit's operation stages (0: none), as a mask of core stages.
  function automatic logic [CS:1] ops(input int a, input int b, input int c, input int d);
    logic [CS:1] m;
    m = '0;
    for (int k = 1; k <= CS; k++) m[k] = (k == a) || (k == b) || (k == c) || (k == d);
    return m;
  endfunction

  // Every float unit with more than one operation: the stages it takes its operands in.
  localparam int NSH = 19;
  logic [CS:1] shared [NSH];
  assign shared = '{
    ops(1, 18, 0, 0),   ops(1, 19, 20, 46),  ops(3, 4, 0, 0),     ops(4, 13, 30, 31), // mul
    ops(13, 14, 0, 0),  ops(18, 19, 40, 0),  ops(19, 32, 33, 0),  ops(20, 21, 0, 0),
    ops(21, 30, 32, 0), ops(45, 46, 0, 0),   ops(50, 51, 52, 0),
    ops(1, 2, 47, 48),  ops(1, 3, 42, 48),   ops(6, 9, 20, 23),   ops(6, 15, 16, 25), // add
    ops(15, 34, 36, 37), ops(51, 52, 53, 0),
    ops(9, 15, 26, 0),  ops(53, 54, 55, 0)};                                          // rsqrt, idx

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      pixel_spacing: assert (!(en_i && valid_i) || (!(|stage_v_i) && !hv_i))
        else $error("shade_unit: a pixel within 4 enabled clocks of another");
      core_aligned: assert ((cv_i & ~stage_phase(ph_i)) == '0)
        else $error("shade_unit: core stages %b not all of phase %0d", cv_i, ph_i);
    end
  end

  for (genvar u = 0; u < NPS; u++) begin : g_ps_check
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        phase_replica: assert (ps_i[u] == (4'b0001 << ph_i))
          else $error("shade_unit: phase replica %0d is %b, phase %0d", u, ps_i[u], ph_i);
      end
    end
  end

  for (genvar u = 0; u < NSH; u++) begin : g_shared
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        unit_once: assert ($onehot0(cv_i & shared[u]))
          else $error("shade_unit: shared unit %0d asked for two operations in one clock", u);
      end
    end
  end

endmodule

bind shade_unit shade_unit_assert #(.NPS(NPS)) u_assert (
  .clk_i, .rst_ni, .en_i, .valid_i, .stage_v_i(stage_v[3:1]), .hv_i(hv_q), .cv_i(cv_q),
  .ph_i(ph_q), .ps_i(ps_q));
`endif
