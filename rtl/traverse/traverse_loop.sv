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
//        (traverse_level_decide, crossing part)
//                                                                   f24_to_index S10 -> S11
//   S11  descent: new level (one; multi: `levels` until the first crossing; XOR of the ends)
//        (traverse_level_decide, descent part)
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

  // Stage registers, written in one always_ff (no copy of the whole ring in combinational logic).
  // A slot (the ray) goes round the whole ring; what one pass computes lives only from the stage
  // that computes it to the last one that reads it (arrays indexed by stage).
  typedef struct packed {
    logic [ID_W-1:0] id;
    ray_t            r;
  } slot_t;
  typedef struct packed {
    logic ok;                      // the height read returned data
    logic rd_err;                  // the height read returned an error
  } rd_t;
  typedef struct packed {
    f24_t te;                      // t_exit = min(tx, ty)
    logic eqx, eqy;                // tx == t_exit, ty == t_exit
  } exit_t;
  typedef struct packed {
    logic is_hit, down, miss;      // (cross = none of them)
  } act_t;
  typedef struct packed {
    f24_t              pu, pv;     // position at t_new
    logic [LVL_W-1:0]  xk;         // crossing: new level
    logic [CELL_W-1:0] xcx, xcy;   // crossing: new cell
    f24_t              xt;         // crossing: max(t, t_exit)
    logic              up;         // crossing went up a level
  } cross_t;
  typedef struct packed {
    sidx_t dcx, dcy;               // descent: child estimate
    sidx_t lox, hix, loy, hiy;     // descent: the children's range at nk
  } child_t;

  logic                    v_q        [D];
  slot_t                   p_q        [D];
  rd_t                     rd_q       [4:16];
  exit_t                   exit_q     [5:10];
  f24_t                    tmin_q     [6:7];    // min(t_exit, t_map)
  logic                    miss_pre_q [6:7];    // t_map <= t_exit
  f24_t                    t_new_q    [7:16];   // max(t, plane)
  act_t                    act_q      [8:16];
  logic signed [IDX_W-1:0] ibx_q      [10:11];  // floor(position at t_end)
  logic signed [IDX_W-1:0] iby_q      [10:11];
  cross_t                  cross_q    [11:16];
  sidx_t                   iax_q, iay_q;        // S12: floor(position at t_new)
  logic [LVL_W-1:0]        nk_q       [12:16];  // descent: new level
  child_t                  child_q    [13:16];
  logic                    v0_d;
  slot_t                   p0_d;

  // ---- S0: height address, exit boundaries -----------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s0;
  /* verilator lint_on UNUSEDSIGNAL */
  assign s0 = p_q[0];

  logic [ADDR_W-1:0] addr0;
  logic              wide0;
  traverse_addr u_addr (
    .base_i     (cfg_i.base),
    .level_off_i(cfg_i.level_off),
    .n_i        (cfg_i.n),
    .bits16_i   (cfg_i.bits16),
    .k_i        (s0.r.k),
    .cx_i       (s0.r.cx),
    .cy_i       (s0.r.cy),
    .addr_o     (addr0),
    .wide_o     (wide0)
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) lk_valid_o <= 1'b0;
    else         lk_valid_o <= v_q[0] && !s0.r.done;
  end
  always_ff @(posedge clk_i) begin
    lk_addr_o <= addr0;
    lk_wide_o <= wide0;
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
  assign tmin5 = f24_min(exit_q[5].te, p_q[5].r.t_map);
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
  assign inside7 = f24_lt(t_new_q[7], tmin_q[7]);
  f24_mul u_dun_x (.clk_i, .en_i(1'b1), .a_i(p_q[7].r.du), .b_i(t_new_q[7]), .y_o(dun_x));
  f24_mul u_dun_y (.clk_i, .en_i(1'b1), .a_i(p_q[7].r.dv), .b_i(t_new_q[7]), .y_o(dun_y));
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

  // ---- S10: floor(position at t_new) ----------------------------------------------------------
  logic signed [IDX_W-1:0] in_x, in_y;
  logic unused_sat_nx, unused_sat_ny;
  f24_to_index #(.W(IDX_W)) u_in_x (.clk_i, .en_i(1'b1),
    .a_i(p_q[10].r.sx.mv ? posn_x : p_q[10].r.u0), .idx_o(in_x), .sat_o(unused_sat_nx));
  f24_to_index #(.W(IDX_W)) u_in_y (.clk_i, .en_i(1'b1),
    .a_i(p_q[10].r.sy.mv ? posn_y : p_q[10].r.v0), .idx_o(in_y), .sat_o(unused_sat_ny));

  // ---- S10: crossing (neighbour, level-up); S11: descent level --------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s10;
  /* verilator lint_on UNUSEDSIGNAL */
  assign s10 = p_q[10];

  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s11;
  /* verilator lint_on UNUSEDSIGNAL */
  assign s11 = p_q[11];

  logic [LVL_W-1:0]  xk10, nk11;
  logic [CELL_W-1:0] xcx10, xcy10;
  logic              up10;
  traverse_level_decide u_level (
    .level_up_i  (cfg_i.policy.level_up),
    .n_i         (cfg_i.n),
    .xk_i        (s10.r.k),
    .xcx_i       (s10.r.cx),
    .xcy_i       (s10.r.cy),
    .eqx_i       (exit_q[10].eqx),
    .eqy_i       (exit_q[10].eqy),
    .sx_i        (s10.r.sx),
    .sy_i        (s10.r.sy),
    .prev_cross_i(s10.r.prev_cross),
    .p1x_i       (ip_x),
    .p1y_i       (ip_y),
    .xk_o        (xk10),
    .xcx_o       (xcx10),
    .xcy_o       (xcy10),
    .up_o        (up10),
    .descent_i   (cfg_i.policy.descent),
    .levels_i    (cfg_i.policy.levels),
    .dk_i        (s11.r.k),
    .dcx_i       (s11.r.cx),
    .dcy_i       (s11.r.cy),
    .crossed_i   (s11.r.crossed),
    .ax_i        (in_x),
    .ay_i        (in_y),
    .bx_i        (ibx_q[11]),
    .by_i        (iby_q[11]),
    .dk_o        (nk11)
  );

  // ---- S12: child estimate and its entry / exit boundaries -------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // a stage view: the stage reads only some fields
  slot_t s12;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [LVL_W-1:0] dd;
  sidx_t c12x, c12y, lox, hix, loy, hiy;
  always_comb begin
    s12  = p_q[12];
    dd   = s12.r.k - nk_q[12];
    lox  = sidx_t'(s12.r.cx) <<< dd;
    hix  = ((sidx_t'(s12.r.cx) + sidx_t'(1)) <<< dd) - sidx_t'(1);
    loy  = sidx_t'(s12.r.cy) <<< dd;
    hiy  = ((sidx_t'(s12.r.cy) + sidx_t'(1)) <<< dd) - sidx_t'(1);
    c12x = clip_idx(iax_q >>> nk_q[12], lox, hix);
    c12y = clip_idx(iay_q >>> nk_q[12], loy, hiy);
  end

  f24_t ben_x, bex_x, ben_y, bex_y;
  f24_from_int #(.W(IDX_W)) u_ben_x (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12x + sidx_t'(s12.r.sx.mv && s12.r.sx.neg)) <<< nk_q[12])), .y_o(ben_x));
  f24_from_int #(.W(IDX_W)) u_bex_x (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12x + sidx_t'(s12.r.sx.mv && !s12.r.sx.neg)) <<< nk_q[12])), .y_o(bex_x));
  f24_from_int #(.W(IDX_W)) u_ben_y (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12y + sidx_t'(s12.r.sy.mv && s12.r.sy.neg)) <<< nk_q[12])), .y_o(ben_y));
  f24_from_int #(.W(IDX_W)) u_bex_y (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'((c12y + sidx_t'(s12.r.sy.mv && !s12.r.sy.neg)) <<< nk_q[12])), .y_o(bex_y));

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

  slot_t  s16, n16;
  rd_t    rd16;
  act_t   act16;
  cross_t x16;
  child_t ch16;
  f24_t   t_new16;
  logic [ITER_W-1:0] it1;
  logic iter16, down16, cross16, up16;
  assign rd16    = rd_q[16];
  assign act16   = act_q[16];
  assign x16     = cross_q[16];
  assign ch16    = child_q[16];
  assign t_new16 = t_new_q[16];
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
    end else if (rd16.rd_err) begin
      n16.r.done = 1'b1;
      n16.r.err  = 1'b1;
    end else if (rd16.ok) begin
      iter16       = 1'b1;
      n16.r.iters  = it1;
      if (act16.is_hit) begin
        n16.r.done = 1'b1;
        n16.r.hit  = 1'b1;
        n16.r.t    = t_new16;
        n16.r.u0   = x16.pu;
        n16.r.v0   = x16.pv;
      end else if (act16.miss) begin
        n16.r.done = 1'b1;
      end else if (act16.down) begin
        down16          = 1'b1;
        n16.r.k         = nk_q[16];
        n16.r.cx        = CELL_W'(correct(ch16.dcx, s16.r.sx, ten_x, tex_x, t_new16,
                                          ch16.lox, ch16.hix));
        n16.r.cy        = CELL_W'(correct(ch16.dcy, s16.r.sy, ten_y, tex_y, t_new16,
                                          ch16.loy, ch16.hiy));
        n16.r.t         = t_new16;
        n16.r.prev_cross = 1'b0;
      end else begin
        cross16          = 1'b1;
        up16             = x16.up;
        n16.r.k          = x16.xk;
        n16.r.cx         = x16.xcx;
        n16.r.cy         = x16.xcy;
        n16.r.t          = x16.xt;
        n16.r.crossed    = 1'b1;
        n16.r.prev_cross = !x16.up;
      end
      if (it1 >= cfg_i.iter_cap && !act16.is_hit && !act16.miss) begin
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
  // S17 -> S0: the ray re-circulates (priority), or a new ray fills the bubble.
  assign p0_d = (v_q[D-1] && !retire) ? s17 : '{id: new_id_i, r: new_ray_i};

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int s = 0; s < D; s++) v_q[s] <= 1'b0;
    end else begin
      v_q[0] <= v0_d;
      for (int s = 1; s < D; s++) v_q[s] <= v_q[s-1];
    end
  end

  always_ff @(posedge clk_i) begin
    // the slots: one stage per clock, S16's next state into S17
    p_q[0] <= p0_d;
    for (int s = 1; s < D - 1; s++) p_q[s] <= p_q[s-1];
    p_q[D-1] <= n16;
    // S3 -> S4
    rd_q[4] <= '{ok: rs_valid_i && rs_hit_i && !rs_err_i, rd_err: rs_valid_i && rs_err_i};
    for (int s = 5; s <= 16; s++) rd_q[s] <= rd_q[s-1];
    // S4 -> S5
    exit_q[5] <= '{te: te, eqx: f24_eq(tx, te), eqy: f24_eq(ty, te)};
    for (int s = 6; s <= 10; s++) exit_q[s] <= exit_q[s-1];
    // S5 -> S6
    tmin_q[6]     <= tmin5;
    miss_pre_q[6] <= f24_le(p_q[5].r.t_map, exit_q[5].te);
    tmin_q[7]     <= tmin_q[6];
    miss_pre_q[7] <= miss_pre_q[6];
    // S6 -> S7
    t_new_q[7] <= f24_max(p_q[6].r.t, plane);
    for (int s = 8; s <= 16; s++) t_new_q[s] <= t_new_q[s-1];
    // S7 -> S8
    act_q[8] <= '{is_hit: inside7 && (p_q[7].r.k == '0), down: inside7 && (p_q[7].r.k != '0),
                  miss: !inside7 && miss_pre_q[7]};
    for (int s = 9; s <= 16; s++) act_q[s] <= act_q[s-1];
    // S9 -> S10
    ibx_q[10] <= ie_x;
    iby_q[10] <= ie_y;
    ibx_q[11] <= ibx_q[10];
    iby_q[11] <= iby_q[10];
    // S10 -> S11
    cross_q[11] <= '{pu: posn_x, pv: posn_y, xk: xk10, xcx: xcx10, xcy: xcy10,
                     xt: f24_max(s10.r.t, exit_q[10].te), up: up10};
    for (int s = 12; s <= 16; s++) cross_q[s] <= cross_q[s-1];
    // S11 -> S12
    iax_q    <= sidx_t'(in_x);
    iay_q    <= sidx_t'(in_y);
    nk_q[12] <= nk11;
    for (int s = 13; s <= 16; s++) nk_q[s] <= nk_q[s-1];
    // S12 -> S13
    child_q[13] <= '{dcx: c12x, dcy: c12y, lox: lox, hix: hix, loy: loy, hiy: hiy};
    for (int s = 14; s <= 16; s++) child_q[s] <= child_q[s-1];
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
