// SPDX-License-Identifier: Apache-2.0
// traverse_level_decide: the level decisions of the second mode, purely combinational: the
// functions traverse_pkg::level_cross and level_descend as a module (their unit test's form;
// traverse_loop calls the functions' parts where it registers their results, so that a simulator
// evaluates them only for the passes that use them).  Two independent decisions, each in two
// stages of traverse_loop (traverse_pkg: cross_pre in S10, cross_up in S11; the clip of the two
// positions in S10, multi_level and descend_pick in S11); level_cross and level_descend compose
// the parts, so this module's test covers them:
//
// Crossing (stages S10 - S11), mirrors model/traverse.py::crossing_step (the "Node crossing"
// block of _trace): the neighbour n = c + (s where this axis's exit time is the node's exit time,
// else 0), then the level-up policy:
//   parent_changed = (nx >> 1 != cx >> 1) | (ny >> 1 != cy >> 1)
//   up = none: 0 | tevs: parent_changed | drobot: 1 | coherent: parent_changed & prev_cross
//      | selective: parent_changed & (max(|(p1x >> k) - cx|, |(p1y >> k) - cy|) != 1)
//   up &= k < n;  new level k + up;  new cell up ? n >> 1 : n
// (p1 = floor of the position where the ray meets the node's plane, level 0).
//
// Descent (stages S10 - S11), mirrors model/traverse.py::descent_level (the "Descent" block of
// _trace):
//   one: k - 1
//   multi (b): k - (crossed ? 1 : min(levels, k))
//   xor: min(bitlen(max(ax ^ bx, ay ^ by)), multi's level), with a = floor(position at t_new) and
//        b = floor(position at min(t_exit, t_map, 1)), both clipped to the node's level-0 cells
//        [c << k, ((c + 1) << k) - 1]
// never below 0 (a ray at level 0 does not descend; its result is 0 and unused).
module traverse_level_decide
  import traverse_pkg::*;
(
  // ---- crossing (S10 - S11) ----
  input  level_up_e               level_up_i,     // level-up policy (cfg policy.level_up)
  input  logic [LVL_W-1:0]        n_i,            // root level: no level-up above it
  input  logic [LVL_W-1:0]        xk_i,           // level of the node the ray leaves
  input  logic [CELL_W-1:0]       xcx_i,          // its cell at level k
  input  logic [CELL_W-1:0]       xcy_i,
  input  logic                    eqx_i,          // tx == t_exit: the ray leaves through u
  input  logic                    eqy_i,          // ty == t_exit: ... through v (both: a corner)
  input  dir_t                    sx_i,           // direction of motion along u
  input  dir_t                    sy_i,           // ... along v
  input  logic                    prev_cross_i,   // last iteration crossed without level-up
  input  logic signed [IDX_W-1:0] p1x_i,          // floor(u at the node's plane) (selective)
  input  logic signed [IDX_W-1:0] p1y_i,          // floor(v at the node's plane)
  output logic [LVL_W-1:0]        xk_o,           // new level
  output logic [CELL_W-1:0]       xcx_o,          // new cell at the new level
  output logic [CELL_W-1:0]       xcy_o,
  output logic                    up_o,           // the crossing went up a level
  // ---- descent (S10 - S11) ----
  input  descent_e                descent_i,      // descent policy (cfg policy.descent)
  input  logic [1:0]              levels_i,       // (b) levels per descent until the first crossing
  input  logic [LVL_W-1:0]        dk_i,           // level of the node the ray descends from
  input  logic [CELL_W-1:0]       dcx_i,          // its cell at level k
  input  logic [CELL_W-1:0]       dcy_i,
  input  logic                    crossed_i,      // the ray has crossed a node before
  input  logic signed [IDX_W-1:0] ax_i,           // floor(u at t_new) (xor)
  input  logic signed [IDX_W-1:0] ay_i,           // floor(v at t_new)
  input  logic signed [IDX_W-1:0] bx_i,           // floor(u at min(t_exit, t_map, 1)) (xor)
  input  logic signed [IDX_W-1:0] by_i,           // floor(v at min(t_exit, t_map, 1))
  output logic [LVL_W-1:0]        dk_o            // new level
);

  // The logic is traverse_pkg::level_cross and level_descend (traverse_loop calls them where it
  // registers their results); this module is their combinational form.
  cross_node_t x;
  assign x     = level_cross(level_up_i, n_i, xk_i, xcx_i, xcy_i, eqx_i, eqy_i, sx_i, sy_i,
                             prev_cross_i, p1x_i, p1y_i);
  assign xk_o  = x.k;
  assign xcx_o = x.cx;
  assign xcy_o = x.cy;
  assign up_o  = x.up;
  assign dk_o  = level_descend(descent_i, levels_i, dk_i, dcx_i, dcy_i, crossed_i, ax_i, ay_i,
                               bx_i, by_i);

endmodule
