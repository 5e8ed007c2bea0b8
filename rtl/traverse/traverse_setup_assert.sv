// SPDX-License-Identifier: Apache-2.0
// traverse_setup_assert: the checks of traverse_setup, bound into every instance (the `bind` at
// the end of this file; not in synthesis), checked by simulation and proven by `make formal`
// (formal/traverse_setup.sby, the float datapath cut; docs/formal.md).  Immediate assertions in
// a clocked block, in the form the formal flow's front end (Yosys read_slang) accepts.
//
//   ray_phase       a ray enters only while in_ready_o (the user's obligation), so that any two
//                   rays are a multiple of 4 clocks apart (the float units are shared over 4
//                   clocks: u and v a clock apart, two operations of an axis 6 stages apart);
//   ray_spacing     no ray in the 3 clocks after one (what ray_phase implies, checked on its own);
//   ray_phase_of_stage  a ray in stage Ts only at phase s mod 4 (the induction invariant of
//                   ray_spacing);
//   setup_id_order  a tracked ray (formal: any ray, picked freely; simulation: every ray that
//                   enters while none is tracked) comes out NS clocks after it entered (NS =
//                   setup_lat(ADD_LAT, MUL_LAT), traverse_setup's latency),
//                   with its id: the pipeline neither loses, duplicates nor swaps ids;
//   trk_in_setup    while inside, the tracked ray's stage holds a ray and its id (the stage
//                   registers of T0 - T(NT-1), the output registers of T(NT) - T(NS-1)): the
//                   invariant that makes the induction step hold.
// Data check (simulation; formal/traverse_setup.sby cuts the float datapath and removes it):
//   t0_same_as_units  the start time (1 - H_root on the shared adder and multiplier, H_root in
//                   two registered steps) is the word of f24_from_unorm and f24_add(1, -H_root)
//                   beside it (an f24_add of ADD_LAT, as the shared one), whenever a ray is
//                   inside, however short the idle stretch before it (given the configuration
//                   stable 4 + ADD_LAT clocks before the ray, traverse_unit's rule).
`ifndef SYNTHESIS
module traverse_setup_assert
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W    = 16,  // traverse_setup's ID_W
  parameter int unsigned ADD_LAT = 2,   // traverse_setup's ADD_LAT (the reference adder's)
  parameter int unsigned NS      = 21,  // its stages (setup_lat(ADD_LAT, MUL_LAT))
  parameter int unsigned NT      = 16,  // its stages with stage registers (T0 .. T(NT-1))
  parameter int unsigned NO      = 5    // its output registers (stages T(NT) .. T(NS-1))
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                in_ready_i,       // traverse_setup's in_ready_o
  input logic                in_valid_i,
  input logic [ID_W-1:0]     in_id_i,
  input logic [NS-1:0]       v_i,          // traverse_setup's v_q: stage Ts holds a ray
  input logic                out_valid_i,
  input logic [ID_W-1:0]     out_id_i,
  input logic [ID_W-1:0]     id_stage_i [NT],    // the ids of T0 .. T(NT-1) (id_s)
  input logic [ID_W-1:0]     out_id_reg_i [NO],  // the ids of T(NT) .. T(NS-1) (out_id_q)
  input logic [1:0]          ph_i,         // traverse_setup's phase (ph_q, mod 4)
  input logic                idle_i,
  input logic [CODE_W-1:0]   root_code_i,  // cfg_i.root_code, .bits16, .policy.clip
  input logic                bits16_i,
  input logic                clip_i,
  input f24_t                t0_i          // t0_q
);

  localparam int unsigned AW = $clog2(NS);

  // The id each stage holds: T0 - T(NT-1) their stage registers, the rest the output registers.
  logic [ID_W-1:0] stage_id [NS];
  always_comb begin
    for (int s = 0; s < NT; s++) stage_id[s] = id_stage_i[s];
    for (int o = 0; o < NO; o++) stage_id[NT+o] = out_id_reg_i[o];
  end

  // pick: which ray to track.  Formal leaves it undriven (a free input: every ray may be the
  // tracked one); simulation tracks whenever it can.
  logic pick;
`ifndef FORMAL
  assign pick = 1'b1;
