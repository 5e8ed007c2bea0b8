// SPDX-License-Identifier: Apache-2.0
// slot_set_abs (formal model only; formal/dm_pipeline_slots.sby): a unit of dm_pipeline that
// carries slot ids, abstracted to what the slot-id composition relies on.  It takes a slot when
// in_valid_i (always: the unit has room for every slot, SLOTS of them) and gives each slot it
// holds back once, after a delay of one clock or more that a free choice sets, in any order
// (held_o: the slots inside).  With HOLD = 0 the slot leaves in the clock it is shown (a
// fixed-latency unit that never stalls: view_calc, the back end from a hit's admission to
// shade_unit's output); with HOLD = 1 a slot shown stays shown until out_ready_i takes it (a
// result stream: traverse_rings' result, held until taken).  What the real units' own proofs
// give (view_calc's tag pipeline, traverse_rings' dealing and return, the traverse ring's ids,
// the texture cache's tags, the colour / normal-map pairing: docs/formal.md) is that every id
// taken comes back exactly once; any order and any delay cover theirs.
//   abs_enter_free  a slot enters only when not inside (the user's obligation, proven by the
//                   composition: the set would merge a duplicate);
//   abs_shown_held  with HOLD, the slot shown is inside (the induction invariant).
`ifdef FORMAL
module slot_set_abs #(
  parameter int unsigned SLOTS = 4,     // slot ids 0 .. SLOTS-1 (a power of two)
  parameter bit          HOLD  = 1'b0   // 1: a slot shown is held until out_ready_i
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     in_valid_i,   // a slot enters
  input  logic [$clog2(SLOTS)-1:0] in_slot_i,
  output logic                     out_valid_o,  // a slot is shown (HOLD 0: and leaves)
  input  logic                     out_ready_i,  // HOLD 1: the slot shown leaves
  output logic [$clog2(SLOTS)-1:0] out_slot_o,
  output logic [SLOTS-1:0]         held_o        // the slots inside
);

  localparam int unsigned SW = $clog2(SLOTS);

  // Free choices: undriven nets, which SymbiYosys makes free inputs every clock (nets, not
  // variables: read_slang gives an undriven variable the constant x).
  wire          show_en;   // a slot is shown
  wire [SW-1:0] pick;      // which one

  logic [SLOTS-1:0] held_q;
  logic             leave;
  logic [SW-1:0]    leave_slot;

  if (HOLD) begin : g_hold
    logic          o_v_q;   // slot o_s_q is shown
    logic [SW-1:0] o_s_q;
    assign out_valid_o = o_v_q;
    assign out_slot_o  = o_s_q;
    assign leave       = o_v_q && out_ready_i;
    assign leave_slot  = o_s_q;
    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        o_v_q <= 1'b0;
        o_s_q <= '0;
      end else if (!o_v_q || leave) begin
        o_v_q <= show_en && held_q[pick] && !(leave && pick == o_s_q);
        o_s_q <= pick;
      end
    end
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        abs_shown_held: assert (!o_v_q || held_q[o_s_q]);
      end
    end
  end else begin : g_now
    assign out_valid_o = show_en && held_q[pick];
    assign out_slot_o  = pick;
    assign leave       = out_valid_o;
    assign leave_slot  = pick;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      held_q <= '0;
    end else begin
      if (leave)      held_q[leave_slot] <= 1'b0;
      if (in_valid_i) held_q[in_slot_i]  <= 1'b1;
    end
  end
  assign held_o = held_q;

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      abs_enter_free: assert (!in_valid_i || !held_q[in_slot_i]);
    end
  end

endmodule
`endif
