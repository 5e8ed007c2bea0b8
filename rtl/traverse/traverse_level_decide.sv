// traverse_level_decide: the level decisions of the second mode, purely combinational.  Two
// independent parts, fed by two stages of traverse_loop:
//
// Crossing (stage S10), mirrors model/traverse.py::crossing_step (the "Node crossing" block of
// _trace): the neighbour n = c + (s where this axis's exit time is the node's exit time, else 0),
// then the level-up policy:
//   parent_changed = (nx >> 1 != cx >> 1) | (ny >> 1 != cy >> 1)
//   up = none: 0 | tevs: parent_changed | drobot: 1 | coherent: parent_changed & prev_cross
//      | selective: parent_changed & (max(|(p1x >> k) - cx|, |(p1y >> k) - cy|) != 1)
//   up &= k < n;  new level k + up;  new cell up ? n >> 1 : n
// (p1 = floor of the position where the ray meets the node's plane, level 0).
//
// Descent (stage S11), mirrors model/traverse.py::descent_level (the "Descent" block of _trace):
//   one: k - 1
//   multi (b): k - (crossed ? 1 : min(levels, k))
//   xor: min(bitlen(max(ax ^ bx, ay ^ by)), multi's level), with a = floor(position at t_new) and
//        b = floor(position at min(t_exit, t_map, 1)), both clipped to the node's level-0 cells
//        [c << k, ((c + 1) << k) - 1]
// never below 0 (a ray at level 0 does not descend; its result is 0 and unused).
module traverse_level_decide
  import traverse_pkg::*;
(
  // ---- crossing (S10) ----
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
  // ---- descent (S11) ----
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

  // Plain data flow, one expression per signal.

  // ---- crossing ------------------------------------------------------------------------------
  sidx_t cx, cy, nx, ny, p1x, p1y, dfx, dfy;
  logic  parent_changed, selective_stay, up;
  assign cx  = sidx_t'(xcx_i);
  assign cy  = sidx_t'(xcy_i);
  assign nx  = cx + (eqx_i ? dir_val(sx_i) : '0);
  assign ny  = cy + (eqy_i ? dir_val(sy_i) : '0);
  assign parent_changed = ((nx >>> 1) != (cx >>> 1)) || ((ny >>> 1) != (cy >>> 1));
  // selective: P1 (where the ray meets this node's plane), in cells of level k; the ray stays
  // when P1 is in the very next node: max(|p1x - cx|, |p1y - cy|) == 1
  assign p1x = sidx_t'(p1x_i) >>> xk_i;
  assign p1y = sidx_t'(p1y_i) >>> xk_i;
  assign dfx = (p1x >= cx) ? p1x - cx : cx - p1x;
  assign dfy = (p1y >= cy) ? p1y - cy : cy - p1y;
  assign selective_stay = (((dfx > dfy) ? dfx : dfy) == sidx_t'(1));
  assign up  = (xk_i < n_i)
            && ((level_up_i == UP_TEVS)      ? parent_changed
              : (level_up_i == UP_DROBOT)    ? 1'b1
              : (level_up_i == UP_SELECTIVE) ? parent_changed && !selective_stay
              : (level_up_i == UP_COHERENT)  ? parent_changed && prev_cross_i
              :                                1'b0);
  assign up_o  = up;
  assign xk_o  = xk_i + LVL_W'(up);
  assign xcx_o = CELL_W'(up ? (nx >>> 1) : nx);
  assign xcy_o = CELL_W'(up ? (ny >>> 1) : ny);

  // ---- descent -------------------------------------------------------------------------------
  sidx_t       lox, hix, loy, hiy, ax, bx, ay, by;
  logic [4:0]  step, nk_multi, bl;
  assign lox  = sidx_t'(dcx_i) <<< dk_i;
  assign hix  = ((sidx_t'(dcx_i) + sidx_t'(1)) <<< dk_i) - sidx_t'(1);
  assign loy  = sidx_t'(dcy_i) <<< dk_i;
  assign hiy  = ((sidx_t'(dcy_i) + sidx_t'(1)) <<< dk_i) - sidx_t'(1);
  assign ax   = clip_idx(sidx_t'(ax_i), lox, hix);
  assign bx   = clip_idx(sidx_t'(bx_i), lox, hix);
  assign ay   = clip_idx(sidx_t'(ay_i), loy, hiy);
  assign by   = clip_idx(sidx_t'(by_i), loy, hiy);
  // bitlen(max(a, b)) = bitlen(a | b): the lowest node holding both ends
  assign bl   = bitlen16(16'(ax ^ bx) | 16'(ay ^ by));
  // (b): `levels` levels per descent until the first crossing, then one (never below 0)
  assign step = crossed_i ? 5'd1 : (dk_i < 4'(levels_i)) ? 5'(dk_i) : 5'(levels_i);
  assign nk_multi = 5'(dk_i) - step;   // k >= 1 for a descending ray
  // not a descending ray (k = 0): 0, to keep the level in range
  assign dk_o = (dk_i == '0)             ? '0
              : (descent_i == DESC_MULTI) ? LVL_W'(nk_multi)
              : (descent_i == DESC_XOR)   ? LVL_W'((bl < nk_multi) ? bl : nk_multi)
              :                             dk_i - LVL_W'(1);

endmodule
