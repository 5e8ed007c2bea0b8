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
//                  most (the stages it works on its operands in: from shade_pkg's schedule).
`ifndef SYNTHESIS
module shade_unit_assert
  import shade_pkg::*;
#(
  parameter int unsigned NPS     = 16,  // shade_unit's NPS: operand selects with a phase replica
  parameter int unsigned ADD_LAT = 2,   // shade_unit's ADD_LAT, MUL_LAT: the schedule
  parameter int unsigned MUL_LAT = 1,
  localparam int unsigned CS = shade_lat(ADD_LAT, MUL_LAT) - 3  // core stages S1 .. SCS
) (
  input logic           clk_i,
  input logic           rst_ni,
  input logic           en_i,
  input logic           valid_i,
  input logic [3:1]     stage_v_i,  // shade_unit's stage_v[3:1]
  input logic           hv_i,       // hv_q: a pixel waits in the hold registers
  input logic [CS:1]    cv_i,       // cv_q: core stage valid bits
  input logic [1:0]     ph_i,       // ph_q: enabled clocks modulo 4
  input logic [3:0]     ps_i [NPS]  // ps_q: the phase replicas
);

  // The core stages k with k mod 4 = r.
  function automatic logic [CS:1] stage_phase(input logic [1:0] r);
    logic [CS:1] m;
    for (int k = 1; k <= CS; k++) m[k] = (k % 4) == int'(r);
    return m;
  endfunction

  // Stages a, a + 1, .., a + n - 1 as a mask of core stages.
  function automatic logic [CS:1] run(input int unsigned a, input int unsigned n);
    logic [CS:1] m;
    m = '0;
    for (int unsigned k = 1; k <= CS; k++) m[k] = (k >= a) && (k < a + n);
    return m;
  endfunction

  // The stages shared unit u (shade_pkg::U_*) works on its operands in (the schedule).
  function automatic logic [CS:1] unit_ops(input int unsigned u);
    logic [CS:1] m;
    m = '0;
    for (int unsigned op = 0; op < SHADE_NOPS; op++) begin
      if (shade_op_unit(op) == u) begin
        m = m | run(shade_op_stage(op, ADD_LAT, MUL_LAT), shade_op_stream(op) ? 2 : 1);
      end
    end
    return m;
  endfunction

  localparam int unsigned C0 = shade_clamp_stage(ADD_LAT, MUL_LAT);  // the tail's first stage
  // Every float unit with more than one operation: the shared units (with u_va and u_caa, one
  // stream each), u_nsqa and u_nla (streams fed directly), the tail's c 255 and its
  // floor(. + 0.5).
  localparam int NSH = SHADE_NUNITS + 4;
  logic [CS:1] shared [NSH];
  for (genvar u = 0; u < SHADE_NUNITS; u++) begin : g_unit
    assign shared[u] = unit_ops(u);
  end
  assign shared[SHADE_NUNITS]     = run(shade_op_stage(OP_NXZ, ADD_LAT, MUL_LAT) + ADD_LAT, 2);
  assign shared[SHADE_NUNITS + 1] = run(shade_op_stage(OP_NUXZ, ADD_LAT, MUL_LAT) + MUL_LAT, 2);
  assign shared[SHADE_NUNITS + 2] = run(C0 + 1, 3);
  assign shared[SHADE_NUNITS + 3] = run(C0 + 1 + MUL_LAT, 3);

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

bind shade_unit shade_unit_assert #(
  .NPS(NPS), .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT)
) u_assert (
  .clk_i, .rst_ni, .en_i, .valid_i, .stage_v_i(stage_v[3:1]), .hv_i(hv_q), .cv_i(cv_q),
  .ph_i(ph_q), .ps_i(ps_q));
`endif
