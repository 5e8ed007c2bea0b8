// SPDX-License-Identifier: Apache-2.0
// traverse_pkg: types, method decoding and float comparisons of the traverse unit.
//
// The traverse unit computes exactly model/traverse.py::_trace with the f24 engine (hit, t, u, v,
// invalid, iterations, bit for bit).  This package holds what its two modes share:
//   - the method codes (index in model.traverse.EXACT_METHODS) and their decoding into the policy
//     bits of model.traverse.Method (start level, descent, level-up, clip);
//   - the ray record setup hands to the loop (per-ray constants of the first mode and the initial
//     traversal state of the second) and the result record;
//   - comparisons, min and max of f24 words with the model's (numpy float64) semantics.
package traverse_pkg;

  import f24_pkg::*;

  // A package's constants serve several modules; not every module uses all of them.
  /* verilator lint_off UNUSEDPARAM */
  localparam int unsigned IDX_W      = 20;  // f24_to_index width: model.arith.INDEX_W
  localparam int unsigned LVL_W      = 4;   // pyramid levels 0 .. 15
  localparam int unsigned MAX_LEVELS = 16;  // level offsets held by the configuration
  localparam int unsigned CELL_W     = 16;  // a cell index at any level: 0 .. 2^15 - 1
  localparam int unsigned DIM_W      = 16;  // map width / height (at most 2^15)
  localparam int unsigned ITER_W     = 16;  // iteration counter and cap
  localparam int unsigned ADDR_W     = 32;  // byte address of a height lookup
  localparam int unsigned CODE_W     = 16;  // a height code (unorm8 in the low byte, or unorm16)
  localparam int unsigned LOOKUP_LAT = 3;   // clocks from lk_valid_o to rs_valid_i
  // Stages of traverse_loop's ring (one ray slot each): one pass = one iteration = LOOP_DEPTH
  // clocks.  17 + 3 * MUL_LAT: three f24_mul on the pass's dependent chain (tx, du * t, the
  // child's crossing times; traverse_loop's header), each MUL_LAT stages; 23 at the package
  // default pipe_pkg::F24_MUL_LAT = 2, 20 at the paper's MUL_LAT 1.  (Its f24_add run at a fixed 3 clocks.)
  localparam int unsigned LOOP_DEPTH = 17 + 3 * pipe_pkg::F24_MUL_LAT;  // loop_depth(F24_MUL_LAT)
  // traverse_loop's busy_o: the rays in its ring and its park queue, loop_depth(MUL_LAT) +
  // PARK_DEPTH <= 2^LOOP_BUSY_W - 1.
  localparam int unsigned LOOP_BUSY_W = 6;
  // traverse_loop's default park queue entries (PARK_DEPTH)
  localparam int unsigned PARK_DEPTH_DEF = 16;
  // traverse_setup's schedule at f24_add LAT add_lat and f24_mul LAT mul_lat (its ADD_LAT /
  // MUL_LAT; its header has the stage table).  setup_gap: the item stages from a shared unit's
  // first operation to its second, add_lat + mul_lat + 3 rounded up to 2 mod 4 (the second
  // operations take the other two clocks of the four): 6 at (2, 1), 10 at (3, 2).  setup_lat:
  // the stages in all (SETUP_LAT at the package defaults).
  function automatic int unsigned setup_gap(int unsigned add_lat, int unsigned mul_lat);
    return add_lat + mul_lat + 3 + (6 - (add_lat + mul_lat + 3) % 4) % 4;
  endfunction
  function automatic int unsigned setup_lat(int unsigned add_lat, int unsigned mul_lat);
    return F24_DIV_LAT + mul_lat + 6 + setup_gap(add_lat, mul_lat);
  endfunction
  // traverse_setup: the reciprocals (f24_div, F24_DIV_LAT clocks), then the rest of the first
  // mode (its header); busy_o counts the rays in it.  SETUP_LAT: setup_lat (above) at
  // pipe_pkg's F24_ADD_LAT / F24_MUL_LAT: F24_DIV_LAT + 13 = 21 at (2, 1), 26 at (3, 2).
  localparam int unsigned SETUP_LAT    = setup_lat(pipe_pkg::F24_ADD_LAT,
                                                   pipe_pkg::F24_MUL_LAT);  // 26
  localparam int unsigned SETUP_BUSY_W = $clog2(SETUP_LAT + 1);

  localparam f24_t F24_POS_ZERO = 24'h000000;
  localparam f24_t F24_SIGN     = 24'h800000;
  /* verilator lint_on UNUSEDPARAM */

  // traverse_loop's ring length for an f24_mul latency of mul_lat clocks (LOOP_DEPTH above is its
  // value at pipe_pkg::F24_MUL_LAT, written out so that tb/harness/sv_params.py can read it).
  function automatic int unsigned loop_depth(input int unsigned mul_lat);
    return 17 + 3 * mul_lat;
  endfunction

  // ---- methods (model.traverse.METHOD_CODES) ------------------------------------------------
  typedef enum logic [3:0] {
    M_OH          = 4'd0,
    M_TEVS        = 4'd1,
    M_DROBOT      = 4'd2,
    M_START_LEVEL = 4'd3,
    M_MULTI_DOWN  = 4'd4,
    M_SELECTIVE   = 4'd5,
    M_COHERENT    = 4'd6,
    M_PARK        = 4'd7,
    M_PARK_GPU    = 4'd8,
    M_PARK_XOR    = 4'd9
  } method_e;

  typedef enum logic [1:0] {
    DESC_ONE   = 2'd0,  // one level per descent
    DESC_MULTI = 2'd1,  // (b) `levels` levels per descent until the first crossing, then one
    DESC_XOR   = 2'd2   // as multi, or lower: the lowest node holding the rest of the ray (XOR)
  } descent_e;

  typedef enum logic [2:0] {
    UP_NONE      = 3'd0,
    UP_TEVS      = 3'd1,  // level up when the parent changes
    UP_DROBOT    = 3'd2,  // level up on every crossing
    UP_SELECTIVE = 3'd3,  // (c1) tevs, but stay when the plane is met in the very next node
    UP_COHERENT  = 3'd4   // (c2) tevs, only after two consecutive crossings at one level
  } level_up_e;

  typedef struct packed {
    logic      start_level;  // (a) start level by XOR / leading zeros
    descent_e  descent;
    logic [1:0] levels;      // (b) levels per descent until the first crossing (multi, xor)
    level_up_e level_up;
    logic      clip;         // start at the root's plane 1 - H_root
  } policy_t;

  // model.traverse.METHODS, field by field (tb/harness/traverse_words.py holds the same table, and the
  // traverse_unit test checks it against the model).  Codes above 9 decode as oh.
  function automatic policy_t decode_method(input logic [3:0] code);
    policy_t p;
    p = '{start_level: 1'b0, descent: DESC_ONE, levels: 2'd2, level_up: UP_NONE, clip: 1'b0};
    case (code)
      M_TEVS:        p.level_up = UP_TEVS;
      M_DROBOT:      p.level_up = UP_DROBOT;
      M_START_LEVEL: p.start_level = 1'b1;
      M_MULTI_DOWN:  p.descent = DESC_MULTI;
      M_SELECTIVE:   p.level_up = UP_SELECTIVE;
      M_COHERENT:    p.level_up = UP_COHERENT;
      M_PARK:        p = '{start_level: 1'b1, descent: DESC_MULTI, levels: 2'd2,
                           level_up: UP_SELECTIVE, clip: 1'b0};
      M_PARK_GPU:    p = '{start_level: 1'b1, descent: DESC_MULTI, levels: 2'd2,
                           level_up: UP_COHERENT, clip: 1'b0};
      M_PARK_XOR:    p = '{start_level: 1'b1, descent: DESC_XOR, levels: 2'd3,
                           level_up: UP_SELECTIVE, clip: 1'b1};
      default:       ;
    endcase
    return p;
  endfunction

  // ---- configuration (static while rays are in the unit) -------------------------------------
  typedef struct packed {
    policy_t                             policy;
    logic [DIM_W-1:0]                    width;      // map width W (level-0 texels)
    logic [DIM_W-1:0]                    height;     // map height H
    logic [LVL_W-1:0]                    n;          // root level: N = 2^n >= max(W, H)
    logic                                bits16;     // 1: unorm16 heights (2 bytes), 0: unorm8
    logic [ADDR_W-1:0]                   base;       // byte address of level 0
    logic [CODE_W-1:0]                   root_code;  // the root texel's code (clip start)
    logic [ITER_W-1:0]                   iter_cap;   // model.traverse.iteration_cap(pyr)
  } cfg_t;

  // ---- the ray record ------------------------------------------------------------------------
  // Direction of motion along one axis: sx of the model (+1, -1, or 0 = no crossing on this axis).
  typedef struct packed {
    logic mv;   // the axis moves (du != 0 and 1/du finite)
    logic neg;  // ... towards -u (only meaningful when mv)
  } dir_t;

  // One ray as setup hands it to the loop: what setup computes once, and the initial state of the
  // iterative search (traverse_loop keeps the fields in its slot table; there, once the ray is
  // done with a hit, t holds the hit time and u0 / v0 hold the hit position u / v).
  typedef struct packed {
    // per-ray constants (first mode)
    f24_t u0, v0, du, dv;
    f24_t inv_du, inv_dv;              // 1 / du, 1 / dv
    dir_t sx, sy;
    f24_t t_map;                       // time of leaving the map's extent
    // traversal state (second mode)
    logic [LVL_W-1:0]  k;              // level
    logic [CELL_W-1:0] cx, cy;         // cell at level k
    f24_t              t;              // time the ray is at (hit time once done with a hit)
    logic              crossed;        // has crossed a node (multi-level descent stops)
    logic              prev_cross;     // the last iteration was a crossing without level-up
    logic [ITER_W-1:0] iters;          // height reads that returned data (iterations)
    // status
    logic done;                        // finished: waits for the result FIFO
    logic hit;
    logic invalid;                     // NaN / Inf field or start outside the map
    logic capped;                      // stopped by the iteration cap (no hit, no miss)
    logic err;                         // a height read returned an error
  } ray_t;

  // What leaves the unit for one ray (besides its id).  t, u, v are meaningful only with hit.
  typedef struct packed {
    f24_t              t, u, v;
    logic              hit, invalid, capped, err;
    logic [ITER_W-1:0] iters;
  } result_t;

  // ---- f24 comparisons with float semantics (NaN compares false, -0 == +0) -------------------
  // Bit-identical to f24_cmp: an order-preserving key with all zeros mapped to one key.  Every
  // helper is one flat expression (no if / else), which simulators evaluate as plain data flow;
  // a value compared several times is converted to its f24_ord_t once (f24_ord) and the ord_*
  // helpers compare those.  The functions below read only the fields / bits they need.
  /* verilator lint_off UNUSEDSIGNAL */
  function automatic logic f24_is_nan(input f24_t x);
    return x[22:0] > 23'h7f0000;     // exponent 127 with a nonzero fraction
  endfunction

  function automatic logic f24_is_zero(input f24_t x);
    return x[22:16] == 7'd0;
  endfunction

  function automatic logic f24_is_finite(input f24_t x);
    return x[22:16] != EXP_SPEC;
  endfunction

  // A value in integer-comparable form: positives above 2^23 (magnitude added), negatives below
  // it (magnitude inverted), every zero (exponent 0) exactly 2^23; NaN is flagged (its key is
  // never looked at).
  typedef struct packed {
    logic        nan;
    logic [23:0] key;
  } f24_ord_t;

  function automatic f24_ord_t f24_ord(input f24_t x);
    return '{nan: f24_is_nan(x),
             key: f24_is_zero(x) ? 24'h800000 : {!x[23], x[22:0] ^ {23{x[23]}}}};
  endfunction

  function automatic logic ord_lt(input f24_ord_t a, input f24_ord_t b);
    return !a.nan && !b.nan && (a.key < b.key);
  endfunction

  function automatic logic ord_le(input f24_ord_t a, input f24_ord_t b);
    return !a.nan && !b.nan && (a.key <= b.key);
  endfunction

  function automatic logic ord_eq(input f24_ord_t a, input f24_ord_t b);
    return !a.nan && !b.nan && (a.key == b.key);
  endfunction

  function automatic logic f24_lt(input f24_t a, input f24_t b);
    return ord_lt(f24_ord(a), f24_ord(b));
  endfunction

  function automatic logic f24_le(input f24_t a, input f24_t b);
    return ord_le(f24_ord(a), f24_ord(b));
  endfunction

  // numpy.minimum / numpy.maximum on float64 (what the model uses): a NaN operand gives NaN, and
  // equal operands (+0 and -0 in particular) give the second one.  These say whether the result
  // is the first operand.
  function automatic logic ord_min_first(input f24_ord_t a, input f24_ord_t b);
    return a.nan || ord_lt(a, b);
  endfunction

  function automatic logic ord_max_first(input f24_ord_t a, input f24_ord_t b);
    return a.nan || ord_lt(b, a);
  endfunction

  function automatic f24_t f24_min(input f24_t a, input f24_t b);
    return ord_min_first(f24_ord(a), f24_ord(b)) ? a : b;
  endfunction

  function automatic f24_t f24_max(input f24_t a, input f24_t b);
    return ord_max_first(f24_ord(a), f24_ord(b)) ? a : b;
  endfunction

  function automatic f24_t f24_neg(input f24_t a);
    return a ^ F24_SIGN;
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // ---- integer helpers -----------------------------------------------------------------------
  // Number of significant bits of a non-negative value (0 -> 0): "levels minus leading zeros",
  // from the log-depth leading-zero count of f24_pkg.
  function automatic logic [4:0] bitlen16(input logic [15:0] x);
    logic [4:0] lz;  // leading zeros of x (0 .. 15 when x != 0)
    lz = f24_clz32({x, 16'd0});
    return (x == 16'd0) ? 5'd0 : 5'd16 - lz;
  endfunction

  typedef logic signed [IDX_W+1:0] sidx_t;  // signed texel / cell arithmetic (22 bits)

  function automatic sidx_t clip_idx(input sidx_t x, input sidx_t lo, input sidx_t hi);
    return (x < lo) ? lo : (x > hi) ? hi : x;
  endfunction

  // s of the model as an integer: +1, -1 or 0 (all ones for -1).
  function automatic sidx_t dir_val(input dir_t s);
    return {{(IDX_W+1){s.mv && s.neg}}, s.mv};
  endfunction


  // ---- level decisions of the second mode (traverse_level_decide has the full description) ---
  // Each decision is split where traverse_loop registers it (one clock each): the crossing into
  // cross_pre (the neighbour, whether the parent changed, selective's "stay") and cross_up (the
  // policy), the descent into the clip of the two positions to the node (node_lo, node_hi,
  // clip_idx), multi_level and descend_pick.  level_cross and level_descend compose the parts
  // (traverse_level_decide, the parts' unit test).

  // Low-bit mask 2^k - 1, bit by bit (each bit a function of k only: no carry chain).
  function automatic sidx_t low_mask(input logic [LVL_W-1:0] k);
    sidx_t m;
    for (int i = 0; i < $bits(sidx_t); i++) m[i] = (i < int'(k));
    return m;
  endfunction

  // A node's level-0 cells [c << k, ((c + 1) << k) - 1] (c >= 0, so its low k bits are free).
  function automatic sidx_t node_lo(input logic [LVL_W-1:0] k, input logic [CELL_W-1:0] c);
    return sidx_t'(c) <<< k;
  endfunction

  function automatic sidx_t node_hi(input logic [LVL_W-1:0] k, input logic [CELL_W-1:0] c);
    return (sidx_t'(c) <<< k) | low_mask(k);
  endfunction

  // Crossing: the neighbour cell and the level-up policy; the new node and whether it went up.
  typedef struct packed {
    logic [LVL_W-1:0]  k;   // new level
    logic [CELL_W-1:0] cx;  // new cell at the new level
    logic [CELL_W-1:0] cy;
    logic              up;  // the crossing went up a level
  } cross_node_t;

  // The crossing's first part: the neighbour n, whether its parent differs, and selective's stay.
  typedef struct packed {
    logic [LVL_W-1:0] k;               // level of the node the ray leaves
    sidx_t            nx, ny;          // the neighbour at level k
    logic             parent_changed;  // (nx >> 1 != cx >> 1) | (ny >> 1 != cy >> 1)
    logic             stay;            // selective: P1 is in the very next node
  } cross_pre_t;

  function automatic cross_pre_t cross_pre(
      input logic [LVL_W-1:0] k, input logic [CELL_W-1:0] xcx, input logic [CELL_W-1:0] xcy,
      input logic eqx, input logic eqy, input dir_t sx, input dir_t sy,
      input logic signed [IDX_W-1:0] p1x_i, input logic signed [IDX_W-1:0] p1y_i);
    sidx_t cx, cy, nx, ny, p1x, p1y;
    logic  nearx, neary;
    cx  = sidx_t'(xcx);
    cy  = sidx_t'(xcy);
    nx  = cx + (eqx ? dir_val(sx) : '0);
    ny  = cy + (eqy ? dir_val(sy) : '0);
    // selective: P1 (where the ray meets this node's plane), in cells of level k; the ray stays
    // when P1 is in the very next node: max(|p1x - cx|, |p1y - cy|) == 1, i.e. both differences
    // in {-1, 0, 1} and not both 0 (equality tests, no subtraction in front of them)
    p1x   = sidx_t'(p1x_i) >>> k;
    p1y   = sidx_t'(p1y_i) >>> k;
    nearx = (p1x == cx) || (p1x == cx + sidx_t'(1)) || (p1x == cx - sidx_t'(1));
    neary = (p1y == cy) || (p1y == cy + sidx_t'(1)) || (p1y == cy - sidx_t'(1));
    return '{k: k, nx: nx, ny: ny,
             parent_changed: ((nx >>> 1) != (cx >>> 1)) || ((ny >>> 1) != (cy >>> 1)),
             stay: nearx && neary && !((p1x == cx) && (p1y == cy))};
  endfunction

  function automatic cross_node_t cross_up(input level_up_e level_up, input logic [LVL_W-1:0] n,
                                           input cross_pre_t x, input logic prev_cross);
    logic up;
    up  = (x.k < n)
       && ((level_up == UP_TEVS)      ? x.parent_changed
         : (level_up == UP_DROBOT)    ? 1'b1
         : (level_up == UP_SELECTIVE) ? x.parent_changed && !x.stay
         : (level_up == UP_COHERENT)  ? x.parent_changed && prev_cross
         :                              1'b0);
    return '{k: x.k + LVL_W'(up), cx: CELL_W'(up ? (x.nx >>> 1) : x.nx),
             cy: CELL_W'(up ? (x.ny >>> 1) : x.ny), up: up};
  endfunction

  function automatic cross_node_t level_cross(
      input level_up_e level_up, input logic [LVL_W-1:0] n, input logic [LVL_W-1:0] k,
      input logic [CELL_W-1:0] xcx, input logic [CELL_W-1:0] xcy, input logic eqx,
      input logic eqy, input dir_t sx, input dir_t sy, input logic prev_cross,
      input logic signed [IDX_W-1:0] p1x_i, input logic signed [IDX_W-1:0] p1y_i);
    return cross_up(level_up, n, cross_pre(k, xcx, xcy, eqx, eqy, sx, sy, p1x_i, p1y_i),
                    prev_cross);
  endfunction

  // Descent, multi (b): `levels` levels per descent until the first crossing, then one (never
  // below 0); k >= 1 for a descending ray.
  function automatic logic [4:0] multi_level(input logic [1:0] levels, input logic [LVL_W-1:0] k,
                                             input logic crossed);
    logic [4:0] step;
    step = crossed ? 5'd1 : (k < 4'(levels)) ? 5'(k) : 5'(levels);
    return 5'(k) - step;
  endfunction

  // Descent: the new level from multi's level and the two positions clipped to the node.
  function automatic logic [LVL_W-1:0] descend_pick(
      input descent_e descent, input logic [LVL_W-1:0] k, input logic [4:0] nk_multi,
      input sidx_t ax, input sidx_t bx, input sidx_t ay, input sidx_t by);
    logic [4:0] bl;
    // bitlen(max(a, b)) = bitlen(a | b): the lowest node holding both ends
    bl = bitlen16(16'(ax ^ bx) | 16'(ay ^ by));
    // not a descending ray (k = 0): 0, to keep the level in range
    return (k == '0)                ? '0
         : (descent == DESC_MULTI) ? LVL_W'(nk_multi)
         : (descent == DESC_XOR)   ? LVL_W'((bl < nk_multi) ? bl : nk_multi)
         :                           k - LVL_W'(1);
  endfunction

  function automatic logic [LVL_W-1:0] level_descend(
      input descent_e descent, input logic [1:0] levels, input logic [LVL_W-1:0] k,
      input logic [CELL_W-1:0] dcx, input logic [CELL_W-1:0] dcy, input logic crossed,
      input logic signed [IDX_W-1:0] ax_i, input logic signed [IDX_W-1:0] ay_i,
      input logic signed [IDX_W-1:0] bx_i, input logic signed [IDX_W-1:0] by_i);
    sidx_t lox, hix, loy, hiy;
    lox = node_lo(k, dcx);
    hix = node_hi(k, dcx);
    loy = node_lo(k, dcy);
    hiy = node_hi(k, dcy);
    return descend_pick(descent, k, multi_level(levels, k, crossed),
                        clip_idx(sidx_t'(ax_i), lox, hix), clip_idx(sidx_t'(bx_i), lox, hix),
                        clip_idx(sidx_t'(ay_i), loy, hiy), clip_idx(sidx_t'(by_i), loy, hiy));
  endfunction

endpackage
