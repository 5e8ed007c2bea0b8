// traverse_loop: the second mode of the traverse unit, the iterative search of model/traverse.py
// (the body of _trace's `while act.size` loop, for one ray per pass).
//
// A ring of LOOP_DEPTH = 18 stages; every stage holds one ray slot and every slot advances one
// stage per clock (the loop never stalls).  One pass round the ring = one iteration = one height
// lookup.  At the ring's tail (S17) a finished ray leaves for the result FIFO; a slot that is then
// empty takes a new ray from setup (re-circulating rays have priority: new rays only fill
// bubbles).
//
// Slot table: the ring moves only the slots' valid bits.  Everything else a slot holds lives in
// one entry of a table of D = 18 entries, one per slot: a ray entering the ring is written into
// its slot's entry, and because every slot advances one stage per clock, the entry of the slot in
// stage s is (ph_q - s) mod 18, with ph_q a phase counter that steps every clock.  So a ray never
// changes entry while it circulates, and a stage reads only the fields it needs (a register file
// of 18 entries with several read ports instead of 18 x ~270 bits of shift registers).  Per entry:
//   - the per-ray constants u0, v0, du, dv, 1/du, 1/dv, directions, t_map and the ray id, written
//     when the ray enters the ring (a hit overwrites u0 / v0 with the hit position);
//   - the traversal state (level, cell, t, flags, iterations), written on entry and by S16;
//   - what one pass computes for a later stage of the same pass (t_exit, t_new, the action, the
//     crossing, the hit position and the descent): written by the stage that computes it, only
//     for the passes that read it, and read up to 10 stages later (before the slot comes round).
// A few activity bits per stage do move with the slots: the slot holds a live ray (S1 - S2), the
// height read returned data (ok) or an error (S3 - S16), the pass hits or descends (S8 - S10), the
// pass descends (S8 - S15).
//
// Clock enables: a unit advances only while its stages hold a pass that uses its result, and
// holds its registers otherwise (less switching, and less work for a simulator).  Before the
// height arrives (S0 - S2) that is a live ray; from S3 on a pass whose height read returned data
// (ok); the positions at t_new only for a pass that hits or descends, the floor of that position
// and the child's boundaries only for a descent.  The units that only some methods use advance
// only for those methods: the positions at t_end (the XOR descent), those at the plane (the
// selective level-up), and the 8-bit or the 16-bit height conversion.
//
// Stage schedule (a unit "a -> b" takes operands in Sa and delivers in Sb):
//   S0   height address base + off[k] + (cy * side_k + cx) * bytes  -> lk_* registers (S1)
//        (traverse_addr)
//        exit boundaries bx = (cx + (sx > 0)) << k                  f24_from_int S0 -> S1
//   S1   lookup presented (lk_valid_o, lk_addr_o, lk_wide_o)
//        bx - u0                                                    f24_add      S1 -> S3
//   S3   response {valid, hit, err, data} (LOOKUP_LAT = 2 after S1)
//        H = code / (2^bits - 1)                                    f24_from_unorm S3 -> S4
//        tx = (bx - u0) * (1/du)                                    f24_mul      S3 -> S4
//   S4   plane = 1 - H                                              f24_add      S4 -> S6
//        t_exit = min(tx, ty) (inf on an axis that does not move)
//   S5   t_end = min(min(t_exit, t_map), 1); du * t_end             f24_mul      S5 -> S6
//   S6   t_new = max(t, plane); u0 + du t_end                       f24_add      S6 -> S8
//        du * plane                                                 f24_mul      S6 -> S7
//   S7   inside / miss / hit / down / cross; du * t_new             f24_mul      S7 -> S8
//        u0 + du plane                                              f24_add      S7 -> S9
//   S8   u0 + du t_new (= the hit's u)                              f24_add      S8 -> S10
//        floor(position at t_end)                                   f24_to_index S8 -> S9
//   S9   floor(position at plane) (selective's P1)                  f24_to_index S9 -> S10
//   S10  crossing: neighbour cell, level-up policy                  floor(position at t_new)
//        (traverse_pkg::level_cross)
//                                                                   f24_to_index S10 -> S11
//   S11  descent: new level (one; multi: `levels` until the first crossing; XOR of the ends)
//        (traverse_pkg::level_descend)
//   S12  child estimate floor(p) >> k', clip; its entry / exit      f24_from_int S12 -> S13
//        and the three cells locate's correction chooses from
//   S13  boundary - u0                                              f24_add      S13 -> S15
//   S15  (boundary - u0) * (1/du)                                   f24_mul      S15 -> S16
//   S16  locate's correction; next state (hit / miss / down / cross / lookup miss / cap)
//   S17  retire to the result FIFO, or merge with a new ray, -> S0
// Positions on an axis that does not move are u0 itself (the model's np.where(s != 0, p, p0)).
// Float units per axis pair: 6 f24_from_int, 13 f24_add, 12 f24_mul, 6 f24_to_index, 2
// f24_from_unorm.  Up to three positions per axis are computed in a pass (at t_end for the XOR
// descent, at the plane for selective's P1, at t_new for locate and the hit); the ring is 18 deep
// (the paper's is 15) because the descent's locate (position, floor, two crossing times,
// correction) follows t_new as a dependent chain of about 9 clocks.
//
// Lookup misses: the ray keeps its state and goes round again; the iteration is not counted
// (iterations = height reads that returned data).  A read error finishes the ray with err = 1.
// Back-pressure: a finished ray leaves only when the result FIFO has room; otherwise it keeps
// circulating (no lookups, state untouched) and tries again one pass later.
module traverse_loop
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W = 8
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  /* verilator lint_off UNUSEDSIGNAL */  // the second mode reads only part of the configuration
  input  cfg_t              cfg_i,
  /* verilator lint_on UNUSEDSIGNAL */
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
  output logic              st_iter_o,   // an iteration (a height read that returned data)
  output logic              st_down_o,   // ... that descended
  output logic              st_cross_o,  // ... that crossed to a neighbour
  output logic              st_up_o,     // ... that crossed and went up a level
  output logic [4:0]        busy_o       // rays in the ring
);

  localparam int unsigned D  = 18;          // LOOP_DEPTH: stages S0 .. S17
  localparam int unsigned SW = $clog2(D);   // slot-table index width

  typedef logic [SW-1:0] slot_idx_t;

  // ---- slot table fields (see the header); each array has one entry per ring slot ------------
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
    logic [ITER_W-1:0] iters;      // height reads that returned data
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
    logic signed [IDX_W-1:0] x, y;
  } idx_pair_t;
  typedef struct packed {
    logic [CELL_W-1:0] back;       // t before the estimate's entry: one cell back (clipped)
    logic [CELL_W-1:0] est;        // the estimate itself
    logic [CELL_W-1:0] fwd;        // t at or after its exit: one cell on (clipped)
  } locate_t;

  // Per ray.
  logic [ID_W-1:0]  id_q     [D];
  f24_pair_t        uv_q     [D];  // u0, v0 (the hit position once done with a hit)
  f24_pair_t        duv_q    [D];  // du, dv
  f24_pair_t        inv_q    [D];  // 1 / du, 1 / dv
  dirs_t            dir_q    [D];
  f24_t             tmap_q   [D];  // time of leaving the map's extent
  node_t            node_q   [D];
  tval_t            t_q      [D];  // time the ray is at (hit time once done with a hit)
  status_t          stat_q   [D];
  // Per pass: [the stage that writes it, on the passes named] the stages that read it.  "ok": the
  // height read returned data; "inside": the pass hits or descends.
  exit_t            exit_q   [D];  // [S4 ok]          S5, S10
  tmin_t            tmin_q   [D];  // [S5 ok]          S7
  tval_t            t_new_q  [D];  // [S6 ok]          S7, S16: max(t, plane)
  act_t             act_q    [D];  // [S7 ok]          S16
  idx_pair_t        ie_q     [D];  // [S9 XOR descent] S11: floor(position at t_end)
  tval_t            xt_q     [D];  // [S10 ok, not inside] S16: the crossing's time max(t, t_exit)
  cross_node_t      cross_q  [D];  // [S10 ok, not inside] S16: the crossing's new node, up
  f24_pair_t        pos_q    [D];  // [S10 inside]     S16: position at t_new (the hit's u, v)
  logic [LVL_W-1:0] nk_q     [D];  // [S11 descent]    S12, S16: the descent's new level
  locate_t          locx_q   [D];  // [S12 descent]    S16
  locate_t          locy_q   [D];

  // ---- ring position, pass activity (see the header) ----------------------------------------
  logic [D-1:0] v_q;               // v_q[s]: the slot in stage s holds a ray
  logic         ok3, err3;         // the height read of the ray in S3 returned data / an error
  logic [16:4]  ok_q, err_q;       // ok3, err3 of the ray in stage s (meaningful with v_q[s])
  logic [10:8]  in_q;              // in_q[s]: ok, and the pass hits or descends (inside its node)
  logic [15:8]  dn_q;              // dn_q[s]: ok, and the pass descends
  logic [2:1]   lv_q;              // lv_q[s]: the slot in stage s holds a live ray (not done)
  logic         xor_desc, sel_up;  // the method uses the XOR descent / the selective level-up
  slot_idx_t    ph_q;              // phase: stage s holds the slot of entry (ph_q - s) mod D
  slot_idx_t    sl [D];            // sl[s] = (ph_q - s) mod D

  always_comb begin
    for (int s = 0; s < D; s++) begin
      sl[s] = (ph_q >= SW'(s)) ? ph_q - SW'(s) : ph_q + SW'(D - s);
    end
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) ph_q <= '0;
    else         ph_q <= (ph_q == SW'(D - 1)) ? '0 : ph_q + SW'(1);
  end

  // ---- S0: height address, exit boundaries -----------------------------------------------------
  node_t n0;
  dirs_t d0;
  assign n0 = node_q[sl[0]];
  assign d0 = dir_q[sl[0]];

  logic [ADDR_W-1:0] addr0;
  logic              wide0;
  traverse_addr u_addr (
    .base_i     (cfg_i.base),
    .level_off_i(cfg_i.level_off),
    .n_i        (cfg_i.n),
    .bits16_i   (cfg_i.bits16),
    .k_i        (n0.k),
    .cx_i       (n0.cx),
    .cy_i       (n0.cy),
    .addr_o     (addr0),
    .wide_o     (wide0)
  );

  logic live0;  // the slot in S0 holds a live ray: it looks its height up
  assign live0 = v_q[0] && !stat_q[sl[0]].done;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) lk_valid_o <= 1'b0;
    else         lk_valid_o <= live0;
  end
  always_ff @(posedge clk_i) begin
    lk_addr_o <= addr0;
    lk_wide_o <= wide0;
  end

  assign xor_desc = (cfg_i.policy.descent == DESC_XOR);
  assign sel_up   = (cfg_i.policy.level_up == UP_SELECTIVE);

  f24_t bx_f, by_f;
  f24_from_int #(.W(IDX_W)) u_bx (.clk_i, .en_i(live0),
    .k_i(IDX_W'((sidx_t'(n0.cx) + sidx_t'(d0.sx.mv && !d0.sx.neg)) <<< n0.k)), .y_o(bx_f));
  f24_from_int #(.W(IDX_W)) u_by (.clk_i, .en_i(live0),
    .k_i(IDX_W'((sidx_t'(n0.cy) + sidx_t'(d0.sy.mv && !d0.sy.neg)) <<< n0.k)), .y_o(by_f));

  // ---- S1 ------------------------------------------------------------------------------------
  f24_pair_t uv1;
  f24_t      dx_f, dy_f;
  assign uv1 = uv_q[sl[1]];
  f24_add u_dx (.clk_i, .en_i(lv_q[1] || lv_q[2]), .a_i(bx_f), .b_i(f24_neg(uv1.u)), .y_o(dx_f));
  f24_add u_dy (.clk_i, .en_i(lv_q[1] || lv_q[2]), .a_i(by_f), .b_i(f24_neg(uv1.v)), .y_o(dy_f));

  // ---- S3: the height arrives ------------------------------------------------------------------
  f24_pair_t inv3;
  f24_t      h8, h16, tx_raw, ty_raw;
  assign inv3 = inv_q[sl[3]];
  assign ok3  = rs_valid_i && rs_hit_i && !rs_err_i;
  assign err3 = rs_valid_i && rs_err_i;
  f24_from_unorm #(.W(8))  u_h8  (.clk_i, .en_i(ok3 && !cfg_i.bits16), .k_i(rs_data_i[7:0]),
                                  .y_o(h8));
  f24_from_unorm #(.W(16)) u_h16 (.clk_i, .en_i(ok3 && cfg_i.bits16), .k_i(rs_data_i), .y_o(h16));
  f24_mul u_tx (.clk_i, .en_i(ok3), .a_i(dx_f), .b_i(inv3.u), .y_o(tx_raw));
  f24_mul u_ty (.clk_i, .en_i(ok3), .a_i(dy_f), .b_i(inv3.v), .y_o(ty_raw));

  // ---- S4: plane, t_exit -----------------------------------------------------------------------
  f24_t  plane;
  dirs_t d4;
  assign d4 = dir_q[sl[4]];
  f24_add u_plane (.clk_i, .en_i(ok_q[4] || ok_q[5]), .a_i(F24_ONE),
                   .b_i(f24_neg(cfg_i.bits16 ? h16 : h8)), .y_o(plane));

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

  // ---- S5: t_end -------------------------------------------------------------------------------
  f24_pair_t duv5;
  f24_t      tmap5, t_end, due_x, due_y;
  tval_t     te5, tmin5;
  f24_ord_t  otmap5;
  tmin_t     tmin5_d;
  assign te5     = exit_q[sl[5]].te;
  assign tmap5   = tmap_q[sl[5]];
  assign duv5    = duv_q[sl[5]];
  assign otmap5  = f24_ord(tmap5);
  assign tmin5   = ord_min_first(te5.ord, otmap5) ? te5 : '{t: tmap5, ord: otmap5};
  assign t_end   = ord_min_first(tmin5.ord, f24_ord(F24_ONE)) ? tmin5.t : F24_ONE;
  assign tmin5_d = '{tmin: tmin5, miss_pre: ord_le(otmap5, te5.ord)};
  f24_mul u_due_x (.clk_i, .en_i(xor_desc && ok_q[5]), .a_i(duv5.u), .b_i(t_end), .y_o(due_x));
  f24_mul u_due_y (.clk_i, .en_i(xor_desc && ok_q[5]), .a_i(duv5.v), .b_i(t_end), .y_o(due_y));

  // ---- S6: t_new, position at t_end, du * plane ------------------------------------------------
  f24_pair_t uv6;
  f24_pair_t duv6;
  f24_t      pose_x, pose_y, dup_x, dup_y;
  assign uv6     = uv_q[sl[6]];
  assign duv6    = duv_q[sl[6]];
  logic pose_en;  // S6 - S7 hold a pass of the XOR descent whose height read returned data
  assign pose_en = xor_desc && (ok_q[6] || ok_q[7]);
  f24_add u_pose_x (.clk_i, .en_i(pose_en), .a_i(uv6.u), .b_i(due_x), .y_o(pose_x));
  f24_add u_pose_y (.clk_i, .en_i(pose_en), .a_i(uv6.v), .b_i(due_y), .y_o(pose_y));
  f24_mul u_dup_x (.clk_i, .en_i(sel_up && ok_q[6]), .a_i(duv6.u), .b_i(plane), .y_o(dup_x));
  f24_mul u_dup_y (.clk_i, .en_i(sel_up && ok_q[6]), .a_i(duv6.v), .b_i(plane), .y_o(dup_y));

  // max(a, b), for t_new = max(t, plane)
  function automatic tval_t t_max(input tval_t a, input f24_t b);
    f24_ord_t ob;
    ob = f24_ord(b);
    return ord_max_first(a.ord, ob) ? a : '{t: b, ord: ob};
  endfunction

  // ---- S7: decisions, du * t_new, position at plane --------------------------------------------
  f24_pair_t uv7;
  f24_pair_t duv7;
  tmin_t     tm7;
  tval_t     t_new7;
  f24_t      dun_x, dun_y, posp_x, posp_y;
  logic      inside7, leaf7;
  act_t      act7;
  assign uv7     = uv_q[sl[7]];
  assign duv7    = duv_q[sl[7]];
  assign tm7     = tmin_q[sl[7]];
  assign t_new7  = t_new_q[sl[7]];
  assign inside7 = ord_lt(t_new7.ord, tm7.tmin.ord);
  assign leaf7   = (node_q[sl[7]].k == '0);
  assign act7    = '{is_hit: inside7 && leaf7, down: inside7 && !leaf7,
                     miss: !inside7 && tm7.miss_pre};
  f24_mul u_dun_x (.clk_i, .en_i(ok_q[7] && inside7), .a_i(duv7.u), .b_i(t_new7.t), .y_o(dun_x));
  f24_mul u_dun_y (.clk_i, .en_i(ok_q[7] && inside7), .a_i(duv7.v), .b_i(t_new7.t), .y_o(dun_y));
  logic posp_en;  // S7 - S8 hold a pass of the selective level-up whose height read returned data
  assign posp_en = sel_up && (ok_q[7] || ok_q[8]);
  f24_add u_posp_x (.clk_i, .en_i(posp_en), .a_i(uv7.u), .b_i(dup_x), .y_o(posp_x));
  f24_add u_posp_y (.clk_i, .en_i(posp_en), .a_i(uv7.v), .b_i(dup_y), .y_o(posp_y));

  // ---- S8: position at t_new, floor(position at t_end) -----------------------------------------
  f24_pair_t uv8;
  f24_t posn_x, posn_y;
  logic signed [IDX_W-1:0] ie_x, ie_y;
  logic unused_sat_ex, unused_sat_ey;
  assign uv8 = uv_q[sl[8]];
  f24_add u_posn_x (.clk_i, .en_i(in_q[8] || in_q[9]), .a_i(uv8.u), .b_i(dun_x), .y_o(posn_x));
  f24_add u_posn_y (.clk_i, .en_i(in_q[8] || in_q[9]), .a_i(uv8.v), .b_i(dun_y), .y_o(posn_y));
  f24_to_index #(.W(IDX_W)) u_ie_x (.clk_i, .en_i(xor_desc && dn_q[8]),
    .a_i(dir_q[sl[8]].sx.mv ? pose_x : uv8.u), .idx_o(ie_x), .sat_o(unused_sat_ex));
  f24_to_index #(.W(IDX_W)) u_ie_y (.clk_i, .en_i(xor_desc && dn_q[8]),
    .a_i(dir_q[sl[8]].sy.mv ? pose_y : uv8.v), .idx_o(ie_y), .sat_o(unused_sat_ey));

  // ---- S9: floor(position at plane) ------------------------------------------------------------
  f24_pair_t uv9;
  logic signed [IDX_W-1:0] ip_x, ip_y;
  logic unused_sat_px, unused_sat_py;
  assign uv9 = uv_q[sl[9]];
  f24_to_index #(.W(IDX_W)) u_ip_x (.clk_i, .en_i(sel_up && ok_q[9] && !in_q[9]),
    .a_i(dir_q[sl[9]].sx.mv ? posp_x : uv9.u), .idx_o(ip_x), .sat_o(unused_sat_px));
  f24_to_index #(.W(IDX_W)) u_ip_y (.clk_i, .en_i(sel_up && ok_q[9] && !in_q[9]),
    .a_i(dir_q[sl[9]].sy.mv ? posp_y : uv9.v), .idx_o(ip_y), .sat_o(unused_sat_py));

  // ---- S10: floor(position at t_new) ----------------------------------------------------------
  f24_pair_t uv10;
  dirs_t     d10;
  logic signed [IDX_W-1:0] in_x, in_y;
  logic unused_sat_nx, unused_sat_ny;
  assign uv10 = uv_q[sl[10]];
  assign d10  = dir_q[sl[10]];
  f24_to_index #(.W(IDX_W)) u_in_x (.clk_i, .en_i(dn_q[10]),
    .a_i(d10.sx.mv ? posn_x : uv10.u), .idx_o(in_x), .sat_o(unused_sat_nx));
  f24_to_index #(.W(IDX_W)) u_in_y (.clk_i, .en_i(dn_q[10]),
    .a_i(d10.sy.mv ? posn_y : uv10.v), .idx_o(in_y), .sat_o(unused_sat_ny));

  // ---- S10: crossing (neighbour, level-up); S11: descent level --------------------------------
  // The decisions themselves (traverse_pkg::level_cross, level_descend) are made where their
  // results are registered (cross_q, nk_q, below), only for the passes that use them.
  node_t   n10, n11;
  exit_t   ex10;
  /* verilator lint_off UNUSEDSIGNAL */  // the crossing reads prev_cross, the descent crossed
  status_t st10, st11;
  /* verilator lint_on UNUSEDSIGNAL */
  idx_pair_t ie11;
  tval_t     t10;
  assign n10  = node_q[sl[10]];
  assign ex10 = exit_q[sl[10]];
  assign st10 = stat_q[sl[10]];
  assign n11  = node_q[sl[11]];
  assign st11 = stat_q[sl[11]];
  assign ie11 = ie_q[sl[11]];
  assign t10     = t_q[sl[10]];


  // ---- S12: child estimate, its entry / exit boundaries, locate's three candidates -----------
  sidx_t            iax_q, iay_q;  // floor(position at t_new), registered S11 -> S12
  node_t            n12;
  dirs_t            d12;
  logic [LVL_W-1:0] nk12, dd;
  sidx_t            c12x, c12y, lox, hix, loy, hiy, stepx, stepy;
  locate_t          loc12x, loc12y;
  assign n12   = node_q[sl[12]];
  assign d12   = dir_q[sl[12]];
  assign nk12  = nk_q[sl[12]];
  assign dd    = n12.k - nk12;
  assign lox   = sidx_t'(n12.cx) <<< dd;
  assign hix   = ((sidx_t'(n12.cx) + sidx_t'(1)) <<< dd) - sidx_t'(1);
  assign loy   = sidx_t'(n12.cy) <<< dd;
  assign hiy   = ((sidx_t'(n12.cy) + sidx_t'(1)) <<< dd) - sidx_t'(1);
  assign c12x  = clip_idx(iax_q >>> nk12, lox, hix);
  assign c12y  = clip_idx(iay_q >>> nk12, loy, hiy);
  assign stepx = dir_val(d12.sx);
  assign stepy = dir_val(d12.sy);
  assign loc12x = '{back: CELL_W'(clip_idx(c12x - stepx, lox, hix)), est: CELL_W'(c12x),
                    fwd: CELL_W'(clip_idx(c12x + stepx, lox, hix))};
  assign loc12y = '{back: CELL_W'(clip_idx(c12y - stepy, loy, hiy)), est: CELL_W'(c12y),
                    fwd: CELL_W'(clip_idx(c12y + stepy, loy, hiy))};

  f24_t ben_x, bex_x, ben_y, bex_y;
  f24_from_int #(.W(IDX_W)) u_ben_x (.clk_i, .en_i(dn_q[12]),
    .k_i(IDX_W'((c12x + sidx_t'(d12.sx.mv && d12.sx.neg)) <<< nk12)), .y_o(ben_x));
  f24_from_int #(.W(IDX_W)) u_bex_x (.clk_i, .en_i(dn_q[12]),
    .k_i(IDX_W'((c12x + sidx_t'(d12.sx.mv && !d12.sx.neg)) <<< nk12)), .y_o(bex_x));
  f24_from_int #(.W(IDX_W)) u_ben_y (.clk_i, .en_i(dn_q[12]),
    .k_i(IDX_W'((c12y + sidx_t'(d12.sy.mv && d12.sy.neg)) <<< nk12)), .y_o(ben_y));
  f24_from_int #(.W(IDX_W)) u_bex_y (.clk_i, .en_i(dn_q[12]),
    .k_i(IDX_W'((c12y + sidx_t'(d12.sy.mv && !d12.sy.neg)) <<< nk12)), .y_o(bex_y));

  // ---- S13, S15: crossing times of the child's boundaries --------------------------------------
  f24_pair_t uv13;
  f24_pair_t inv15;
  f24_t      den_x, dex_x, den_y, dex_y, ten_x, tex_x, ten_y, tex_y;
  assign uv13  = uv_q[sl[13]];
  assign inv15 = inv_q[sl[15]];
  logic bd_en;  // S13 - S14 hold a descent
  assign bd_en = dn_q[13] || dn_q[14];
  f24_add u_den_x (.clk_i, .en_i(bd_en), .a_i(ben_x), .b_i(f24_neg(uv13.u)), .y_o(den_x));
  f24_add u_dex_x (.clk_i, .en_i(bd_en), .a_i(bex_x), .b_i(f24_neg(uv13.u)), .y_o(dex_x));
  f24_add u_den_y (.clk_i, .en_i(bd_en), .a_i(ben_y), .b_i(f24_neg(uv13.v)), .y_o(den_y));
  f24_add u_dex_y (.clk_i, .en_i(bd_en), .a_i(bex_y), .b_i(f24_neg(uv13.v)), .y_o(dex_y));
  f24_mul u_ten_x (.clk_i, .en_i(dn_q[15]), .a_i(den_x), .b_i(inv15.u), .y_o(ten_x));
  f24_mul u_tex_x (.clk_i, .en_i(dn_q[15]), .a_i(dex_x), .b_i(inv15.u), .y_o(tex_x));
  f24_mul u_ten_y (.clk_i, .en_i(dn_q[15]), .a_i(den_y), .b_i(inv15.v), .y_o(ten_y));
  f24_mul u_tex_y (.clk_i, .en_i(dn_q[15]), .a_i(dex_y), .b_i(inv15.v), .y_o(tex_y));

  // ---- S16: next state -----------------------------------------------------------------------
  // locate's correction: the cell whose crossing times bracket t (cells are half-open in t).
  function automatic logic [CELL_W-1:0] correct(input locate_t c, input f24_ord_t t_entry,
                                                input f24_ord_t t_exit, input f24_ord_t t);
    return ord_lt(t, t_entry) ? c.back : ord_le(t_exit, t) ? c.fwd : c.est;
  endfunction

  /* verilator lint_off UNUSEDSIGNAL */  // a live ray has no final flag (hit, ...) set: not read
  status_t st16;
  /* verilator lint_on UNUSEDSIGNAL */
  status_t nst16;
  act_t    act16;
  cross_node_t x16;
  tval_t   t_new16;
  logic [ITER_W-1:0] it1;
  logic live16, err16, iter16, hit16, miss16, down16, cross16, cap16;
  assign st16    = stat_q[sl[16]];
  assign act16   = act_q[sl[16]];
  assign x16     = cross_q[sl[16]];
  assign t_new16 = t_new_q[sl[16]];
  assign it1     = st16.iters + ITER_W'(1);
  // A ray finished earlier (waiting for room in the result FIFO) is left untouched, and so is
  // one whose lookup missed in the cache (same state, round again).
  assign live16  = v_q[16] && !st16.done;
  assign err16   = live16 && err_q[16];
  assign iter16  = live16 && !err_q[16] && ok_q[16];
  assign hit16   = iter16 && act16.is_hit;
  assign miss16  = iter16 && !act16.is_hit && act16.miss;
  assign down16  = iter16 && !act16.is_hit && !act16.miss && act16.down;
  assign cross16 = iter16 && !act16.is_hit && !act16.miss && !act16.down;
  assign cap16   = iter16 && !act16.is_hit && !act16.miss && (it1 >= cfg_i.iter_cap);
  // (written for a live ray only, which has none of the final flags set yet)
  assign nst16   = '{crossed:    st16.crossed || cross16,
                     prev_cross: cross16 ? !x16.up : (st16.prev_cross && !down16),
                     done:       err16 || hit16 || miss16 || cap16,
                     hit:        hit16,
                     invalid:    1'b0,
                     capped:     cap16,
                     err:        err16,
                     iters:      iter16 ? it1 : st16.iters};

  assign st_iter_o  = iter16;
  assign st_down_o  = down16;
  assign st_cross_o = cross16;
  assign st_up_o    = cross16 && x16.up;

  // ---- S17: retire, merge ----------------------------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // the tail reads the result flags only
  status_t st17;
  /* verilator lint_on UNUSEDSIGNAL */
  logic    retire, bypass, admit;
  assign st17   = stat_q[sl[D-1]];
  assign retire = v_q[D-1] && st17.done && !res_full_i;
  // A ray that setup already finished (invalid, or never enters the map) goes straight to the
  // result FIFO when the tail does not use it this clock.
  assign bypass = !retire && new_valid_i && new_ray_i.done && !res_full_i;
  assign admit  = new_valid_i && !new_ray_i.done && (!v_q[D-1] || retire);

  assign new_pop_o  = bypass || admit;
  assign res_push_o = retire || bypass;
  assign res_id_o   = retire ? id_q[sl[D-1]] : new_id_i;
  assign res_o      = retire ? '{t: t_q[sl[D-1]].t, u: uv_q[sl[D-1]].u, v: uv_q[sl[D-1]].v,
                                 hit: st17.hit, invalid: st17.invalid, capped: st17.capped,
                                 err: st17.err, iters: st17.iters}
                             : '{t: new_ray_i.t, u: new_ray_i.u0, v: new_ray_i.v0,
                                 hit: new_ray_i.hit, invalid: new_ray_i.invalid,
                                 capped: new_ray_i.capped, err: new_ray_i.err,
                                 iters: new_ray_i.iters};

  // ---- ring and slot table -------------------------------------------------------------------
  // S17 -> S0: the ray re-circulates (priority), or a new ray fills the bubble.
  always_ff @(posedge clk_i) begin
    if (!rst_ni) v_q <= '0;
    else         v_q <= {v_q[D-2:0], (v_q[D-1] && !retire) || admit};
  end

  always_ff @(posedge clk_i) begin
    ok_q  <= {ok_q[15:4], ok3};
    err_q <= {err_q[15:4], err3};
    in_q  <= {in_q[9:8], ok_q[7] && inside7};
    dn_q  <= {dn_q[14:8], ok_q[7] && act7.down};
    lv_q  <= {lv_q[1], v_q[0] && !stat_q[sl[0]].done};
  end

  always_ff @(posedge clk_i) begin
    // S17: a new ray enters its slot's entry (that slot is in S0 next clock).
    if (admit) begin
      id_q[sl[D-1]]   <= new_id_i;
      uv_q[sl[D-1]]   <= '{u: new_ray_i.u0, v: new_ray_i.v0};
      duv_q[sl[D-1]]  <= '{u: new_ray_i.du, v: new_ray_i.dv};
      inv_q[sl[D-1]]  <= '{u: new_ray_i.inv_du, v: new_ray_i.inv_dv};
      dir_q[sl[D-1]]  <= '{sx: new_ray_i.sx, sy: new_ray_i.sy};
      tmap_q[sl[D-1]] <= new_ray_i.t_map;
      node_q[sl[D-1]] <= '{k: new_ray_i.k, cx: new_ray_i.cx, cy: new_ray_i.cy};
      t_q[sl[D-1]]    <= '{t: new_ray_i.t, ord: f24_ord(new_ray_i.t)};
      stat_q[sl[D-1]] <= '{crossed: new_ray_i.crossed, prev_cross: new_ray_i.prev_cross,
                           done: new_ray_i.done, hit: new_ray_i.hit,
                           invalid: new_ray_i.invalid, capped: new_ray_i.capped,
                           err: new_ray_i.err, iters: new_ray_i.iters};
    end
    // S16: the next state (only a live ray whose lookup answered changes).
    if (err16 || iter16) stat_q[sl[16]] <= nst16;
    if (hit16 || down16) t_q[sl[16]] <= t_new16;
    if (cross16) begin
      t_q[sl[16]]    <= xt_q[sl[16]];
      node_q[sl[16]] <= '{k: x16.k, cx: x16.cx, cy: x16.cy};
    end
    if (down16) node_q[sl[16]] <= '{k:  nk_q[sl[16]],
                                    cx: correct(locx_q[sl[16]], f24_ord(ten_x), f24_ord(tex_x),
                                                t_new16.ord),
                                    cy: correct(locy_q[sl[16]], f24_ord(ten_y), f24_ord(tex_y),
                                                t_new16.ord)};
    if (hit16) uv_q[sl[16]] <= pos_q[sl[16]];
    // What this pass computes for its later stages.
    // (only the passes whose height read returned data: the others use none of it)
    if (ok_q[4]) exit_q[sl[4]]  <= exit_of(d4.sx.mv ? tx_raw : F24_POS_INF,
                                           d4.sy.mv ? ty_raw : F24_POS_INF);
    if (ok_q[5]) tmin_q[sl[5]]  <= tmin5_d;
    if (ok_q[6]) t_new_q[sl[6]] <= t_max(t_q[sl[6]], plane);
    if (ok_q[7]) act_q[sl[7]]   <= act7;
    // (only the passes that use them later: XOR descents, crossings, hits, descents)
    if (dn_q[9] && xor_desc) ie_q[sl[9]] <= '{x: ie_x, y: ie_y};
    if (ok_q[10] && !in_q[10]) begin
      xt_q[sl[10]]    <= ord_max_first(t10.ord, ex10.te.ord) ? t10 : ex10.te;
      cross_q[sl[10]] <= level_cross(cfg_i.policy.level_up, cfg_i.n, n10.k, n10.cx, n10.cy,
                                     ex10.eqx, ex10.eqy, d10.sx, d10.sy, st10.prev_cross, ip_x,
                                     ip_y);
    end
    if (in_q[10])      pos_q[sl[10]]  <= '{u: posn_x, v: posn_y};
    if (dn_q[11])      nk_q[sl[11]]   <= level_descend(cfg_i.policy.descent,
                                                       cfg_i.policy.levels, n11.k, n11.cx,
                                                       n11.cy, st11.crossed, in_x, in_y, ie11.x,
                                                       ie11.y);
    if (dn_q[12]) begin
      locx_q[sl[12]] <= loc12x;
      locy_q[sl[12]] <= loc12y;
    end
  end

  always_ff @(posedge clk_i) begin
    if (dn_q[11]) begin
      iax_q <= sidx_t'(in_x);
      iay_q <= sidx_t'(in_y);
    end
  end

  always_comb begin
    busy_o = 5'($countones(v_q));
  end

`ifndef SYNTHESIS
  // A response only ever answers a request made LOOKUP_LAT clocks earlier.
  logic lk_d1_q, lk_d2_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) {lk_d1_q, lk_d2_q} <= '0;
    else         {lk_d2_q, lk_d1_q} <= {lk_d1_q, lk_valid_o};
  end
  no_spurious_response: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                         rs_valid_i |-> lk_d2_q)
    else $error("traverse_loop: height response without a request");
  new_ray_only_in_bubble: assert property (@(posedge clk_i) disable iff (!rst_ni)
                                           admit |-> (!v_q[D-1] || retire));
  // A ray that is not done has none of the final flags (S16 relies on it).
  live_ray_has_no_result: assert property (@(posedge clk_i) disable iff (!rst_ni)
      live16 |-> !(st16.hit || st16.invalid || st16.capped || st16.err));
`endif

endmodule
