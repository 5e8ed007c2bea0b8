// traverse_loop: the second mode of the traverse unit, the iterative search of model/traverse.py
// (the body of _trace's `while act.size` loop, for one ray per pass).
//
// A ring of LOOP_DEPTH = 18 stage registers; every stage holds one ray slot (valid bit + record)
// and every slot advances one stage per clock (the loop never stalls: all float units run with
// en_i = 1).  One pass round the ring = one iteration = one height lookup.  At the ring's tail
// (S17) a finished ray leaves for the result FIFO; a slot that is then empty takes a new ray from
// setup (re-circulating rays have priority: new rays only fill bubbles).
//
// Stage schedule (a unit "a -> b" takes operands in Sa and delivers in Sb):
//   S0   height address base + off[k] + (cy * side_k + cx) * bytes  -> lk_* registers (S1)
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
//                                                                   f24_to_index S10 -> S11
//   S11  descent: new level (one; multi: `levels` until the first crossing; XOR of the ends)
//   S12  child estimate floor(p) >> k', clip; its entry / exit      f24_from_int S12 -> S13
//   S13  boundary - u0                                              f24_add      S13 -> S15
//   S15  (boundary - u0) * (1/du)                                   f24_mul      S15 -> S16
//   S16  locate's correction; next state (hit / miss / down / cross / lookup miss / cap)
//   S17  retire to the result FIFO, or merge with a new ray, -> S0
// Positions on an axis that does not move are u0 itself (the model's np.where(s != 0, p, p0)).
// Float units per axis pair: 6 f24_from_int, 13 f24_add, 12 f24_mul, 6 f24_to_index, 2
// f24_from_unorm.  Three positions per axis are computed every pass (at t_end for the XOR descent,
// at the plane for selective's P1, at t_new for locate and the hit); the ring is 18 deep (the
// paper's is 15) because the descent's locate (position, floor, two crossing times, correction)
// follows t_new as a dependent chain of about 9 clocks.
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

  localparam int unsigned D = 18;  // LOOP_DEPTH: stages S0 .. S17

  typedef struct packed {
    logic [ID_W-1:0]  id;
    ray_t             r;
    logic             ok;                    // S4+: the height read returned data
    logic             rd_err;                // S4+: the height read returned an error
    f24_t             te;                    // S5+: t_exit = min(tx, ty)
    logic             eqx, eqy;              // S5+: tx == t_exit, ty == t_exit
    f24_t             tmin;                  // S6+: min(t_exit, t_map)
    logic             miss_pre;              // S6+: t_map <= t_exit
    f24_t             t_new;                 // S7+: max(t, plane)
    logic             is_hit, down, miss;    // S8+ (cross = none of them)
    sidx_t            ibx, iby;              // S10+: floor(position at t_end)
    f24_t             pu, pv;                // S11+: position at t_new
    logic [LVL_W-1:0] xk;                    // S11+: crossing: new level
    logic [CELL_W-1:0] xcx, xcy;             // S11+: crossing: new cell
    f24_t             xt;                    // S11+: crossing: max(t, t_exit)
    logic             up;                    // S11+: crossing went up a level
    sidx_t            iax, iay;              // S12+: floor(position at t_new)
    logic [LVL_W-1:0] nk;                    // S12+: descent: new level
    sidx_t            dcx, dcy;              // S13+: descent: child estimate
    sidx_t            lox, hix, loy, hiy;    // S13+: descent: the children's range at nk
  } slot_t;

  logic  v_q [D];
  slot_t p_q [D];
  slot_t p_d [D];
  logic  v0_d;

  // ---- S0: height address, exit boundaries -----------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s0;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [ADDR_W-1:0] texel;
  logic [LVL_W-1:0]  sh0;
  assign s0  = p_q[0];
  assign sh0 = cfg_i.n - s0.r.k;  // log2 of the row pitch of level k
  assign texel = ((ADDR_W'(s0.r.cy) << sh0) + ADDR_W'(s0.r.cx)) << cfg_i.bits16;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) lk_valid_o <= 1'b0;
    else         lk_valid_o <= v_q[0] && !s0.r.done;
  end
  always_ff @(posedge clk_i) begin
    lk_addr_o <= cfg_i.base + cfg_i.level_off[s0.r.k] + texel;
    lk_wide_o <= cfg_i.bits16;
  end

  f24_t bx_f, by_f;
  f24_from_int #(.W(IDX_W)) u_bx (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((sidx_t'(s0.r.cx) + sidx_t'(s0.r.sx.mv && !s0.r.sx.neg)) <<< s0.r.k)), .y_o(bx_f));
  f24_from_int #(.W(IDX_W)) u_by (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((sidx_t'(s0.r.cy) + sidx_t'(s0.r.sy.mv && !s0.r.sy.neg)) <<< s0.r.k)), .y_o(by_f));

  // ---- S1 ------------------------------------------------------------------------------------
  f24_t dx_f, dy_f;
  f24_add u_dx (.clk_i, .en_i(1'b1), .a_i(bx_f), .b_i(f24_neg(p_q[1].r.u0)), .y_o(dx_f));
  f24_add u_dy (.clk_i, .en_i(1'b1), .a_i(by_f), .b_i(f24_neg(p_q[1].r.v0)), .y_o(dy_f));

  // ---- S3: the height arrives ------------------------------------------------------------------
  f24_t h8, h16, tx_raw, ty_raw;
  f24_from_unorm #(.W(8))  u_h8  (.clk_i, .en_i(1'b1), .k_i(rs_data_i[7:0]), .y_o(h8));
  f24_from_unorm #(.W(16)) u_h16 (.clk_i, .en_i(1'b1), .k_i(rs_data_i), .y_o(h16));
  f24_mul u_tx (.clk_i, .en_i(1'b1), .a_i(dx_f), .b_i(p_q[3].r.inv_du), .y_o(tx_raw));
  f24_mul u_ty (.clk_i, .en_i(1'b1), .a_i(dy_f), .b_i(p_q[3].r.inv_dv), .y_o(ty_raw));

  // ---- S4: plane, t_exit -----------------------------------------------------------------------
  f24_t plane, tx, ty, te;
  f24_add u_plane (.clk_i, .en_i(1'b1), .a_i(F24_ONE), .b_i(f24_neg(cfg_i.bits16 ? h16 : h8)),
                   .y_o(plane));
  assign tx = p_q[4].r.sx.mv ? tx_raw : F24_POS_INF;
  assign ty = p_q[4].r.sy.mv ? ty_raw : F24_POS_INF;
  assign te = f24_min(tx, ty);

  // ---- S5: t_end -------------------------------------------------------------------------------
  f24_t tmin5, t_end, due_x, due_y;
  assign tmin5 = f24_min(p_q[5].te, p_q[5].r.t_map);
  assign t_end = f24_min(tmin5, F24_ONE);
  f24_mul u_due_x (.clk_i, .en_i(1'b1), .a_i(p_q[5].r.du), .b_i(t_end), .y_o(due_x));
  f24_mul u_due_y (.clk_i, .en_i(1'b1), .a_i(p_q[5].r.dv), .b_i(t_end), .y_o(due_y));

  // ---- S6: t_new, position at t_end, du * plane ------------------------------------------------
  f24_t pose_x, pose_y, dup_x, dup_y;
  f24_add u_pose_x (.clk_i, .en_i(1'b1), .a_i(p_q[6].r.u0), .b_i(due_x), .y_o(pose_x));
  f24_add u_pose_y (.clk_i, .en_i(1'b1), .a_i(p_q[6].r.v0), .b_i(due_y), .y_o(pose_y));
  f24_mul u_dup_x (.clk_i, .en_i(1'b1), .a_i(p_q[6].r.du), .b_i(plane), .y_o(dup_x));
  f24_mul u_dup_y (.clk_i, .en_i(1'b1), .a_i(p_q[6].r.dv), .b_i(plane), .y_o(dup_y));

  // ---- S7: decisions, du * t_new, position at plane --------------------------------------------
  f24_t dun_x, dun_y, posp_x, posp_y;
  logic inside7;
  assign inside7 = f24_lt(p_q[7].t_new, p_q[7].tmin);
  f24_mul u_dun_x (.clk_i, .en_i(1'b1), .a_i(p_q[7].r.du), .b_i(p_q[7].t_new), .y_o(dun_x));
  f24_mul u_dun_y (.clk_i, .en_i(1'b1), .a_i(p_q[7].r.dv), .b_i(p_q[7].t_new), .y_o(dun_y));
  f24_add u_posp_x (.clk_i, .en_i(1'b1), .a_i(p_q[7].r.u0), .b_i(dup_x), .y_o(posp_x));
  f24_add u_posp_y (.clk_i, .en_i(1'b1), .a_i(p_q[7].r.v0), .b_i(dup_y), .y_o(posp_y));

  // ---- S8: position at t_new, floor(position at t_end) -----------------------------------------
  f24_t posn_x, posn_y;
  logic signed [IDX_W-1:0] ie_x, ie_y;
  logic unused_sat_ex, unused_sat_ey;
  f24_add u_posn_x (.clk_i, .en_i(1'b1), .a_i(p_q[8].r.u0), .b_i(dun_x), .y_o(posn_x));
  f24_add u_posn_y (.clk_i, .en_i(1'b1), .a_i(p_q[8].r.v0), .b_i(dun_y), .y_o(posn_y));
  f24_to_index #(.W(IDX_W)) u_ie_x (.clk_i, .en_i(1'b1),
    .a_i(p_q[8].r.sx.mv ? pose_x : p_q[8].r.u0), .idx_o(ie_x), .sat_o(unused_sat_ex));
  f24_to_index #(.W(IDX_W)) u_ie_y (.clk_i, .en_i(1'b1),
    .a_i(p_q[8].r.sy.mv ? pose_y : p_q[8].r.v0), .idx_o(ie_y), .sat_o(unused_sat_ey));

  // ---- S9: floor(position at plane) ------------------------------------------------------------
  logic signed [IDX_W-1:0] ip_x, ip_y;
  logic unused_sat_px, unused_sat_py;
  f24_to_index #(.W(IDX_W)) u_ip_x (.clk_i, .en_i(1'b1),
    .a_i(p_q[9].r.sx.mv ? posp_x : p_q[9].r.u0), .idx_o(ip_x), .sat_o(unused_sat_px));
  f24_to_index #(.W(IDX_W)) u_ip_y (.clk_i, .en_i(1'b1),
    .a_i(p_q[9].r.sy.mv ? posp_y : p_q[9].r.v0), .idx_o(ip_y), .sat_o(unused_sat_py));

  // ---- S10: crossing and level-up; floor(position at t_new) ------------------------------------
  logic signed [IDX_W-1:0] in_x, in_y;
  logic unused_sat_nx, unused_sat_ny;
  f24_to_index #(.W(IDX_W)) u_in_x (.clk_i, .en_i(1'b1),
    .a_i(p_q[10].r.sx.mv ? posn_x : p_q[10].r.u0), .idx_o(in_x), .sat_o(unused_sat_nx));
  f24_to_index #(.W(IDX_W)) u_in_y (.clk_i, .en_i(1'b1),
    .a_i(p_q[10].r.sy.mv ? posn_y : p_q[10].r.v0), .idx_o(in_y), .sat_o(unused_sat_ny));

  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s10;
  /* verilator lint_on UNUSEDSIGNAL */
  sidx_t c10x, c10y, nx, ny, p1x, p1y, dfx, dfy, diff;
  logic  parent_changed, cup;
  always_comb begin
    s10  = p_q[10];
    c10x = sidx_t'(s10.r.cx);
    c10y = sidx_t'(s10.r.cy);
    nx   = c10x + (s10.eqx ? dir_val(s10.r.sx) : '0);
    ny   = c10y + (s10.eqy ? dir_val(s10.r.sy) : '0);
    parent_changed = ((nx >>> 1) != (c10x >>> 1)) || ((ny >>> 1) != (c10y >>> 1));
    // selective: P1 (where the ray meets this node's plane), in cells of level k
    p1x  = sidx_t'(ip_x) >>> s10.r.k;
    p1y  = sidx_t'(ip_y) >>> s10.r.k;
    dfx  = (p1x >= c10x) ? p1x - c10x : c10x - p1x;
    dfy  = (p1y >= c10y) ? p1y - c10y : c10y - p1y;
    diff = (dfx > dfy) ? dfx : dfy;
    case (cfg_i.policy.level_up)
      UP_TEVS:      cup = parent_changed;
      UP_DROBOT:    cup = 1'b1;
      UP_SELECTIVE: cup = parent_changed && (diff != sidx_t'(1));
      UP_COHERENT:  cup = parent_changed && s10.r.prev_cross;
      default:      cup = 1'b0;
    endcase
    cup = cup && (s10.r.k < cfg_i.n);
  end

  // ---- S11: descent level ------------------------------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s11;
  /* verilator lint_on UNUSEDSIGNAL */
  sidx_t lo0x, hi0x, lo0y, hi0y, ax, bx, ay, by;
  logic [15:0] xr;
  logic [4:0]  step, nk0, bl;
  logic [LVL_W-1:0] nk_xor, nk11;
  always_comb begin
    s11  = p_q[11];
    lo0x = sidx_t'(s11.r.cx) <<< s11.r.k;
    hi0x = ((sidx_t'(s11.r.cx) + sidx_t'(1)) <<< s11.r.k) - sidx_t'(1);
    lo0y = sidx_t'(s11.r.cy) <<< s11.r.k;
    hi0y = ((sidx_t'(s11.r.cy) + sidx_t'(1)) <<< s11.r.k) - sidx_t'(1);
    ax   = clip_idx(sidx_t'(in_x), lo0x, hi0x);
    bx   = clip_idx(s11.ibx, lo0x, hi0x);
    ay   = clip_idx(sidx_t'(in_y), lo0y, hi0y);
    by   = clip_idx(s11.iby, lo0y, hi0y);
    xr   = (16'(ax ^ bx) > 16'(ay ^ by)) ? 16'(ax ^ bx) : 16'(ay ^ by);
    // (b): `levels` levels per descent until the first crossing, then one (never below 0)
    if (s11.r.crossed)                         step = 5'd1;
    else if (s11.r.k < 4'(cfg_i.policy.levels)) step = 5'(s11.r.k);
    else                                       step = 5'(cfg_i.policy.levels);
    nk0  = 5'(s11.r.k) - step;                // k >= 1 for a descending ray
    bl   = bitlen16(xr);
    nk_xor = LVL_W'((bl < nk0) ? bl : nk0);   // down to the lowest node holding the rest
    case (cfg_i.policy.descent)
      DESC_MULTI: nk11 = LVL_W'(nk0);
      DESC_XOR:   nk11 = nk_xor;
      default:    nk11 = s11.r.k - LVL_W'(1);
    endcase
    if (s11.r.k == '0) nk11 = '0;              // not a descending ray: keep in range
  end

  // ---- S12: child estimate and its entry / exit boundaries -------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s12;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [LVL_W-1:0] dd;
  sidx_t c12x, c12y, lox, hix, loy, hiy;
  always_comb begin
    s12  = p_q[12];
    dd   = s12.r.k - s12.nk;
    lox  = sidx_t'(s12.r.cx) <<< dd;
    hix  = ((sidx_t'(s12.r.cx) + sidx_t'(1)) <<< dd) - sidx_t'(1);
    loy  = sidx_t'(s12.r.cy) <<< dd;
    hiy  = ((sidx_t'(s12.r.cy) + sidx_t'(1)) <<< dd) - sidx_t'(1);
    c12x = clip_idx(s12.iax >>> s12.nk, lox, hix);
    c12y = clip_idx(s12.iay >>> s12.nk, loy, hiy);
  end

  f24_t ben_x, bex_x, ben_y, bex_y;
  f24_from_int #(.W(IDX_W)) u_ben_x (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12x + sidx_t'(s12.r.sx.mv && s12.r.sx.neg)) <<< s12.nk)), .y_o(ben_x));
  f24_from_int #(.W(IDX_W)) u_bex_x (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12x + sidx_t'(s12.r.sx.mv && !s12.r.sx.neg)) <<< s12.nk)), .y_o(bex_x));
  f24_from_int #(.W(IDX_W)) u_ben_y (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12y + sidx_t'(s12.r.sy.mv && s12.r.sy.neg)) <<< s12.nk)), .y_o(ben_y));
  f24_from_int #(.W(IDX_W)) u_bex_y (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12y + sidx_t'(s12.r.sy.mv && !s12.r.sy.neg)) <<< s12.nk)), .y_o(bex_y));

  // ---- S13, S15: crossing times of the child's boundaries --------------------------------------
  f24_t den_x, dex_x, den_y, dex_y, ten_x, tex_x, ten_y, tex_y;
  f24_add u_den_x (.clk_i, .en_i(1'b1), .a_i(ben_x), .b_i(f24_neg(p_q[13].r.u0)), .y_o(den_x));
  f24_add u_dex_x (.clk_i, .en_i(1'b1), .a_i(bex_x), .b_i(f24_neg(p_q[13].r.u0)), .y_o(dex_x));
  f24_add u_den_y (.clk_i, .en_i(1'b1), .a_i(ben_y), .b_i(f24_neg(p_q[13].r.v0)), .y_o(den_y));
  f24_add u_dex_y (.clk_i, .en_i(1'b1), .a_i(bex_y), .b_i(f24_neg(p_q[13].r.v0)), .y_o(dex_y));
  f24_mul u_ten_x (.clk_i, .en_i(1'b1), .a_i(den_x), .b_i(p_q[15].r.inv_du), .y_o(ten_x));
  f24_mul u_tex_x (.clk_i, .en_i(1'b1), .a_i(dex_x), .b_i(p_q[15].r.inv_du), .y_o(tex_x));
  f24_mul u_ten_y (.clk_i, .en_i(1'b1), .a_i(den_y), .b_i(p_q[15].r.inv_dv), .y_o(ten_y));
  f24_mul u_tex_y (.clk_i, .en_i(1'b1), .a_i(dex_y), .b_i(p_q[15].r.inv_dv), .y_o(tex_y));

  // ---- S16: next state -----------------------------------------------------------------------
  // locate's correction: the cell whose crossing times bracket t (cells are half-open in t).
  function automatic sidx_t correct(input sidx_t c, input dir_t s, input f24_t t_entry,
                                    input f24_t t_exit, input f24_t t, input sidx_t lo,
                                    input sidx_t hi);
    sidx_t r;
    if (f24_lt(t, t_entry))      r = c - dir_val(s);
    else if (f24_le(t_exit, t))  r = c + dir_val(s);
    else                         r = c;
    return clip_idx(r, lo, hi);
  endfunction

  slot_t s16, n16;
  logic [ITER_W-1:0] it1;
  logic iter16, down16, cross16, up16;
  always_comb begin
    s16     = p_q[16];
    n16     = s16;
    it1     = s16.r.iters + ITER_W'(1);
    iter16  = 1'b0;
    down16  = 1'b0;
    cross16 = 1'b0;
    up16    = 1'b0;
    if (s16.r.done) begin
      // finished earlier, waiting for room in the result FIFO: untouched
    end else if (s16.rd_err) begin
      n16.r.done = 1'b1;
      n16.r.err  = 1'b1;
    end else if (s16.ok) begin
      iter16       = 1'b1;
      n16.r.iters  = it1;
      if (s16.is_hit) begin
        n16.r.done = 1'b1;
        n16.r.hit  = 1'b1;
        n16.r.t    = s16.t_new;
        n16.r.u0   = s16.pu;
        n16.r.v0   = s16.pv;
      end else if (s16.miss) begin
        n16.r.done = 1'b1;
      end else if (s16.down) begin
        down16          = 1'b1;
        n16.r.k         = s16.nk;
        n16.r.cx        = CELL_W'(correct(s16.dcx, s16.r.sx, ten_x, tex_x, s16.t_new,
                                          s16.lox, s16.hix));
        n16.r.cy        = CELL_W'(correct(s16.dcy, s16.r.sy, ten_y, tex_y, s16.t_new,
                                          s16.loy, s16.hiy));
        n16.r.t         = s16.t_new;
        n16.r.prev_cross = 1'b0;
      end else begin
        cross16          = 1'b1;
        up16             = s16.up;
        n16.r.k          = s16.xk;
        n16.r.cx         = s16.xcx;
        n16.r.cy         = s16.xcy;
        n16.r.t          = s16.xt;
        n16.r.crossed    = 1'b1;
        n16.r.prev_cross = !s16.up;
      end
      if (it1 >= cfg_i.iter_cap && !s16.is_hit && !s16.miss) begin
        n16.r.done   = 1'b1;
        n16.r.capped = 1'b1;
      end
    end
    // else: the lookup missed in the cache: same state, round again
  end

  assign st_iter_o  = v_q[16] && iter16;
  assign st_down_o  = v_q[16] && down16;
  assign st_cross_o = v_q[16] && cross16;
  assign st_up_o    = v_q[16] && up16;

  // ---- S17: retire, merge ----------------------------------------------------------------------
  slot_t s17;
  logic  retire, bypass, admit;
  assign s17    = p_q[D-1];
  assign retire = v_q[D-1] && s17.r.done && !res_full_i;
  // A ray that setup already finished (invalid, or never enters the map) goes straight to the
  // result FIFO when the tail does not use it this clock.
  assign bypass = !retire && new_valid_i && new_ray_i.done && !res_full_i;
  assign admit  = new_valid_i && !new_ray_i.done && (!v_q[D-1] || retire);

  assign new_pop_o  = bypass || admit;
  assign res_push_o = retire || bypass;
  assign res_id_o   = retire ? s17.id : new_id_i;
  assign res_o      = ray_result(retire ? s17.r : new_ray_i);
  assign v0_d       = (v_q[D-1] && !retire) || admit;

  // ---- stage registers -----------------------------------------------------------------------
  always_comb begin
    for (int s = 1; s < D; s++) p_d[s] = p_q[s-1];
    p_d[0] = s17;                            // re-circulates (priority) ...
    if (!(v_q[D-1] && !retire)) begin        // ... or a new ray fills the bubble
      p_d[0].id = new_id_i;
      p_d[0].r  = new_ray_i;
    end
    // S3 -> S4
    p_d[4].ok     = rs_valid_i && rs_hit_i && !rs_err_i;
    p_d[4].rd_err = rs_valid_i && rs_err_i;
    // S4 -> S5
    p_d[5].te  = te;
    p_d[5].eqx = f24_eq(tx, te);
    p_d[5].eqy = f24_eq(ty, te);
    // S5 -> S6
    p_d[6].tmin     = tmin5;
    p_d[6].miss_pre = f24_le(p_q[5].r.t_map, p_q[5].te);
    // S6 -> S7
    p_d[7].t_new = f24_max(p_q[6].r.t, plane);
    // S7 -> S8
    p_d[8].is_hit = inside7 && (p_q[7].r.k == '0);
    p_d[8].down   = inside7 && (p_q[7].r.k != '0);
    p_d[8].miss   = !inside7 && p_q[7].miss_pre;
    // S9 -> S10
    p_d[10].ibx = sidx_t'(ie_x);
    p_d[10].iby = sidx_t'(ie_y);
    // S10 -> S11
    p_d[11].pu  = posn_x;
    p_d[11].pv  = posn_y;
    p_d[11].xk  = s10.r.k + LVL_W'(cup);
    p_d[11].xcx = CELL_W'(cup ? (nx >>> 1) : nx);
    p_d[11].xcy = CELL_W'(cup ? (ny >>> 1) : ny);
    p_d[11].xt  = f24_max(s10.r.t, s10.te);
    p_d[11].up  = cup;
    // S11 -> S12
    p_d[12].iax = sidx_t'(in_x);
    p_d[12].iay = sidx_t'(in_y);
    p_d[12].nk  = nk11;
    // S12 -> S13
    p_d[13].dcx = c12x;
    p_d[13].dcy = c12y;
    p_d[13].lox = lox;
    p_d[13].hix = hix;
    p_d[13].loy = loy;
    p_d[13].hiy = hiy;
    // S16 -> S17
    p_d[17] = n16;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int s = 0; s < D; s++) v_q[s] <= 1'b0;
    end else begin
      v_q[0] <= v0_d;
      for (int s = 1; s < D; s++) v_q[s] <= v_q[s-1];
    end
  end

  always_ff @(posedge clk_i) begin
    for (int s = 0; s < D; s++) p_q[s] <= p_d[s];
  end

  always_comb begin
    busy_o = '0;
    for (int s = 0; s < D; s++) busy_o = busy_o + 5'(v_q[s]);
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
`endif

endmodule
