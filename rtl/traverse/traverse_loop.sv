// SPDX-License-Identifier: Apache-2.0
// traverse_loop: the second mode of the traverse unit, the iterative search of model/traverse.py
// (the body of _trace's `while act.size` loop, for one ray per pass).
//
// A ring of D = traverse_pkg::loop_depth(MUL_LAT) = 17 + 3 * MUL_LAT stages (20 at MUL_LAT 1,
// 23 at MUL_LAT 2); every stage holds one ray slot and every slot advances one stage per clock
// (the loop never stalls).  One pass round the ring = one iteration = one height lookup.  At the
// ring's tail (S19) a finished ray leaves for the result FIFO; a slot that is then empty takes a
// new ray from setup (re-circulating rays have priority: new rays only fill bubbles).
//
// Float latencies: every f24_mul runs at MUL_LAT (a parameter, default pipe_pkg::F24_MUL_LAT;
// the same word at every LAT); the position adders at a fixed POS_ADD_LAT = 3 (not
// pipe_pkg::F24_ADD_LAT: the schedule is written for 3, checked by an $error); traverse_bdiff,
// f24_to_index, f24_from_unorm and f24_one_minus at their fixed latencies.  Three multipliers lie
// on the pass's dependent chain (tx, du * time, the child's crossing times), so each clock of
// MUL_LAT above 1 adds three stages.  Stage names: S0 .. S19 below, and the numbers in signal
// names (t6_q ... done19_q), are the stages at MUL_LAT 1; the code indexes stages by localparams
// computed from MUL_LAT (S_RS, S_EXIT, ... S_TL), which are, at MUL_LAT 1 / MUL_LAT 2:
//   S0 - S4  lookup; S_RS = 4: the response, tx's operands          0 - 4    / 0 - 4
//   S5       S_EXIT: tx, ty arrive; t_exit; the exit check; 1 - H (at MUL_LAT > 1 in S_EXIT - 1,
//            H held MUL_LAT - 2 clocks; the plane registered for S_TNEW)
//                                                                    5        / 6
//   S6, S7   S_TNEW, S_DEC (du * that time: its operands)            6, 7     / 7, 8
//   S8       S_POS: u0 + du * that time (f24_add, 3 clocks)          8        / 10
//   S11-S15  S_FLR, S_XPRE, S_XUP, S_CB, S_LOC                       11 - 15  / 13 - 17
//   S17      S_TEN: (entry boundary - u0) * (1/du), its operands
//            (1/du read in S_TEN - 2)                                17       / 19
//   S18      S_NS = S_TEN + MUL_LAT: the crossing times arrive; the next
//            state (its copies made in S_NS - 1); locate's entry check 18     / 21
//   S19      S_TL = S_NS + 1 = D - 1: the tail                       19       / 22
// At MUL_LAT 1 the ring is clock for clock the 20-stage ring.  A multiplier's clock enable is
// the OR of the activity of the MUL_LAT stages its operations occupy (its registers advance while
// any of them holds a pass that uses it).
//
// Ring registers: a ray's fields move with it, one register per field and stage (f_q[s] is the
// field of the ray in stage s; S19 hands on to S0).  A stage reads the fields it needs straight
// from its own stage's registers, and a stage that changes a field writes the next stage's
// register (f_q[s + 1] <= new value instead of f_q[s]).  Per ray:
//   - the per-ray constants u0, v0, directions, t_map and the ray id, loaded when the ray enters
//     the ring (u0, v0 become the hit's u, v when the ray hits: the result reads them);
//   - the traversal state (level, cell, t, flags, iterations), loaded on entry and by S18 (the
//     level and cell also by S19, a descent's node); the flags include the two exit-check bits
//     of a descent's estimate (below, "Locate's exit check");
//   - what one pass computes for a stage far later in the same pass (t_new, the action, the
//     crossing and the hit position): registers from the stage after the one that computes it
//     to the one that reads it only.
// du, dv, 1/du, 1/dv (96 bits, read in S2 - S4 and S15 only) stay in two tables of D =
// LOOP_DEPTH entries in block RAM, one per slot: the entry of the slot in stage s is (ph - s)
// mod D, with ph a phase that steps every clock (each stage counts its own index, sl_q[s]).  (The
// ring was a slot table for every field before: its D:1 read multiplexers and the write
// multiplexers of the state cost ~7,000 LUT4s, and the ring's registers cost no more flip-flops
// than the table's.)  Activity bits per stage move with the slots too: the slot holds a ray
// (v_q), a live ray (S1 - S4), the height read returned data (ok) or an error (S4 - S18), the pass
// hits or descends (S8 - S13), the pass descends (S8 - S18).
//
// Clock enables: a unit advances only while its stages hold a pass that uses its result, and
// holds its registers otherwise (less switching, and less work for a simulator).  Until the
// height arrives (S0 - S4) that is a live ray; from S4 on a pass whose height read returned data
// (ok): the position (at t_new or at the plane) too; its floor and the child's boundaries only
// for a descent, or for a crossing of the selective level-up (the floor at the plane, P1).  The
// position at t_end (and its floor) advance only for the XOR descent.
//
// Registered operands: a float unit takes its operands from registers (a unit's result, a ring
// register, or a copy made one clock earlier, name ending in the stage that uses it, _q), never
// through a table read or a comparison, min, max, clip, add or shift in the same clock: the
// units are only just fast enough for 100 MHz from registers.  Integer logic that feeds a unit
// has a stage of its own, and so does every comparison the next stage acts on.  For S0 the tail
// (S19) loads the ray that comes round: the node S18 wrote, the descent's node (corrected in S18
// into a register of S19, so that the crossing times' comparisons, right behind two
// multipliers, do not share a clock with the entry multiplexers of S0), or the new ray from
// setup.
//
// Stage schedule (a unit "a -> b" takes operands in Sa and delivers in Sb):
//   S19  (previous pass) node, directions of the ray entering S0   -> node_q[0], dir_q[0]
//   S0   height address base + off[k] + (cy * side_k + cx) * bytes  -> lk_* registers (S1)
//        (traverse_addr); exit boundary integer (cx + (sx > 0)) << k -> S1
//   S1   lookup presented (lk_valid_o, lk_addr_o, lk_wide_o)
//        bx - u0 (fixed point, see below)                           traverse_bdiff S1 -> S4
//   S4   response {valid, hit, err, data} (LOOKUP_LAT = 3 after S1)
//        H = code / (2^bits - 1) (unorm8 as unorm16 code * 257)     f24_from_unorm S4 -> S5
//        tx = (bx - u0) * (1/du)                                    f24_mul      S4 -> S5
//        min(t_map, 1)
//   S5   plane = 1 - H (f24_add(1, -H), H in [0, 1])                f24_one_minus S5 -> S6
//        t_exit = min(tx, ty) (inf on an axis that does not move); t_end = min(t_exit,
//        min(t_map, 1)) (= min(min(t_exit, t_map), 1): min is associative, NaN and ties too);
//        locate's exit check (tx <= t, ty <= t with a check bit set): a redo
//   S6   t_new = max(t, plane); min(t_exit, t_map); whether t_new < min(t_exit, t_map) (the
//        pass hits or descends, S7's comparison on the same words): the time whose position
//        the pass uses, t_new for a hit or a descent, else the plane (selective's P1)
//   S7   inside / miss / hit / down / cross
//        du * (that time)                                           f24_mul      S7 -> S8
//        du * t_end                                                 f24_mul      S7 -> S8
//   S8   u0 + du * (that time) (f24_add at LAT 3)                   f24_add      S8 -> S11
//        u0 + du t_end                                              f24_add      S8 -> S11
//   S11  position at t_new (a hit's u) or at the plane (a crossing)
//        floor(position) (a descent, or selective's P1 for a crossing) f24_to_index S11 -> S12
//        floor(position at t_end)                                   f24_to_index S11 -> S12
//   S12  crossing's time; crossing, part 1: neighbour cell, parent, selective's stay
//        (traverse_pkg::cross_pre); descent: the two positions clipped to the node
//   S13  crossing, part 2: level-up policy (cross_up); descent: new level (one; multi: `levels`
//        until the first crossing; XOR of the ends) (descend_pick)
//   S14  the child's entry boundary integers (c + (s < 0)) << k' (c the child estimate
//        floor(p) >> k', p clipped to the node), straight into traverse_bdiff, whose first
//        stage only registers them: entry boundary - u0 (fixed point, see below)
//                                                                   traverse_bdiff S14 -> S17
//        child estimate c, the child's range at level k'
//   S15  one cell back (clipped); whether one cell on is in the child's range
//   S17  (entry boundary - u0) * (1/du)                             f24_mul      S17 -> S18
//        the state's copies for S18; a redo's node (one cell on)
//   S18  next state (hit / miss / down / cross / lookup miss / cap / redo); locate's entry
//        check (the descent's cell, from the entry crossing times)  -> ndn19_q
//   S19  retire to the result FIFO, park, or merge with a new ray, -> S0
// Positions on an axis that does not move are u0 itself (the model's np.where(s != 0, p, p0)).
// Boundary - u0 (the model's ar.sub(ar.from_int(b), p0) of a crossing time) is traverse_bdiff:
// u0 taken to 19 fraction bits (the last one sticky), subtracted from the integer boundary and
// rounded once, the same f24 word as f24_from_int and f24_add for every boundary in [0, 2^15]
// and u0 in [0, 2^15) (the ring's only operands: the checker flags others), in the same 3 clocks;
// the entry and exit boundaries of a descent share one unit's shift of u0.
// Float units per axis pair: 4 boundary differences (traverse_bdiff), 4 f24_add, 8 f24_mul, 4
// f24_to_index, 1 f24_from_unorm, 1 f24_one_minus; without XOR_PATH 2 f24_add, 6 f24_mul, 2
// f24_to_index (the position at t_end and its floor serve the XOR descent only: XOR_PATH = 0 leaves
// them out and runs the XOR descent, park-xor's, as the multi-level descent).  The plane's 1 - H is
// f24_one_minus, not an adder: the same word for every H in [0, 1] in one clock instead of two, so
// the cache's third clock of lookup latency (its block RAMs' read registers copied before the tag
// compare) costs the ring no stage.  Up to two positions per axis are computed in a pass: at t_end
// for the XOR descent, and one at the time the pass uses, t_new (locate, the hit) or the plane
// (selective's P1 for a crossing; a pass needs never both).  Picking that time first (S6) costs the
// ring a stage: 20 deep (the paper's is 15), because the descent's locate (time, position, floor,
// clip, level, boundaries, two crossing times, entry check) follows the plane's arrival as a
// dependent chain of 13 clocks (S6 - S19, at MUL_LAT 1; 16 at MUL_LAT 2), the correction's
// comparisons in a stage of their own.  The position adders
// run at three clocks (their two-clock first stage, alignment shift and carry chain together,
// was the ring's slowest path) in the same ring: the boundary integers, which had a register of
// their own before traverse_bdiff's first stage (a register of the same integers, shifted by
// wiring), now go straight into that stage.  (Computing the positions at t and at the plane both,
// and picking one in parallel, took a ring of 18 and two f24_mul, two f24_add more per axis pair.)
//
// Lookup misses: the ray keeps its state and goes round again; the iteration is not counted
// (iterations = height reads that returned data, a redo's excepted: below).  A read error
// finishes the ray with err = 1.
//
// Locate's exit check: locate (model/traverse.py) corrects a descent's estimate by one cell with
// the crossing times of its two edges: one back when t is before its entry, one on when t is at
// or after its exit.  The entry check is made in the descent (S18).  The exit check is left to
// the next pass, whose tx, ty are the estimate's exit crossing times (the same boundary, u0 and
// 1/du, so the same words): the descent sets a check bit per axis where the entry check left the
// estimate and one cell on lies in the child's range (chkx, chky).  With a check bit set and
// t >= tx (ty), the pass is a redo: the height it read is neither used nor counted (ok and err
// are cleared from S_TNEW on, as for a lookup miss), the node moves one cell on along the axes
// whose check failed (made in S17, written by S18 like a crossing's node), and the check bits
// clear.  The next pass is the model's iteration on the corrected cell, at the same t.  A pass
// that finds the estimate right clears the bits as it makes its iteration; a lookup miss keeps
// them (the check is made again).  The check costs no multiplier (the descent's exit crossing
// times took two per axis pair, and a boundary difference each); a redo costs the ray one pass
// and one height read more, which the model counts as "relocate" (lookups = iterations +
// relocations when no lookup misses).  Redos are rare: the estimate is one cell short only where
// the rounded position at t lies a few ulp short of the cell's exit edge (0.02 - 0.05% of the
// descents on make render's frames).
// Back-pressure: a finished ray leaves only when the result FIFO has room; otherwise it keeps
// circulating (no lookups, state untouched) and tries again one pass later.
//
// Parking (PARK): with incoherent rays most lookups miss, and a missed ray would hold its slot
// for a whole pass for nothing while new rays wait in the setup FIFO.  At the tail a ray whose
// lookup missed (state unchanged) may instead leave the ring for the park queue, a FIFO of
// PARK_DEPTH entries in LUT RAM holding all it resumes with: id, u0, v0, directions, t_map, the
// traversal state (node, t, status, iterations), du, dv, 1/du, 1/dv (read from the tables in S18
// into their own read registers) and the clock it parked.  Its slot then takes a new ray at once.
// It parks only when a ray takes its slot in the same clock (a new ray, or the queue's head) and
// the queue has room (or its head leaves in that clock); otherwise it circulates as without
// parking.  The queue's head takes a free slot at the tail, before any new ray, once it has been
// parked PARK_WAIT clocks (its line has had time to arrive; the parked ray looks it up again in
// S1 after re-entering), or at once when no new ray waits.  The bound on waiting: once the head
// has waited PARK_MAX clocks it takes the slot of whatever ray reaches the tail that is not done,
// and that ray parks in its place (any pass: the tail holds a ray's complete state, with the
// descent's node corrected in S18); only a finished ray that the result FIFO has no room for
// delays it.  Entering from the queue writes the ray's table entries like a new ray's.  Results
// never depend on when a ray runs (a lookup that misses changes nothing), so they are the same
// word for word with and without parking; only the clock counts differ.  busy_o counts the rays
// in the ring and the queue.
module traverse_loop
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W     = 8,
  // f24_mul latency (1 .. 3; f24_mul's LAT, the same word at every LAT): the ring is
  // loop_depth(MUL_LAT) = 17 + 3 * MUL_LAT stages (header, "Stage schedule").  The f24_add (the
  // positions) run at a fixed POS_ADD_LAT = 3 whatever pipe_pkg::F24_ADD_LAT is.
  parameter int unsigned MUL_LAT  = pipe_pkg::F24_MUL_LAT,
  // 1: every method.  0: no XOR descent: the positions at t_end and their floors (2 f24_mul,
  // 2 f24_add, 2 f24_to_index) are left out, and a configuration with the XOR descent (park-xor)
  // descends as the multi-level descent instead (DESC_XOR runs as DESC_MULTI with the same
  // `levels`: park-xor becomes start level, multi-level descent of 3 levels, selective level-up,
  // clip; bit-exact with the model's method of those fields, not with park-xor).
  parameter bit          XOR_PATH = 1'b1,
  // Parking (header: "Parking"): 1: a ray whose lookup missed may leave the ring for the park
  // queue, its slot free for another ray.  0: no park queue (the ring without parking, clock for
  // clock; no park register, no queue, no extra table read port).  Off by default: the park
  // decision costs the ring about 10 MHz out of context (docs/traverse.md, "Parking").
  parameter bit          PARK       = 1'b0,
  // park queue entries (LUT RAM); loop_depth(MUL_LAT) + PARK_DEPTH < 2^LOOP_BUSY_W (busy_o
  // counts ring and queue)
  parameter int unsigned PARK_DEPTH = PARK_DEPTH_DEF,
  // clocks a parked ray waits (for its line to arrive) before it takes a free slot ahead of new
  // rays (with no new ray waiting it takes one at once)
  parameter int unsigned PARK_WAIT  = 16,
  // clocks the park queue's head waits before it takes the slot of any ray at the tail that is
  // not done (that ray is parked in its place): the bound on waiting
  parameter int unsigned PARK_MAX   = 4 * loop_depth(MUL_LAT)
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  /* verilator lint_off UNUSEDSIGNAL */  // the second mode reads only part of the configuration
  input  cfg_t              cfg_i,
  /* verilator lint_on UNUSEDSIGNAL */
  // the level-offset table (traverse_addr, LUT RAM; not reset, static while busy)
  input  logic              hlt_we_i,
  input  logic [LVL_W-1:0]  hlt_waddr_i,
  input  logic [ADDR_W-1:0] hlt_wdata_i,
  // new rays from setup (head of the setup FIFO, first-word fall-through)
  input  logic              new_valid_i,
  input  logic [ID_W-1:0]   new_id_i,
  input  ray_t              new_ray_i,
  output logic              new_pop_o,
  // finished rays to the result FIFO
  input  logic              res_full_i,
  output logic              res_push_o,
  output logic [ID_W-1:0]   res_id_o,
  output result_t           res_o,
  // height lookups (master; the response comes LOOKUP_LAT clocks after the request)
  output logic              lk_valid_o,
  output logic [ADDR_W-1:0] lk_addr_o,
  output logic              lk_wide_o,
  input  logic              rs_valid_i,
  input  logic              rs_hit_i,
  input  logic              rs_err_i,
  input  logic [CODE_W-1:0] rs_data_i,
  // statistics strobes (one clock each) and occupancy
  output logic              st_iter_o,   // an iteration (a height read that returned data;
                                         // not a redo's)
  output logic              st_down_o,   // ... that descended
  output logic              st_cross_o,  // ... that crossed to a neighbour
  output logic              st_up_o,     // ... that crossed and went up a level
  output logic [LOOP_BUSY_W-1:0] busy_o  // rays in the ring and the park queue
);

  // The position adders (u0 + du t, S8): three clocks (f24_add's LAT 3, the same word), so that
  // no stage holds the adder's alignment shift and its carry chain together (at two clocks the
  // adder's first stage was the ring's slowest path); the schedule (header) is written for 3.
  localparam int unsigned POS_ADD_LAT = 3;
  if (POS_ADD_LAT != 3) begin : g_check_pos_lat
    $error("traverse_loop: the stage schedule is written for POS_ADD_LAT = 3");
  end
  if (MUL_LAT < 1 || MUL_LAT > 3) begin : g_check_mul_lat
    $error("traverse_loop: MUL_LAT must be in 1 .. 3 (f24_mul's LAT)");
  end
  localparam int unsigned BD_LAT = 3;  // traverse_bdiff: boundary - u0 in 3 clocks
  // The stage schedule (header): a stage's index at MUL_LAT; the value at MUL_LAT 1 is the name
  // the header and the signals use (S5 ... S19), the one at MUL_LAT 2 follows.  S0 - S4 do not
  // depend on it (the lookup's LOOKUP_LAT).
  localparam int unsigned S_RS   = 4;                      // 4  4: response; tx, ty operands
  localparam int unsigned S_EXIT = S_RS + MUL_LAT;         // 5  6: tx, ty; t_exit; 1 - H
  localparam int unsigned S_TNEW = S_EXIT + 1;             // 6  7: t_new, the time to position
  localparam int unsigned S_DEC  = S_EXIT + 2;             // 7  8: decisions; du * that time
  localparam int unsigned S_POS  = S_DEC + MUL_LAT;        // 8  10: u0 + du * that time
  localparam int unsigned S_FLR  = S_POS + POS_ADD_LAT;    // 11 13: floors
  localparam int unsigned S_XPRE = S_FLR + 1;              // 12 14: crossing part 1, clips
  localparam int unsigned S_XUP  = S_FLR + 2;              // 13 15: level-up; new level
  localparam int unsigned S_CB   = S_FLR + 3;              // 14 16: child's boundaries - u0
  localparam int unsigned S_LOC  = S_CB + 1;               // 15 17: locate's candidates
  localparam int unsigned S_TEN  = S_CB + BD_LAT;          // 17 19: (boundary - u0) * (1/du)
  localparam int unsigned S_NS   = S_TEN + MUL_LAT;        // 18 21: next state; locate's
                                                           //        correction (compared)
  localparam int unsigned S_TL   = S_NS + 1;               // 19 22: the tail
  localparam int unsigned D  = S_TL + 1;    // stages S0 .. S_TL: traverse_pkg::loop_depth(MUL_LAT)
  localparam int unsigned SW = $clog2(D);   // block RAM table index width
  if (D != loop_depth(MUL_LAT)) begin : g_check_depth
    $error("traverse_loop: %0d stages, traverse_pkg::loop_depth says %0d", D, loop_depth(MUL_LAT));
  end

  typedef logic [SW-1:0] slot_idx_t;

  // ---- ring fields (see the header) -----------------------------------------------------------
  typedef struct packed {
    f24_t u, v;                    // a value per axis
  } f24_pair_t;
  typedef struct packed {
    dir_t sx, sy;                  // directions of motion
  } dirs_t;
  typedef struct packed {
    logic [LVL_W-1:0]  k;          // level
    logic [CELL_W-1:0] cx, cy;     // cell at level k
  } node_t;
  typedef struct packed {
    logic              crossed;    // has crossed a node (multi-level descent stops)
    logic              prev_cross; // the last iteration was a crossing without level-up
    logic              done;       // finished: waits for the result FIFO
    logic              hit;
    logic              invalid;
    logic              capped;
    logic              err;
    logic              chkx, chky; // the node is a descent's estimate whose exit crossing time
                                   // on x / y is still to be compared with t (next pass, S_EXIT)
    logic [ITER_W-1:0] iters;      // height reads that returned data (not a redo's)
  } status_t;
  typedef struct packed {
    f24_t     t;                   // a time
    f24_ord_t ord;                 // ... in comparable form (times are compared several times)
  } tval_t;
  // Per pass.
  typedef struct packed {
    tval_t te;                     // t_exit = min(tx, ty)
    logic  eqx, eqy;               // tx == t_exit, ty == t_exit
  } exit_t;
  typedef struct packed {
    tval_t tmin;                   // min(t_exit, t_map)
    logic  miss_pre;               // t_map <= t_exit
  } tmin_t;
  typedef struct packed {
    logic is_hit, down, miss;      // (cross = none of them)
  } act_t;
  typedef struct packed {
    sidx_t x, y;
  } sidx_pair_t;
  typedef struct packed {
    logic [CELL_W-1:0] back;       // t before the estimate's entry: one cell back (clipped)
    logic [CELL_W-1:0] est;        // the estimate itself
    logic              fwd;        // one cell on lies in the child's range (the exit check can
                                   // move the estimate, on the next pass)
  } locate_t;
  typedef struct packed {
    logic [LVL_W-1:0] nk;          // the descent's new level
    locate_t          x, y;        // locate's candidates per axis
  } desc_t;

  // Per ray, round the whole ring: f_q[s] is the field of the ray in stage s.
  logic [ID_W-1:0]  id_q     [D];
  f24_pair_t        uv_q     [D];  // u0, v0; the hit's u, v once the ray has hit (from S19)
  dirs_t            dir_q    [D];
  f24_t             tmap_q   [D];  // time of leaving the map's extent
  node_t            node_q   [D];  // (S18 a crossing, S19 a descent, S19 a new ray)
  f24_t             t_q      [D];  // time the ray is at (hit time once done with a hit)
  status_t          stat_q   [D];
  // Per pass: [the stage that computes it, on the passes named] the stage that reads it; the
  // registers run from the stage after the first to the second.  "ok": the height read returned
  // data; "inside": the pass hits or descends.
  f24_t        t_new_q [S_NS:S_DEC];     // [S6 ok]              S18: max(t, plane)
  act_t        act_q   [S_NS-1:S_DEC+1]; // [S7 ok]              S16
  f24_pair_t   pos_q   [S_NS:S_XPRE];    // [S11 inside]          S18: position at t_new
  f24_t        xt_q    [S_NS:S_XUP];     // [S12 ok, not inside] S18: the crossing's time
                                         // max(t, t_exit)
  cross_node_t cross_q [S_NS:S_CB];      // [S13 ok, not inside] S18: the crossing's new node, up
  // Per ray, in block RAM: du, dv and 1/du, 1/dv, one entry per slot (see the header), written
  // when the ray enters the ring.  They are read only into registers, so synthesis can put them
  // in block RAM (ram_style; a 16x4 LUT RAM costs 6 LUT4s).  Their reads are made a stage early
  // into the block RAM's own read register (duv5_q, inv3_q, inv15_q) and then copied into a
  // fabric register next to the multipliers: the block RAM's 4.3 ns clock-to-out, routed into a
  // multiplier, was the ring's slowest path (69 MHz).
  (* ram_style = "block" *) f24_pair_t duv_q [D];  // du, dv
  (* ram_style = "block" *) f24_pair_t inv_q [D];  // 1 / du, 1 / dv

  // ---- ring position, pass activity (see the header) ----------------------------------------
  logic [D-1:0] v_q;               // v_q[s]: the slot in stage s holds a ray
  logic         ok4, err4;         // the height read of the ray in S4 returned data / an error
  logic [S_NS:5]       ok_q, err_q;  // ok4, err4 of the ray in stage s (meaningful with v_q[s])
  logic [S_XUP:S_DEC+1] in_q;  // in_q[s]: ok, and the pass hits or descends (inside its node)
  logic [S_NS:S_DEC+1]  dn_q;  // dn_q[s]: ok, and the pass descends
  logic [S_EXIT-1:1]   lv_q;   // lv_q[s]: the slot in stage s holds a live ray (not done)
  typedef struct packed {
    logic x, y;
  } rd_t;
  rd_t          rd5;               // S_EXIT: the exit check moves the node on x / y (a redo)
  rd_t          redo_q [S_NS:S_TNEW];  // ... of the ray in stage s (meaningful with v_q[s])
  logic         xor_desc, sel_up;  // the method uses the XOR descent / the selective level-up
  descent_e     desc;              // the descent policy run (DESC_XOR as DESC_MULTI without
                                   // XOR_PATH)
  slot_idx_t    sl_q [D];          // stage s holds the slot of entry sl_q[s] = (ph - s) mod D
                                   // of the block RAM tables, ph = sl_q[0] the phase

  // Each stage's slot index is a counter of its own rather than ph - s: its table reads then
  // start at a register placed near them, not behind a subtraction and a shared net (the phase's
  // fanout to every stage's subtraction was 70% of the ring's slowest path, 71 MHz).  The
  // counters are not merged by synthesis: each has its own reset value.  (Only the stages that
  // read or write the tables use theirs: synthesis removes the others.)
  for (genvar g = 0; g < D; g++) begin : g_sl
    always_ff @(posedge clk_i) begin
      if (!rst_ni) sl_q[g] <= SW'((D - g) % D);
      else         sl_q[g] <= (sl_q[g] == SW'(D - 1)) ? '0 : sl_q[g] + SW'(1);
    end
  end

  assign xor_desc = XOR_PATH && (cfg_i.policy.descent == DESC_XOR);
  assign desc     = xor_desc ? DESC_XOR
                  : (cfg_i.policy.descent == DESC_XOR) ? DESC_MULTI : cfg_i.policy.descent;
  assign sel_up   = (cfg_i.policy.level_up == UP_SELECTIVE);

  // ---- registered reads and short pipelines (see the header) ---------------------------------
  logic       live0_q;             // S0 holds a live ray: it looks its height up
  logic [LVL_W-1:0] nk0_q;         // S0: n - node_q[0].k (loaded with node_q[0], for the address)
  logic [IDX_W-1:0] kbx1_q, kby1_q;  // S1: exit boundary integers
  f24_pair_t  inv3_q, inv4_q;      // S3 (block RAM read register), S4
  dirs_t      d5_q;                // S5
  tval_t      tmap5_q;             // S5: t_map
  exit_t      ex_q [S_XPRE:S_TNEW];  // S6 - S12: t_exit (computed in S5)
  tval_t      tmap6_q;             // S6: t_map
  tval_t      t6_q;                // S6
  f24_pair_t  duv5_q, duv6_q, duv7_q;  // S5 (block RAM read register), S6, S7
  f24_t       tp7_q;               // S7: t_new for a hit or descent, else the plane (from S6)
  f24_ord_t   t_new7_q;            // S7: max(t, plane) (computed in S6), comparable
  tmin_t      tmin7_q;             // S7 (computed in S6)
  logic       leaf7_q;             // S7: the node is at level 0
  f24_pair_t  uv8_q;               // S8
  f24_pair_t  uv11_q;              // S11
  dirs_t      d11_q, d12_q, d13_q, d14_q, d15_q;  // S11 - S15
  node_t      n11_q, n12_q, n13_q, n14_q;         // S11 - S14
  sidx_pair_t lo12_q, hi12_q;      // S12: the node's level-0 cells (computed in S11)
  logic       crossed12_q, prev12_q, prev13_q;   // S12, S13: status bits
  tval_t      t12_q;               // S12
  cross_pre_t xpre13_q;            // S13: crossing, part 1 (computed in S12)
  sidx_pair_t a13_q, b13_q;        // S13: positions at t_new, t_end clipped to the node
  logic [4:0] nkm13_q;             // S13: multi's new level
  sidx_pair_t a14_q;               // S14
  logic [LVL_W-1:0] nk14_q, nk15_q;  // S14, S15: the descent's new level (computed in S13)
  logic [IDX_W-1:0] kben_x14, kben_y14;  // S14: the child's entry boundaries
  sidx_pair_t c15_q, lo15_q, hi15_q;  // S15: child estimate, the child's range at level k'
  desc_t      dsc_q [S_NS:S_LOC+1];  // S16 - S18: new level, locate's candidates (from S15)
  f24_pair_t  inv16_q, inv17_q;    // S16 (block RAM read register), S17
  status_t    st18_q;              // S18
  logic [ITER_W-1:0] it18_q;       // S18: iterations + 1
  act_t       act18_q;             // S18
  f24_ord_t   t_new18_q;           // S18: t_new, comparable
  logic       down19_q, done19_q;  // S19: the pass descended (not capped); the ray is done
  node_t      ndn19_q;             // S19: the descent's node, locate's entry check made (S18)
  node_t      rn18_q;              // S18: a redo's node, one cell on (computed in S17)

  // ---- S0: height address, exit boundary integers ----------------------------------------------
  logic [ADDR_W-1:0] addr0;
  logic              wide0;
  traverse_addr u_addr (
    .clk_i,
    .hlt_we_i,
    .hlt_waddr_i,
    .hlt_wdata_i,
    .base_i     (cfg_i.base),
    .bits16_i   (cfg_i.bits16),
    .k_i        (node_q[0].k),
    .nk_i       (nk0_q),
    .cx_i       (node_q[0].cx),
    .cy_i       (node_q[0].cy),
    .addr_o     (addr0),
    .wide_o     (wide0)
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) lk_valid_o <= 1'b0;
    else         lk_valid_o <= live0_q;
  end
  always_ff @(posedge clk_i) begin
    lk_addr_o <= addr0;
    lk_wide_o <= wide0;
    if (live0_q) begin
      kbx1_q <= IDX_W'((sidx_t'(node_q[0].cx) + sidx_t'(dir_q[0].sx.mv && !dir_q[0].sx.neg))
                       <<< node_q[0].k);
      kby1_q <= IDX_W'((sidx_t'(node_q[0].cy) + sidx_t'(dir_q[0].sy.mv && !dir_q[0].sy.neg))
                       <<< node_q[0].k);
    end
  end

  // ---- S1 - S3: bx - u0 (traverse_bdiff: fixed point, the word of f24_from_int, f24_add) -------
  f24_t dx_f [1], dy_f [1];
  logic bx_en;  // S1 - S3 hold a live ray
  assign bx_en = lv_q[1] || lv_q[2] || lv_q[3];
  traverse_bdiff #(.W(IDX_W), .NB(1)) u_dx (.clk_i, .en_i(bx_en), .b_i('{kbx1_q}),
                                            .u_i(uv_q[1].u), .y_o(dx_f));
  traverse_bdiff #(.W(IDX_W), .NB(1)) u_dy (.clk_i, .en_i(bx_en), .b_i('{kby1_q}),
                                            .u_i(uv_q[1].v), .y_o(dy_f));

  // ---- S4: the height arrives; tx ---------------------------------------------------------------
  // One 16-bit conversion for both widths: code / 255 = (code * 257) / 65535, the same number, so
  // the same rounded f24 (a multiplexer in front of the fast unit, not of the plane's unit).
  // The width flag is a copy of cfg_i.bits16 in a register of its own beside the conversion
  // (the configuration changes only while the unit is idle, and a ray reaches S4 many clocks
  // after it enters; asserted: bits16_copy): the configuration's register also drives the
  // address unit, and in the routed top its wire to this select was 3.5 ns of the worst path.
  f24_t h, tx_raw, ty_raw;
  logic bits16_q;
  always_ff @(posedge clk_i) bits16_q <= cfg_i.bits16;
  assign ok4  = rs_valid_i && rs_hit_i && !rs_err_i;
  assign err4 = rs_valid_i && rs_err_i;
  f24_from_unorm #(.W(16)) u_h (.clk_i, .en_i(ok4),
    .k_i(bits16_q ? rs_data_i : {rs_data_i[7:0], rs_data_i[7:0]}), .y_o(h));
  // (tx, ty for every live ray: whether its read returned data is known only in this stage;
  // the units advance while S4 .. S_EXIT - 1 hold a live ray)
  logic tx_en;
  assign tx_en = |lv_q[S_EXIT-1:S_RS];
  f24_mul #(.LAT(MUL_LAT)) u_tx (.clk_i, .en_i(tx_en), .a_i(dx_f[0]), .b_i(inv4_q.u),
                                 .y_o(tx_raw));
  f24_mul #(.LAT(MUL_LAT)) u_ty (.clk_i, .en_i(tx_en), .a_i(dy_f[0]), .b_i(inv4_q.v),
                                 .y_o(ty_raw));

  // ---- S5: plane = 1 - H (f24_one_minus: f24_add(1, -H) for H in [0, 1], in one clock) --------
  // At MUL_LAT 1 the unit takes H in S5 = S_EXIT and the plane goes straight into S6's
  // comparisons.  At MUL_LAT > 1 H waits MUL_LAT - 2 registers and the unit runs a clock earlier
  // (S_EXIT - 1 -> S_EXIT); the plane and its comparable form are then registered for S_TNEW
  // (plane6_q, plane6_o_q): S6's comparisons start at a register instead of behind f24_ord (the
  // plane through f24_ord and two comparisons in series was the ring's slowest path, 84.7 MHz).
  f24_t     h_x;       // the plane unit's operand, H
  logic     h_ok;      // ... belongs to a pass whose height read returned data
  f24_t     plane6;    // the plane in S_TNEW
  f24_ord_t plane6_o;  // ... comparable
  if (MUL_LAT > 1) begin : g_plane_early
    localparam int unsigned S_PL = S_EXIT - 1;  // the plane unit's stage
    f24_t     plane6_q;
    f24_ord_t plane6_o_q;
    if (MUL_LAT > 2) begin : g_h_delay
      f24_t hd_q [MUL_LAT-2];  // hd_q[i]: H in S6 + i
      always_ff @(posedge clk_i) begin
        if (ok_q[5]) hd_q[0] <= h;
        for (int i = 1; i < MUL_LAT - 2; i++) begin
          if (ok_q[5+i]) hd_q[i] <= hd_q[i-1];
        end
      end
      assign h_x = hd_q[MUL_LAT-3];
    end else begin : g_h_now
      assign h_x = h;
    end
    assign h_ok = ok_q[S_PL];
    f24_t plane_pl;  // the plane in S_EXIT
    f24_one_minus u_plane (.clk_i, .en_i(ok_q[S_PL]), .a_i(h_x), .y_o(plane_pl));
    always_ff @(posedge clk_i) begin
      if (ok_q[S_EXIT]) begin
        plane6_q   <= plane_pl;
        plane6_o_q <= f24_ord(plane_pl);
      end
    end
    assign plane6   = plane6_q;
    assign plane6_o = plane6_o_q;
  end else begin : g_plane_now
    assign h_x  = h;
    assign h_ok = ok_q[S_EXIT];
    f24_one_minus u_plane (.clk_i, .en_i(ok_q[S_EXIT]), .a_i(h_x), .y_o(plane6));
    assign plane6_o = f24_ord(plane6);
  end

  function automatic tval_t tval(input f24_t t);
    return '{t: t, ord: f24_ord(t)};
  endfunction

  // ---- S5: t_exit, t_end -----------------------------------------------------------------------
  // t_exit = min(tx, ty), and whether tx / ty equal it (knowing which one it is).
  function automatic exit_t exit_of(input f24_t tx, input f24_t ty);
    f24_ord_t ox, oy;
    logic     x_first, eq_xy;
    ox      = f24_ord(tx);
    oy      = f24_ord(ty);
    x_first = ord_min_first(ox, oy);  // t_exit is tx
    eq_xy   = ord_eq(ox, oy);
    return '{te: x_first ? tval_t'{t: tx, ord: ox} : tval_t'{t: ty, ord: oy},
             eqx: x_first ? !ox.nan : eq_xy, eqy: x_first ? eq_xy : !oy.nan};
  endfunction

  // min(min(a, b), c), the three comparisons side by side.
  function automatic f24_t min3(input f24_t a, input f24_t b, input tval_t c);
    f24_ord_t oa, ob;
    logic     a_first, a_c, b_c;
    oa      = f24_ord(a);
    ob      = f24_ord(b);
    a_first = ord_min_first(oa, ob);     // min(a, b) is a
    a_c     = ord_min_first(oa, c.ord);  // min(a, c) is a
    b_c     = ord_min_first(ob, c.ord);
    return (a_first ? a_c : b_c) ? (a_first ? a : b) : c.t;
  endfunction

  f24_t tx5, ty5;  // inf on an axis that does not move
  assign tx5 = d5_q.sx.mv ? tx_raw : F24_POS_INF;
  assign ty5 = d5_q.sy.mv ? ty_raw : F24_POS_INF;

  // ---- S5: locate's exit check (header: "Locate's exit check") ---------------------------------
  // tx, ty are the crossing times of the node's exit boundaries: for a descent's estimate the
  // exit times of locate's estimate.  t at or after one of them: the ray is one cell on.  (A
  // check bit is set only on an axis that moves, for a ray that is not done.)
  f24_ord_t t5_o;
  assign t5_o = f24_ord(t_q[S_EXIT]);
  assign rd5  = '{x: v_q[S_EXIT] && stat_q[S_EXIT].chkx && ord_le(f24_ord(tx_raw), t5_o),
                  y: v_q[S_EXIT] && stat_q[S_EXIT].chky && ord_le(f24_ord(ty_raw), t5_o)};

  // ---- S6: t_new, min(t_exit, t_map), whether the pass will be inside: the time to position ---
  // t_new7 and tmin7 are what S7 compares; S6 makes the same comparison on the same words to pick
  // the one time whose position the pass uses: t_new for a hit or a descent (its locate, the
  // hit's u, v), the plane for a crossing (selective's P1).  (t_new is t or the plane: when it is
  // the plane both are one word.)
  f24_ord_t t_new6;
  tmin_t    tmin6;
  logic     t_first6, inside6;
  logic     e_first6;  // min(t_exit, t_map) is t_exit
  assign t_first6 = ord_max_first(t6_q.ord, plane6_o);
  assign t_new6   = t_first6 ? t6_q.ord : plane6_o;
  assign e_first6 = ord_min_first(ex_q[S_TNEW].te.ord, tmap6_q.ord);
  assign tmin6    = '{tmin: e_first6 ? ex_q[S_TNEW].te : tmap6_q,
                      miss_pre: ord_le(tmap6_q.ord, ex_q[S_TNEW].te.ord)};
  // inside6 = ord_lt(t_new6, tmin6.tmin.ord): the comparison of the chosen operands is the
  // choice among the four comparisons, which run side by side with t_first6 and e_first6 (not
  // after them).
  assign inside6  = t_first6 ? (e_first6 ? ord_lt(t6_q.ord, ex_q[S_TNEW].te.ord)
                                         : ord_lt(t6_q.ord, tmap6_q.ord))
                             : (e_first6 ? ord_lt(plane6_o, ex_q[S_TNEW].te.ord)
                                         : ord_lt(plane6_o, tmap6_q.ord));

  // ---- S7: decisions; du * that time ------------------------------------------------------------
  logic inside7;
  act_t act7;
  assign inside7 = ord_lt(t_new7_q, tmin7_q.tmin.ord);
  assign act7    = '{is_hit: inside7 && leaf7_q, down: inside7 && !leaf7_q,
                     miss: !inside7 && tmin7_q.miss_pre};
  f24_t dtp_x, dtp_y;
  logic dtp_en;  // S7 .. S_POS - 1 hold a pass whose height read returned data
  assign dtp_en = |ok_q[S_POS-1:S_DEC];
  f24_mul #(.LAT(MUL_LAT)) u_dtp_x (.clk_i, .en_i(dtp_en), .a_i(duv7_q.u), .b_i(tp7_q),
                                    .y_o(dtp_x));
  f24_mul #(.LAT(MUL_LAT)) u_dtp_y (.clk_i, .en_i(dtp_en), .a_i(duv7_q.v), .b_i(tp7_q),
                                    .y_o(dtp_y));

  // ---- S8: u0 + du * that time, u0 + du t_end (f24_add at POS_ADD_LAT = 3) -------------------
  f24_t pos_x, pos_y;
  logic pos_en;  // S8 - S10 hold a pass whose height read returned data
  assign pos_en  = |ok_q[S_FLR-1:S_POS];
  f24_add #(.LAT(POS_ADD_LAT)) u_pos_x (.clk_i, .en_i(pos_en), .a_i(uv8_q.u), .b_i(dtp_x),
                                        .y_o(pos_x));
  f24_add #(.LAT(POS_ADD_LAT)) u_pos_y (.clk_i, .en_i(pos_en), .a_i(uv8_q.v), .b_i(dtp_y),
                                        .y_o(pos_y));

  // ---- S11: floors of the position (at t_new or the plane), at t_end --------------------------
  // A descent floors the position at t_new, a crossing of the selective level-up the one at the
  // plane (P1): never both in one pass, so they share a unit.
  logic signed [IDX_W-1:0] ia_x, ia_y, ie_x, ie_y;
  logic unused_sat_ax, unused_sat_ay;
  logic ia_en;
  assign ia_en = dn_q[S_FLR] || (sel_up && ok_q[S_FLR] && !in_q[S_FLR]);
  f24_to_index #(.W(IDX_W)) u_ia_x (.clk_i, .en_i(ia_en),
    .a_i(d11_q.sx.mv ? pos_x : uv11_q.u), .idx_o(ia_x), .sat_o(unused_sat_ax));
  f24_to_index #(.W(IDX_W)) u_ia_y (.clk_i, .en_i(ia_en),
    .a_i(d11_q.sy.mv ? pos_y : uv11_q.v), .idx_o(ia_y), .sat_o(unused_sat_ay));

  // ---- S6 - S12: the XOR descent's position at t_end and its floor (XOR_PATH only) -----------
  if (XOR_PATH) begin : g_xor
    f24_t due_x, due_y, pose_x, pose_y;
    logic pose_en;  // S8 - S10 hold a pass of the XOR descent whose height read returned data
    logic unused_sat_ex, unused_sat_ey;
    tval_t tm1_5_q;  // S5: min(t_map, 1)
    f24_t  tend6_q, tend7_q;  // S6, S7: t_end (computed in S5)
    always_ff @(posedge clk_i) begin
      if (lv_q[S_EXIT-1]) begin
        tm1_5_q <= ord_min_first(f24_ord(tmap_q[S_EXIT-1]), f24_ord(F24_ONE))
                   ? tval(tmap_q[S_EXIT-1]) : tval(F24_ONE);
      end
      if (ok_q[S_EXIT]) tend6_q <= min3(tx5, ty5, tm1_5_q);
      if (ok_q[S_TNEW]) tend7_q <= tend6_q;
    end
    assign pose_en = xor_desc && pos_en;
    f24_mul #(.LAT(MUL_LAT)) u_due_x (.clk_i, .en_i(xor_desc && dtp_en), .a_i(duv7_q.u),
                                      .b_i(tend7_q), .y_o(due_x));
    f24_mul #(.LAT(MUL_LAT)) u_due_y (.clk_i, .en_i(xor_desc && dtp_en), .a_i(duv7_q.v),
                                      .b_i(tend7_q), .y_o(due_y));
    f24_add #(.LAT(POS_ADD_LAT)) u_pose_x (.clk_i, .en_i(pose_en), .a_i(uv8_q.u), .b_i(due_x),
                                           .y_o(pose_x));
    f24_add #(.LAT(POS_ADD_LAT)) u_pose_y (.clk_i, .en_i(pose_en), .a_i(uv8_q.v), .b_i(due_y),
                                           .y_o(pose_y));
    f24_to_index #(.W(IDX_W)) u_ie_x (.clk_i, .en_i(xor_desc && dn_q[S_FLR]),
      .a_i(d11_q.sx.mv ? pose_x : uv11_q.u), .idx_o(ie_x), .sat_o(unused_sat_ex));
    f24_to_index #(.W(IDX_W)) u_ie_y (.clk_i, .en_i(xor_desc && dn_q[S_FLR]),
      .a_i(d11_q.sy.mv ? pose_y : uv11_q.v), .idx_o(ie_y), .sat_o(unused_sat_ey));
  end else begin : g_no_xor
    // (descend_pick reads the ends' floors for DESC_XOR only, which is never run here)
    assign ie_x = ia_x;
    assign ie_y = ia_y;
  end

  // ---- S14: child estimate, its entry / exit boundaries, the child's range --------------------
  // c = clip(floor(p) >> k', child range) = clip(floor(p), node) >> k' (the node's range is
  // whole cells of level k'), so c << k' is the clipped p with its low k' bits cleared.
  function automatic logic [IDX_W-1:0] child_bound(input sidx_t a, input logic [LVL_W-1:0] nk,
                                                   input logic inc);
    return IDX_W'((a & ~low_mask(nk)) + (sidx_t'(inc) <<< nk));  // ((a >> nk) + inc) << nk
  endfunction

  // The XOR descent's second end (without XOR_PATH the first: descend_pick does not read it)
  sidx_pair_t b13;
  assign b13 = XOR_PATH ? b13_q : a13_q;

  logic [LVL_W-1:0] dd14;  // levels descended
  assign dd14 = n14_q.k - nk14_q;

  // ---- S14 - S17: crossing times of the child's entry boundaries ------------------------------
  // entry boundary - u0 per axis (traverse_bdiff).  The boundary integers go straight from their
  // logic (S14's registers a14_q, nk14_q, d14_q) into the unit, whose first stage only registers
  // them (b * 2^19: wiring).  The exit boundary's crossing time is the next pass's tx, ty (the
  // exit check, header: "Locate's exit check").
  assign kben_x14 = child_bound(a14_q.x, nk14_q, d14_q.sx.mv && d14_q.sx.neg);
  assign kben_y14 = child_bound(a14_q.y, nk14_q, d14_q.sy.mv && d14_q.sy.neg);
  f24_t dbx [1], dby [1];  // entry - u0
  f24_t ten_x, ten_y;
  logic bd_en;  // S14 - S16 hold a descent
  assign bd_en = |dn_q[S_TEN-1:S_CB];
  traverse_bdiff #(.W(IDX_W), .NB(1)) u_dbx (.clk_i, .en_i(bd_en), .b_i('{kben_x14}),
                                             .u_i(uv_q[S_CB].u), .y_o(dbx));
  traverse_bdiff #(.W(IDX_W), .NB(1)) u_dby (.clk_i, .en_i(bd_en), .b_i('{kben_y14}),
                                             .u_i(uv_q[S_CB].v), .y_o(dby));
  logic ten_en;  // S17 .. S_NS - 1 hold a descent (the crossing times' multipliers)
  assign ten_en = |dn_q[S_NS-1:S_TEN];
  f24_mul #(.LAT(MUL_LAT)) u_ten_x (.clk_i, .en_i(ten_en), .a_i(dbx[0]), .b_i(inv17_q.u),
                                    .y_o(ten_x));
  f24_mul #(.LAT(MUL_LAT)) u_ten_y (.clk_i, .en_i(ten_en), .a_i(dby[0]), .b_i(inv17_q.v),
                                    .y_o(ten_y));

  // ---- S18: next state -----------------------------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // a live ray has no final flag (hit, ...) set: not read
  status_t st18;
  /* verilator lint_on UNUSEDSIGNAL */
  status_t nst18;
  cross_node_t x18;
  logic live18, err18, iter18, hit18, miss18, down18, cross18, cap18, redo18;
  logic chkx18, chky18;  // the descent's estimate stands on x / y: its exit check is due
  assign st18    = st18_q;
  assign x18     = cross_q[S_NS];
  // A ray finished earlier (waiting for room in the result FIFO) is left untouched, and so is
  // one whose lookup missed in the cache (same state, round again).
  assign live18  = v_q[S_NS] && !st18.done;
  assign err18   = live18 && err_q[S_NS];
  assign iter18  = live18 && !err_q[S_NS] && ok_q[S_NS];
  assign hit18   = iter18 && act18_q.is_hit;
  assign miss18  = iter18 && !act18_q.is_hit && act18_q.miss;
  assign down18  = iter18 && !act18_q.is_hit && !act18_q.miss && act18_q.down;
  assign cross18 = iter18 && !act18_q.is_hit && !act18_q.miss && !act18_q.down;
  assign cap18   = iter18 && !act18_q.is_hit && !act18_q.miss && (it18_q >= cfg_i.iter_cap);
  // The exit check found the estimate one cell short: the pass only moves the node on (its
  // height read is not an iteration; S_TNEW on saw neither data nor an error).
  assign redo18  = live18 && (redo_q[S_NS].x || redo_q[S_NS].y);
  // (written for a live ray only, which has none of the final flags set yet)
  assign nst18   = '{crossed:    st18.crossed || cross18,
                     prev_cross: cross18 ? !x18.up : (st18.prev_cross && !down18),
                     done:       err18 || hit18 || miss18 || cap18,
                     hit:        hit18,
                     invalid:    1'b0,
                     capped:     cap18,
                     err:        err18,
                     chkx:       down18 && !cap18 && chkx18,
                     chky:       down18 && !cap18 && chky18,
                     iters:      iter18 ? it18_q : st18.iters};

  assign st_iter_o  = iter18;
  assign st_down_o  = down18;
  assign st_cross_o = cross18;
  assign st_up_o    = cross18 && x18.up;

  // ---- S18: the descent's cell (locate's entry check); S19: retire, merge --------------------
  // locate's entry check: t before the estimate's entry crossing time is one cell back (cells
  // are half-open in t).  Made in S18 from the crossing times as f24_mul delivers them, into
  // ndn19_q: the tail (S19) reads the corrected node from a register, so no comparison lies
  // between a multiplier and the entry multiplexers of S0.  Where the estimate stands and one
  // cell on is in the child's range, its exit check is left to the next pass (chkx, chky).
  logic backx18, backy18;  // t < the estimate's entry crossing time
  assign backx18 = ord_lt(t_new18_q, f24_ord(ten_x));
  assign backy18 = ord_lt(t_new18_q, f24_ord(ten_y));
  assign chkx18  = !backx18 && dsc_q[S_NS].x.fwd;
  assign chky18  = !backy18 && dsc_q[S_NS].y.fwd;
  node_t ndn18, n_new;
  assign ndn18 = '{k:  dsc_q[S_NS].nk,
                   cx: backx18 ? dsc_q[S_NS].x.back : dsc_q[S_NS].x.est,
                   cy: backy18 ? dsc_q[S_NS].y.back : dsc_q[S_NS].y.est};
  assign n_new = '{k: new_ray_i.k, cx: new_ray_i.cx, cy: new_ray_i.cy};

  /* verilator lint_off UNUSEDSIGNAL */  // the tail reads the result flags only
  status_t st19;
  /* verilator lint_on UNUSEDSIGNAL */
  logic    retire, bypass, admit, new_cand, free19;
  logic    park, unpark;  // the ray at the tail parks; the park queue's head takes the slot
  assign st19   = stat_q[D-1];
  assign retire = v_q[D-1] && done19_q && !res_full_i;
  // A ray that setup already finished (invalid, or never enters the map) goes straight to the
  // result FIFO when the tail does not use it this clock.
  assign bypass   = !retire && new_valid_i && new_ray_i.done && !res_full_i;
  // The slot at the tail is free: no ray, or its ray retires or parks.  A parked ray that takes
  // it (unpark) goes before a new ray.
  assign new_cand = new_valid_i && !new_ray_i.done;
  assign free19   = !v_q[D-1] || retire || park;
  assign admit    = new_cand && free19 && !unpark;

  // ---- S19: the park queue (PARK) -------------------------------------------------------------
  // A FIFO of PARK_DEPTH entries (LUT RAM) holding everything a ray resumes with.  A ray at the
  // tail that is not done parks when its lookup missed this pass (its state is unchanged), or
  // when the queue's head has waited PARK_MAX clocks (any pass: its state is complete at the
  // tail), if a ray takes its slot at once (a new ray, or the head) and the queue has room (or
  // the head leaves in the same clock).  The head takes a free slot (before a new ray) when it
  // has waited PARK_WAIT clocks, or when no new ray waits.
  typedef struct packed {
    logic [ID_W-1:0] id;
    f24_pair_t       uv, duv, inv;
    dirs_t           dir;
    f24_t            tmap, t;
    node_t           node;
    status_t         stat;
  } park_t;
  localparam int unsigned PQ   = (PARK_DEPTH > 0) ? PARK_DEPTH : 1;
  localparam int unsigned PAW  = (PQ > 1) ? $clog2(PQ) : 1;
  localparam int unsigned PCW  = $clog2(PQ + 1);
  localparam int unsigned PHW  = $clog2(PARK_MAX + 1);
  localparam int unsigned BUSY_MAX = (1 << LOOP_BUSY_W) - 1;
  if (PARK && (PARK_DEPTH < 1 || D + PARK_DEPTH > BUSY_MAX || PARK_WAIT > 255
               || PARK_MAX < 1)) begin : g_check_park
    $error("traverse_loop: PARK_DEPTH 1 .. %0d, PARK_WAIT <= 255, PARK_MAX >= 1",
           BUSY_MAX - D);
  end
  park_t          pk_head;         // the queue's head
  logic [PCW-1:0] pk_cnt;          // rays parked
  logic [PAW-1:0] pk_rd;           // (checker) the head's entry
  logic [PQ-1:0]  pk_v;            // (checker) pk_v[i]: entry i holds a ray
  logic [ID_W-1:0] pk_id [PQ];     // (checker) their ids
  logic           pk_old;          // (checker) the head has waited PARK_MAX clocks
  logic [PHW-1:0] pk_hw;           // (checker) clocks the head has waited (saturating)
  if (PARK) begin : g_park
    (* ram_style = "distributed" *) park_t pk_q [PQ];
    logic [7:0]     ts_mem [PQ];   // the clock each entry parked (mod 256; two read ports)
    logic [PAW-1:0] rd_q, wr;      // head, next free entry (rd + count, mod PQ)
    logic [PAW-1:0] rd1;           // the entry after the head (rd + 1, mod PQ)
    logic [PAW:0]   wsum;
    logic [PCW-1:0] cnt_q;
    logic [7:0]     ts_q;          // clock counter for the entries' time stamps
    logic [PHW-1:0] hw_q;          // clocks the head has waited, saturating at PARK_MAX
    logic           miss19_q;      // S19: the ray's height read returned neither data nor an
                                   // error (a lookup miss, for a ray that is not done)
    f24_pair_t      pduv19_q, pinv19_q;  // S19: du, dv, 1/du, 1/dv (block RAM read registers)
    logic           ne, full, ready, cand;
    // The head's two flags, registered (computed a clock ahead for the head of the next clock,
    // off the park decision's path): old_q = pk_old (the head has waited PARK_MAX clocks),
    // wait_q = its age (clocks since it parked, mod 256) >= PARK_WAIT.
    logic           old_q, wait_q, old_d, wait_d;
    logic [7:0]     age1, age1_nxt;  // next clock's age of the head, of the entry after it
    assign wsum   = (PAW+1)'(rd_q) + (PAW+1)'(cnt_q);
    assign wr     = (wsum >= (PAW+1)'(PQ)) ? PAW'(wsum - (PAW+1)'(PQ)) : PAW'(wsum);
    assign ne     = (cnt_q != '0);
    assign full   = (cnt_q == PCW'(PQ));
    assign rd1    = (rd_q == PAW'(PQ - 1)) ? '0 : rd_q + PAW'(1);
    assign pk_old = old_q;
    assign ready  = old_q || wait_q;
    // Next clock's head: the same (no unpark); the entry after it (unpark, 2 or more parked);
    // or the ray parking in this clock (an empty queue, or one ray that unparks): age 1.
    assign age1     = ts_q + 8'd1 - ts_mem[rd_q];
    assign age1_nxt = ts_q + 8'd1 - ts_mem[rd1];
    assign wait_d   = unpark ? ((cnt_q > PCW'(1)) ? (age1_nxt >= 8'(PARK_WAIT))
                                                  : (8'd1 >= 8'(PARK_WAIT)))
                             : ne ? (age1 >= 8'(PARK_WAIT)) : (8'd1 >= 8'(PARK_WAIT));
    // hw_q's next value is PARK_MAX (and the queue not empty) exactly when the head stays and
    // has waited PARK_MAX - 1 clocks or more
    assign old_d    = ne && !unpark && (32'(hw_q) + 1 >= PARK_MAX);
    assign cand   = ne && (ready || !new_cand);
    assign park   = v_q[D-1] && !done19_q && (miss19_q || pk_old) && (new_cand || cand)
                    && (!full || cand);
    assign unpark = cand && free19;
    assign pk_head = pk_q[rd_q];
    assign pk_cnt  = cnt_q;
    assign pk_rd   = rd_q;
    assign pk_hw   = hw_q;
    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        rd_q  <= '0;
        cnt_q <= '0;
        ts_q  <= '0;
        hw_q  <= '0;
        old_q  <= 1'b0;
        wait_q <= 1'b0;
      end else begin
        old_q  <= old_d;
        wait_q <= wait_d;
        ts_q  <= ts_q + 8'd1;
        cnt_q <= cnt_q + PCW'(park) - PCW'(unpark);
        if (unpark) rd_q <= (rd_q == PAW'(PQ - 1)) ? '0 : rd_q + PAW'(1);
        hw_q  <= (unpark || !ne) ? '0 : pk_old ? hw_q : hw_q + PHW'(1);
      end
    end
    always_ff @(posedge clk_i) begin
      // (not live18: a ray that is not done in S19 was live in S18, and the status's done flag
      // would bring the float datapath into the park decision, which the formal model cuts at
      // done19_q)
      miss19_q <= !ok_q[S_NS] && !err_q[S_NS] && !(redo_q[S_NS].x || redo_q[S_NS].y);
      if (v_q[S_NS]) begin
        pduv19_q <= duv_q[sl_q[S_NS]];
        pinv19_q <= inv_q[sl_q[S_NS]];
      end
      if (park) begin
        pk_q[wr] <= '{id: id_q[D-1], uv: uv_q[D-1], duv: pduv19_q, inv: pinv19_q,
                      dir: dir_q[D-1], tmap: tmap_q[D-1], t: t_q[D-1],
                      node: down19_q ? ndn19_q : node_q[D-1], stat: stat_q[D-1]};
        ts_mem[wr] <= ts_q;
      end
    end
    for (genvar g = 0; g < PQ; g++) begin : g_pk_v
      assign pk_v[g]  = ((g >= rd_q) ? (PCW'(g) - PCW'(rd_q)) : (PCW'(g + PQ) - PCW'(rd_q)))
                        < cnt_q;
      assign pk_id[g] = pk_q[g].id;
    end
  end else begin : g_no_park
    assign park    = 1'b0;
    assign unpark  = 1'b0;
    assign pk_head = '0;
    assign pk_cnt  = '0;
    assign pk_rd   = '0;
    assign pk_v    = '0;
    assign pk_id   = '{default: '0};
    assign pk_old  = 1'b0;
    assign pk_hw   = '0;
  end

  assign new_pop_o  = bypass || admit;
  assign res_push_o = retire || bypass;
  assign res_id_o   = retire ? id_q[D-1] : new_id_i;
  // (a retiring ray's uv_q holds the hit's u, v if it hit, else u0, v0)
  assign res_o      = retire ? '{t: t_q[D-1], u: uv_q[D-1].u, v: uv_q[D-1].v,
                                 hit: st19.hit, invalid: st19.invalid, capped: st19.capped,
                                 err: st19.err, iters: st19.iters}
                             : '{t: new_ray_i.t, u: new_ray_i.u0, v: new_ray_i.v0,
                                 hit: new_ray_i.hit, invalid: new_ray_i.invalid,
                                 capped: new_ray_i.capped, err: new_ray_i.err,
                                 iters: new_ray_i.iters};

  // ---- ring ------------------------------------------------------------------------------------
  // S19 -> S0: the ray re-circulates (priority), or a new ray fills the bubble.
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      v_q     <= '0;
      live0_q <= 1'b0;
    end else begin
      v_q     <= {v_q[D-2:0], (v_q[D-1] && !retire && !park) || admit || unpark};
      live0_q <= admit || unpark || (v_q[D-1] && !done19_q && !park);
    end
  end

  // The stage flags are reset: they enable the stages' registers and the checks, and a reset
  // shorter than the ring must not leave a power-up value in them.
  // A redo (rd5) clears the pass's ok and err from S_TNEW on: nothing after S_EXIT acts on its
  // height read.
  logic [S_NS:5] ok_d, err_d;
  always_comb begin
    ok_d[5]  = ok4;
    err_d[5] = err4;
    for (int s = 6; s <= S_NS; s++) begin
      ok_d[s]  = ok_q[s-1];
      err_d[s] = err_q[s-1];
    end
    ok_d[S_TNEW]  = ok_q[S_EXIT] && !(rd5.x || rd5.y);
    err_d[S_TNEW] = err_q[S_EXIT] && !(rd5.x || rd5.y);
  end
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      ok_q  <= '0;
      err_q <= '0;
      in_q  <= '0;
      dn_q  <= '0;
      lv_q  <= '0;
      redo_q <= '{default: '0};
    end else begin
      ok_q  <= ok_d;
      err_q <= err_d;
      redo_q[S_TNEW] <= rd5;
      for (int s = S_TNEW + 1; s <= S_NS; s++) redo_q[s] <= redo_q[s-1];
      in_q  <= {in_q[S_XUP-1:S_DEC+1], ok_q[S_DEC] && inside7};
      dn_q  <= {dn_q[S_NS-1:S_DEC+1], ok_q[S_DEC] && act7.down};
      lv_q  <= {lv_q[S_EXIT-2:1], live0_q};
    end
  end

  // The registered reads and the pipelines; each loads while the stage before its reader holds a
  // pass that uses it.
  always_ff @(posedge clk_i) begin
    // S19 -> S0: the ray coming round (S18 wrote a crossing's node), its descent's node, or the
    // new ray
    if (lv_q[2]) inv3_q <= inv_q[sl_q[2]];
    if (lv_q[3]) inv4_q <= inv3_q;
    if (lv_q[S_EXIT-1]) begin
      duv5_q  <= duv_q[sl_q[S_EXIT-1]];
      d5_q    <= dir_q[S_EXIT-1];
      tmap5_q <= tval(tmap_q[S_EXIT-1]);
    end
    if (ok_q[S_EXIT]) begin
      ex_q[S_TNEW] <= exit_of(tx5, ty5);
      tmap6_q <= tmap5_q;
      t6_q    <= tval(t_q[S_EXIT]);
      duv6_q  <= duv5_q;
    end
    if (ok_q[S_TNEW]) begin
      t_new7_q <= t_new6;
      tmin7_q  <= tmin6;
      leaf7_q  <= (node_q[S_TNEW].k == '0);
      tp7_q    <= (inside6 && t_first6) ? t6_q.t : plane6;
      duv7_q   <= duv6_q;
    end
    for (int s = S_TNEW; s < S_XPRE; s++) begin
      if (ok_q[s]) ex_q[s+1] <= ex_q[s];
    end
    if (ok_q[S_POS-1]) uv8_q <= uv_q[S_POS-1];
    if (ok_q[S_FLR-1]) begin
      uv11_q <= uv_q[S_FLR-1];
      d11_q  <= dir_q[S_FLR-1];
      n11_q  <= node_q[S_FLR-1];
    end
    if (ok_q[S_FLR]) begin
      d12_q       <= d11_q;
      n12_q       <= n11_q;
      lo12_q      <= '{x: node_lo(n11_q.k, n11_q.cx), y: node_lo(n11_q.k, n11_q.cy)};
      hi12_q      <= '{x: node_hi(n11_q.k, n11_q.cx), y: node_hi(n11_q.k, n11_q.cy)};
      crossed12_q <= stat_q[S_FLR].crossed;
      prev12_q    <= stat_q[S_FLR].prev_cross;
      t12_q       <= tval(t_q[S_FLR]);
    end
    // S12 -> S13: the crossing's first part, the descent's clipped positions
    if (ok_q[S_XPRE] && !in_q[S_XPRE]) begin
      xpre13_q <= cross_pre(n12_q.k, n12_q.cx, n12_q.cy, ex_q[S_XPRE].eqx, ex_q[S_XPRE].eqy,
                            d12_q.sx, d12_q.sy, ia_x, ia_y);
      prev13_q <= prev12_q;
    end
    if (dn_q[S_XPRE]) begin
      a13_q   <= '{x: clip_idx(sidx_t'(ia_x), lo12_q.x, hi12_q.x),
                   y: clip_idx(sidx_t'(ia_y), lo12_q.y, hi12_q.y)};
      b13_q   <= '{x: clip_idx(sidx_t'(ie_x), lo12_q.x, hi12_q.x),
                   y: clip_idx(sidx_t'(ie_y), lo12_q.y, hi12_q.y)};
      nkm13_q <= multi_level(cfg_i.policy.levels, n12_q.k, crossed12_q);
      n13_q   <= n12_q;
      d13_q   <= d12_q;
    end
    // S13 -> S14: the new level
    if (dn_q[S_XUP]) begin
      nk14_q <= descend_pick(desc, n13_q.k, nkm13_q, a13_q.x, b13.x, a13_q.y, b13.y);
      a14_q  <= a13_q;
      n14_q  <= n13_q;
      d14_q  <= d13_q;
    end
    // S14 -> S15: the child's estimate and range (its boundary integers: S14, above)
    if (dn_q[S_CB]) begin
      c15_q      <= '{x: a14_q.x >>> nk14_q, y: a14_q.y >>> nk14_q};
      lo15_q     <= '{x: node_lo(dd14, n14_q.cx), y: node_lo(dd14, n14_q.cy)};
      hi15_q     <= '{x: node_hi(dd14, n14_q.cx), y: node_hi(dd14, n14_q.cy)};
      nk15_q     <= nk14_q;
      d15_q      <= d14_q;
    end
    // S15 -> S16: locate's three candidates
    if (dn_q[S_LOC]) begin
      dsc_q[S_LOC+1] <= '{nk: nk15_q,
        x: '{back: CELL_W'(clip_idx(c15_q.x - dir_val(d15_q.sx), lo15_q.x, hi15_q.x)),
             est:  CELL_W'(c15_q.x),
             fwd:  d15_q.sx.mv && (d15_q.sx.neg ? (c15_q.x > lo15_q.x) : (c15_q.x < hi15_q.x))},
        y: '{back: CELL_W'(clip_idx(c15_q.y - dir_val(d15_q.sy), lo15_q.y, hi15_q.y)),
             est:  CELL_W'(c15_q.y),
             fwd:  d15_q.sy.mv && (d15_q.sy.neg ? (c15_q.y > lo15_q.y) : (c15_q.y < hi15_q.y))}};
    end
    for (int s = S_LOC + 1; s < S_NS; s++) begin
      if (dn_q[s]) dsc_q[s+1] <= dsc_q[s];
    end
    if (dn_q[S_TEN-2]) inv16_q <= inv_q[sl_q[S_TEN-2]];
    if (dn_q[S_TEN-1]) inv17_q <= inv16_q;
    if (v_q[S_NS-1]) begin
      st18_q  <= stat_q[S_NS-1];
      it18_q  <= stat_q[S_NS-1].iters + ITER_W'(1);
      act18_q <= act_q[S_NS-1];
    end
    // S18 -> S19 (t_new from S17)
    if (dn_q[S_NS-1]) t_new18_q <= f24_ord(t_new_q[S_NS-1]);
    if (dn_q[S_NS]) ndn19_q <= ndn18;
    // S17 -> S18: a redo's node, one cell on along the axes its exit check moved
    if (v_q[S_NS-1] && (redo_q[S_NS-1].x || redo_q[S_NS-1].y)) begin
      rn18_q <= '{k:  node_q[S_NS-1].k,
                  cx: node_q[S_NS-1].cx
                      + (redo_q[S_NS-1].x ? CELL_W'(dir_val(dir_q[S_NS-1].sx)) : '0),
                  cy: node_q[S_NS-1].cy
                      + (redo_q[S_NS-1].y ? CELL_W'(dir_val(dir_q[S_NS-1].sy)) : '0)};
    end
    down19_q <= down18 && !cap18;  // (a capped ray is done: its node is never read again)
    done19_q <= (err18 || iter18) ? nst18.done : st18.done;
  end

  // The ring: every field moves on one stage per clock; a stage that changes a field loads the
  // next stage's register instead.
  always_ff @(posedge clk_i) begin
    for (int s = 1; s < D; s++) begin
      id_q[s]   <= id_q[s-1];
      uv_q[s]   <= uv_q[s-1];
      dir_q[s]  <= dir_q[s-1];
      tmap_q[s] <= tmap_q[s-1];
      node_q[s] <= node_q[s-1];
      t_q[s]    <= t_q[s-1];
      stat_q[s] <= stat_q[s-1];
    end
    // S19 -> S0: the ray re-circulates (its descent's node, if it descended), or a new ray fills
    // the bubble
    // the bubble, or a parked ray comes back
    id_q[0]   <= admit ? new_id_i : unpark ? pk_head.id : id_q[D-1];
    uv_q[0]   <= admit ? '{u: new_ray_i.u0, v: new_ray_i.v0} : unpark ? pk_head.uv : uv_q[D-1];
    dir_q[0]  <= admit ? '{sx: new_ray_i.sx, sy: new_ray_i.sy}
               : unpark ? pk_head.dir : dir_q[D-1];
    tmap_q[0] <= admit ? new_ray_i.t_map : unpark ? pk_head.tmap : tmap_q[D-1];
    node_q[0] <= admit ? n_new : unpark ? pk_head.node : down19_q ? ndn19_q : node_q[D-1];
    // (n - k of the same node, each candidate's difference made before the choice)
    nk0_q     <= admit ? cfg_i.n - new_ray_i.k : unpark ? cfg_i.n - pk_head.node.k
               : down19_q ? cfg_i.n - ndn19_q.k : cfg_i.n - node_q[D-1].k;
    t_q[0]    <= admit ? new_ray_i.t : unpark ? pk_head.t : t_q[D-1];
    stat_q[0] <= admit ? status_t'{crossed: new_ray_i.crossed, prev_cross: new_ray_i.prev_cross,
                                   done: new_ray_i.done, hit: new_ray_i.hit,
                                   invalid: new_ray_i.invalid, capped: new_ray_i.capped,
                                   err: new_ray_i.err, chkx: 1'b0, chky: 1'b0,
                                   iters: new_ray_i.iters}
               : unpark ? pk_head.stat : stat_q[D-1];
    // S18 -> S19: the next state (only a live ray whose lookup answered changes); a hit's u, v
    // take the place of u0, v0 (no stage reads those again)
    if (err18 || iter18) stat_q[S_TL] <= nst18;
    if (redo18) begin
      stat_q[S_TL]      <= st18;
      stat_q[S_TL].chkx <= 1'b0;
      stat_q[S_TL].chky <= 1'b0;
      node_q[S_TL]      <= rn18_q;
    end
    if (hit18 || down18) t_q[S_TL] <= t_new_q[S_NS];
    if (cross18) begin
      t_q[S_TL]    <= xt_q[S_NS];
      node_q[S_TL] <= '{k: x18.k, cx: x18.cx, cy: x18.cy};
    end
    if (hit18) uv_q[S_TL] <= pos_q[S_NS];
    // What this pass computes for its later stages (only for the passes that read it: the height
    // read returned data; hits and descents; crossings).
    for (int s = S_DEC + 1; s <= S_NS; s++) t_new_q[s] <= t_new_q[s-1];
    for (int s = S_DEC + 2; s < S_NS; s++) act_q[s] <= act_q[s-1];
    for (int s = S_XPRE + 1; s <= S_NS; s++) pos_q[s] <= pos_q[s-1];
    for (int s = S_XUP + 1; s <= S_NS; s++) xt_q[s] <= xt_q[s-1];
    for (int s = S_CB + 1; s <= S_NS; s++) cross_q[s] <= cross_q[s-1];
    if (ok_q[S_TNEW]) t_new_q[S_DEC] <= t_first6 ? t6_q.t : plane6;
    if (ok_q[S_DEC]) act_q[S_DEC+1] <= act7;
    if (in_q[S_FLR]) pos_q[S_XPRE] <= '{u: pos_x, v: pos_y};
    if (ok_q[S_XPRE] && !in_q[S_XPRE]) begin
      xt_q[S_XUP] <= ord_max_first(t12_q.ord, ex_q[S_XPRE].te.ord) ? t12_q.t
                                                                   : ex_q[S_XPRE].te.t;
    end
    if (ok_q[S_XUP] && !in_q[S_XUP]) begin
      cross_q[S_CB] <= cross_up(cfg_i.policy.level_up, cfg_i.n, xpre13_q, prev13_q);
    end
  end

  // (checker) the slots whose ray has an exit check due, and those whose ray is done
  logic [D-1:0] chk_v, chk_done;
  for (genvar g = 0; g < D; g++) begin : g_chk
    assign chk_v[g]    = v_q[g] && (stat_q[g].chkx || stat_q[g].chky);
    assign chk_done[g] = stat_q[g].done;
  end

  // The block RAM tables: written when a ray enters the ring (new or from the park queue), in
  // its slot's entry (that slot is in S0 next clock).
  always_ff @(posedge clk_i) begin
    if (admit || unpark) begin
      duv_q[sl_q[D-1]] <= unpark ? pk_head.duv : '{u: new_ray_i.du, v: new_ray_i.dv};
      inv_q[sl_q[D-1]] <= unpark ? pk_head.inv : '{u: new_ray_i.inv_du, v: new_ray_i.inv_dv};
    end
  end

  always_comb begin
    busy_o = LOOP_BUSY_W'($countones(v_q)) + LOOP_BUSY_W'(pk_cnt);
  end

  // The simulation checks are in traverse_loop_assert.sv (bound into every instance).

endmodule
