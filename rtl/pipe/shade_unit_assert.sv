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
//                  most (the stages it takes its operands in: the table below).
`ifndef SYNTHESIS
module shade_unit_assert
  import shade_pkg::*;
#(
  parameter int unsigned NPS = 20   // shade_unit's NPS: shared units with an operand select
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

  localparam int unsigned CS = SHADE_LAT - 3;   // core stages S1 .. S41

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
  localparam int NSH = 26;
  logic [CS:1] shared [NSH];
  assign shared = '{
    ops(1, 12, 0, 0),   ops(1, 19, 20, 30),  ops(8, 9, 0, 0),     ops(8, 9, 0, 0),    // mul
    ops(9, 10, 0, 0),   ops(12, 13, 26, 27), ops(19, 20, 21, 22), ops(20, 21, 0, 0),
    ops(20, 21, 0, 0),  ops(20, 21, 0, 0),   ops(28, 29, 30, 31), ops(29, 30, 0, 0),
    ops(35, 36, 37, 0),
    ops(1, 2, 0, 0),    ops(1, 2, 0, 0),     ops(4, 15, 0, 0),    ops(9, 10, 0, 0),   // add
    ops(10, 11, 0, 0),  ops(12, 13, 0, 0),   ops(21, 22, 0, 0),   ops(23, 24, 0, 0),
    ops(27, 32, 0, 0),  ops(32, 33, 0, 0),   ops(36, 37, 38, 0),
    ops(6, 16, 17, 0),  ops(38, 39, 40, 0)};                                          // rsqrt, idx

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