`endif
  logic            trk_q;      // a ray is tracked
  logic [ID_W-1:0] trk_id_q;   // its id
  logic [AW-1:0]   trk_s_q;    // its stage
  logic            trk_out;    // it leaves in this clock
  assign trk_out = trk_q && trk_s_q == AW'(NS - 1);
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      trk_q <= 1'b0;
    end else if (in_valid_i && pick && (!trk_q || trk_out)) begin
      trk_q    <= 1'b1;
      trk_id_q <= in_id_i;
      trk_s_q  <= '0;
    end else if (trk_out) begin
      trk_q <= 1'b0;
    end else if (trk_q) begin
      trk_s_q <= trk_s_q + AW'(1);
    end
  end

  // A ray in stage Ts: the phase is s mod 4 (the invariant that makes ray_spacing inductive).
  logic phase_ok;
  always_comb begin
    phase_ok = 1'b1;
    for (int s = 0; s < NS; s++) begin
      if (v_i[s] && ph_i != 2'(s)) phase_ok = 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      ray_phase: assert (!in_valid_i || in_ready_i)
        else $error("traverse_setup: a ray entered while in_ready_o = 0");
      ray_spacing: assert (!in_valid_i || v_i[2:0] == '0)
        else $error("traverse_setup: a ray less than 4 clocks after the one before");
      ray_phase_of_stage: assert (phase_ok)
        else $error("traverse_setup: a ray in a stage off the phase");
      setup_id_order: assert (!trk_out || (out_valid_i && out_id_i == trk_id_q))
        else $error("traverse_setup: ray id %0d due out, out_valid %0d id %0d", trk_id_q,
                    out_valid_i, out_id_i);
      trk_in_setup: assert (!trk_q || (32'(trk_s_q) < NS && v_i[trk_s_q]
                                       && stage_id[trk_s_q] == trk_id_q))
        else $error("traverse_setup: the tracked ray (id %0d) is not at its stage %0d", trk_id_q,
                    trk_s_q);
    end
  end

  // The reference start time: the units the first mode used before sharing.
  f24_t h8, h16, ref_t0;
  f24_from_unorm #(.W(8))  u_ref_h8  (.clk_i, .en_i(idle_i), .k_i(root_code_i[7:0]), .y_o(h8));
  f24_from_unorm #(.W(16)) u_ref_h16 (.clk_i, .en_i(idle_i), .k_i(root_code_i), .y_o(h16));
  f24_add #(.LAT(ADD_LAT)) u_ref_plane (.clk_i, .en_i(idle_i), .a_i(F24_ONE),
                                        .b_i(f24_neg(bits16_i ? h16 : h8)), .y_o(ref_t0));
  f24_t ref_t0_q;
  always_ff @(posedge clk_i) begin
    if (idle_i) ref_t0_q <= clip_i ? f24_max(F24_POS_ZERO, ref_t0) : F24_POS_ZERO;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      t0_same_as_units: assert (idle_i || t0_i == ref_t0_q)
        else $error("traverse_setup: t0 %h, f24_add(1, -f24_from_unorm(root)) gives %h", t0_i,
                    ref_t0_q);
    end
  end

endmodule

// The parameters and the id path of the instance (its localparams NS, NT, NO: the schedule).
bind traverse_setup traverse_setup_assert #(.ID_W(ID_W), .ADD_LAT(ADD_LAT),
                                            .NS(NS), .NT(NT), .NO(NO)) u_assert (
  .clk_i, .rst_ni, .ph_i(ph_q), .in_ready_i(in_ready_o), .in_valid_i,
  .in_id_i, .v_i(v_q),
  .out_valid_i(out_valid_o), .out_id_i(out_id_o), .id_stage_i(id_s),
  .out_id_reg_i(out_id_q),
  .idle_i, .root_code_i(cfg_i.root_code), .bits16_i(cfg_i.bits16), .clip_i(cfg_i.policy.clip),
  .t0_i(t0_q));
`endif
