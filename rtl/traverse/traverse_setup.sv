// traverse_setup: the first mode of the traverse unit (model/traverse.py: setup() and the "first
// mode" block of _trace), a fixed-depth pipeline taking one ray per clock, never stalling.
//
// In: the ray's four numbers as f24 words (the model's ar.r() of the float64 ray).  Out, SETUP_LAT
// clocks later: the ray record (traverse_pkg::ray_t) with the per-ray constants, the start time t0,
// the start level and the start cell, or done = 1 for an invalid ray or one that never enters the
// map (the model's "gone": no iteration).
//
// Stage schedule (T0 = the input register; "a -> b": a unit takes operands at Ta, result at Tb):
//   T0  invalid checks (NaN / Inf field, negative start)        1/du, 1/dv: f24_div T0 -> T2
//       exit boundary of the map b = du > 0 ? W : 0             f24_from_int T0 -> T1
//       position at t0: du * t0                                 f24_mul T0 -> T1
//       floor(u0), floor(v0) (start < W, < H)                   f24_to_index T0 -> T1
//   T1  invalid = ... | floor(u0) >= W | floor(v0) >= H
//       b - u0                                                  f24_add T1 -> T3
//       u0 + du t0                                              f24_add T1 -> T3
//   T2  sx = sign(du) if du != 0 and 1/du finite
//   T3  (b - u0) * (1/du)                                       f24_mul T3 -> T4
//       floor(position at t0) (u0 if sx = 0)                    f24_to_index T3 -> T4
//   T4  t_map = min(tmx, tmy); locate estimate c = clip(floor, -1, N)
//       entry / exit boundary of c                              f24_from_int T4 -> T5
//   T5  gone = t_map <= t0; t_end = clip ? min(1, t_map) : 1
//       du * t_end                                              f24_mul T5 -> T6
//       boundary - u0                                           f24_add T5 -> T7
//   T6  u0 + du t_end                                           f24_add T6 -> T8
//   T7  (boundary - u0) * (1/du): crossing times                f24_mul T7 -> T8
//   T8  locate correction by the crossing times, clip to [-1, N]
//       floor(position at t_end) (u0 if sx = 0)                 f24_to_index T8 -> T9
//   T9  gone |= start cell outside the map; start level k by XOR / bit length; cell >> k: out
//       (traverse_start_level).
//
// The start time t0 (0, or max(0, 1 - H_root) for the clip policy) is the same for every ray; a
// small always-running pipeline derives it from the configuration (ready 4 clocks after a change).
module traverse_setup
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W = 8
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  /* verilator lint_off UNUSEDSIGNAL */  // the first mode reads only part of the configuration
  input  cfg_t            cfg_i,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic            in_valid_i,  // a ray enters T0 (no back-pressure: the caller has room)
  input  logic [ID_W-1:0] in_id_i,
  input  f24_t            in_u0_i,
  input  f24_t            in_v0_i,
  input  f24_t            in_du_i,
  input  f24_t            in_dv_i,
  output logic            out_valid_o,
  output logic [ID_W-1:0] out_id_o,
  output ray_t            out_ray_o,
  output logic [3:0]      busy_o       // rays in the pipeline (for slot accounting)
);

  localparam int unsigned NS = 10;  // stages T0 .. T9

  // Stage registers, written in one always_ff (no copy of the whole pipeline in combinational
  // logic).  Every value lives from the stage that computes it to the last one that reads it;
  // arrays are indexed by stage.
  typedef struct packed {
    logic [ID_W-1:0] id;
    f24_t            u0, v0, du, dv;
  } in_t;                             // T0 .. T9: the ray as it came in
  typedef struct packed {
    f24_t inv_du, inv_dv;             // 1 / du, 1 / dv
    dir_t sx, sy;                     // directions of motion
  } dirs_t;                           // T3 .. T9

  logic  v_q       [NS];
  in_t   in_q      [NS];
  logic  bad_q;                       // T1: NaN / Inf field or a negative start
  logic  invalid_q [2:NS-1];          // T2 ..: bad, or a start at or beyond W / H
  dirs_t dir_q     [3:NS-1];
  f24_t  t_map_q   [5:NS-1];          // time of leaving the map's extent
  logic  gone_q    [6:NS-1];          // t_map <= t0: never enters
  sidx_t c0x_q     [5:NS-1];          // start cell: T5 .. T8 estimate, T9 corrected
  sidx_t c0y_q     [5:NS-1];

  // ---- configuration-derived constants -------------------------------------------------------
  sidx_t width_s, height_s, size_s;   // W, H, N = 2^n
  assign width_s  = sidx_t'(cfg_i.width);
  assign height_s = sidx_t'(cfg_i.height);
  assign size_s   = sidx_t'(1) <<< cfg_i.n;

  // t0 = clip ? max(+0, 1 - H_root) : +0 (model: np.maximum(zeros, sub(one, h_root))).
  f24_t h_root8, h_root16, t0_raw, t0_q;
  f24_from_unorm #(.W(8))  u_root8  (.clk_i, .en_i(1'b1), .k_i(cfg_i.root_code[7:0]), .y_o(h_root8));
  f24_from_unorm #(.W(16)) u_root16 (.clk_i, .en_i(1'b1), .k_i(cfg_i.root_code), .y_o(h_root16));
  f24_add u_root_plane (.clk_i, .en_i(1'b1), .a_i(F24_ONE),
                        .b_i(f24_neg(cfg_i.bits16 ? h_root16 : h_root8)), .y_o(t0_raw));
  always_ff @(posedge clk_i) begin
    t0_q <= cfg_i.policy.clip ? f24_max(F24_POS_ZERO, t0_raw) : F24_POS_ZERO;
  end

  // ---- float units -------------------------------------------------------------------------
  // T0
  f24_t inv_x, inv_y, bmx_f, bmy_f, dut0_x, dut0_y;
  logic signed [IDX_W-1:0] iu0, iv0;
  logic unused_sat_u0, unused_sat_v0;
  logic du_pos, dv_pos;
  assign du_pos = !in_q[0].du[23] && !f24_is_zero(in_q[0].du);
  assign dv_pos = !in_q[0].dv[23] && !f24_is_zero(in_q[0].dv);

  f24_div u_inv_x (.clk_i, .en_i(1'b1), .a_i(F24_ONE), .b_i(in_q[0].du), .y_o(inv_x));
  f24_div u_inv_y (.clk_i, .en_i(1'b1), .a_i(F24_ONE), .b_i(in_q[0].dv), .y_o(inv_y));
  f24_from_int #(.W(IDX_W)) u_bmx (.clk_i, .en_i(1'b1),
    .k_i(du_pos ? IDX_W'(cfg_i.width) : '0), .y_o(bmx_f));
  f24_from_int #(.W(IDX_W)) u_bmy (.clk_i, .en_i(1'b1),
    .k_i(dv_pos ? IDX_W'(cfg_i.height) : '0), .y_o(bmy_f));
  f24_mul u_dut0_x (.clk_i, .en_i(1'b1), .a_i(in_q[0].du), .b_i(t0_q), .y_o(dut0_x));
  f24_mul u_dut0_y (.clk_i, .en_i(1'b1), .a_i(in_q[0].dv), .b_i(t0_q), .y_o(dut0_y));
  f24_to_index #(.W(IDX_W)) u_iu0 (.clk_i, .en_i(1'b1), .a_i(in_q[0].u0), .idx_o(iu0),
                                   .sat_o(unused_sat_u0));
  f24_to_index #(.W(IDX_W)) u_iv0 (.clk_i, .en_i(1'b1), .a_i(in_q[0].v0), .idx_o(iv0),
                                   .sat_o(unused_sat_v0));

  // T1
  f24_t dmx, dmy, pos0_x, pos0_y;
  f24_add u_dmx (.clk_i, .en_i(1'b1), .a_i(bmx_f), .b_i(f24_neg(in_q[1].u0)), .y_o(dmx));
  f24_add u_dmy (.clk_i, .en_i(1'b1), .a_i(bmy_f), .b_i(f24_neg(in_q[1].v0)), .y_o(dmy));
  f24_add u_pos0_x (.clk_i, .en_i(1'b1), .a_i(in_q[1].u0), .b_i(dut0_x), .y_o(pos0_x));
  f24_add u_pos0_y (.clk_i, .en_i(1'b1), .a_i(in_q[1].v0), .b_i(dut0_y), .y_o(pos0_y));

  // T3
  f24_t tmx_raw, tmy_raw;
  logic signed [IDX_W-1:0] ip0x, ip0y;
  logic unused_sat_p0x, unused_sat_p0y;
  f24_mul u_tmx (.clk_i, .en_i(1'b1), .a_i(dmx), .b_i(dir_q[3].inv_du), .y_o(tmx_raw));
  f24_mul u_tmy (.clk_i, .en_i(1'b1), .a_i(dmy), .b_i(dir_q[3].inv_dv), .y_o(tmy_raw));
  f24_to_index #(.W(IDX_W)) u_ip0x (.clk_i, .en_i(1'b1),
    .a_i(dir_q[3].sx.mv ? pos0_x : in_q[3].u0), .idx_o(ip0x), .sat_o(unused_sat_p0x));
  f24_to_index #(.W(IDX_W)) u_ip0y (.clk_i, .en_i(1'b1),
    .a_i(dir_q[3].sy.mv ? pos0_y : in_q[3].v0), .idx_o(ip0y), .sat_o(unused_sat_p0y));

  // T4: entry / exit boundaries of the estimated start cell (level 0)
  sidx_t est_x, est_y;
  f24_t  ben_x, bex_x, ben_y, bex_y;
  assign est_x = clip_idx(sidx_t'(ip0x), -sidx_t'(1), size_s);
  assign est_y = clip_idx(sidx_t'(ip0y), -sidx_t'(1), size_s);
  f24_from_int #(.W(IDX_W)) u_ben_x (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'(est_x + sidx_t'(dir_q[4].sx.mv && dir_q[4].sx.neg))), .y_o(ben_x));
  f24_from_int #(.W(IDX_W)) u_bex_x (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'(est_x + sidx_t'(dir_q[4].sx.mv && !dir_q[4].sx.neg))), .y_o(bex_x));
  f24_from_int #(.W(IDX_W)) u_ben_y (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'(est_y + sidx_t'(dir_q[4].sy.mv && dir_q[4].sy.neg))), .y_o(ben_y));
  f24_from_int #(.W(IDX_W)) u_bex_y (.clk_i, .en_i(1'b1),
    .k_i(IDX_W'(est_y + sidx_t'(dir_q[4].sy.mv && !dir_q[4].sy.neg))), .y_o(bex_y));

  // T5
  f24_t t_end, due_x, due_y, den_x, dex_x, den_y, dex_y;
  assign t_end = cfg_i.policy.clip ? f24_min(F24_ONE, t_map_q[5]) : F24_ONE;
  f24_mul u_due_x (.clk_i, .en_i(1'b1), .a_i(in_q[5].du), .b_i(t_end), .y_o(due_x));
  f24_mul u_due_y (.clk_i, .en_i(1'b1), .a_i(in_q[5].dv), .b_i(t_end), .y_o(due_y));
  f24_add u_den_x (.clk_i, .en_i(1'b1), .a_i(ben_x), .b_i(f24_neg(in_q[5].u0)), .y_o(den_x));
  f24_add u_dex_x (.clk_i, .en_i(1'b1), .a_i(bex_x), .b_i(f24_neg(in_q[5].u0)), .y_o(dex_x));
  f24_add u_den_y (.clk_i, .en_i(1'b1), .a_i(ben_y), .b_i(f24_neg(in_q[5].v0)), .y_o(den_y));
  f24_add u_dex_y (.clk_i, .en_i(1'b1), .a_i(bex_y), .b_i(f24_neg(in_q[5].v0)), .y_o(dex_y));

  // T6
  f24_t pose_x, pose_y;
  f24_add u_pose_x (.clk_i, .en_i(1'b1), .a_i(in_q[6].u0), .b_i(due_x), .y_o(pose_x));
  f24_add u_pose_y (.clk_i, .en_i(1'b1), .a_i(in_q[6].v0), .b_i(due_y), .y_o(pose_y));

  // T7
  f24_t ten_x, tex_x, ten_y, tex_y;
  f24_mul u_ten_x (.clk_i, .en_i(1'b1), .a_i(den_x), .b_i(dir_q[7].inv_du), .y_o(ten_x));
  f24_mul u_tex_x (.clk_i, .en_i(1'b1), .a_i(dex_x), .b_i(dir_q[7].inv_du), .y_o(tex_x));
  f24_mul u_ten_y (.clk_i, .en_i(1'b1), .a_i(den_y), .b_i(dir_q[7].inv_dv), .y_o(ten_y));
  f24_mul u_tex_y (.clk_i, .en_i(1'b1), .a_i(dex_y), .b_i(dir_q[7].inv_dv), .y_o(tex_y));

  // T8
  logic signed [IDX_W-1:0] ipe_x, ipe_y;
  logic unused_sat_pex, unused_sat_pey;
  f24_to_index #(.W(IDX_W)) u_ipe_x (.clk_i, .en_i(1'b1),
    .a_i(dir_q[8].sx.mv ? pose_x : in_q[8].u0), .idx_o(ipe_x), .sat_o(unused_sat_pex));
  f24_to_index #(.W(IDX_W)) u_ipe_y (.clk_i, .en_i(1'b1),
    .a_i(dir_q[8].sy.mv ? pose_y : in_q[8].v0), .idx_o(ipe_y), .sat_o(unused_sat_pey));

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

  // ---- stage registers -----------------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      for (int s = 0; s < NS; s++) v_q[s] <= 1'b0;
    end else begin
      v_q[0] <= in_valid_i;
      for (int s = 1; s < NS; s++) v_q[s] <= v_q[s-1];
    end
  end

  always_ff @(posedge clk_i) begin
    // T0: the ray (captured every clock; v_q says whether it is one)
    in_q[0] <= '{id: in_id_i, u0: in_u0_i, v0: in_v0_i, du: in_du_i, dv: in_dv_i};
    for (int s = 1; s < NS; s++) in_q[s] <= in_q[s-1];
    // T0 -> T1
    bad_q <= !f24_is_finite(in_q[0].u0) || !f24_is_finite(in_q[0].v0) ||
             !f24_is_finite(in_q[0].du) || !f24_is_finite(in_q[0].dv) ||
             (in_q[0].u0[23] && !f24_is_zero(in_q[0].u0)) ||
             (in_q[0].v0[23] && !f24_is_zero(in_q[0].v0));
    // T1 -> T2
    invalid_q[2] <= bad_q || (sidx_t'(iu0) >= width_s) || (sidx_t'(iv0) >= height_s);
    for (int s = 3; s < NS; s++) invalid_q[s] <= invalid_q[s-1];
    // T2 -> T3
    dir_q[3] <= '{inv_du: inv_x, inv_dv: inv_y,
                  sx: '{mv: !f24_is_zero(in_q[2].du) && f24_is_finite(inv_x), neg: in_q[2].du[23]},
                  sy: '{mv: !f24_is_zero(in_q[2].dv) && f24_is_finite(inv_y), neg: in_q[2].dv[23]}};
    for (int s = 4; s < NS; s++) dir_q[s] <= dir_q[s-1];
    // T4 -> T5
    t_map_q[5] <= f24_min(dir_q[4].sx.mv ? tmx_raw : F24_POS_INF,
                          dir_q[4].sy.mv ? tmy_raw : F24_POS_INF);
    for (int s = 6; s < NS; s++) t_map_q[s] <= t_map_q[s-1];
    c0x_q[5] <= est_x;
    c0y_q[5] <= est_y;
    for (int s = 6; s < NS - 1; s++) begin
      c0x_q[s] <= c0x_q[s-1];
      c0y_q[s] <= c0y_q[s-1];
    end
    // T5 -> T6
    gone_q[6] <= f24_le(t_map_q[5], t0_q);
    for (int s = 7; s < NS; s++) gone_q[s] <= gone_q[s-1];
    // T8 -> T9: locate's correction
    c0x_q[NS-1] <= correct(c0x_q[NS-2], dir_q[NS-2].sx, ten_x, tex_x, t0_q, -sidx_t'(1), size_s);
    c0y_q[NS-1] <= correct(c0y_q[NS-2], dir_q[NS-2].sy, ten_y, tex_y, t0_q, -sidx_t'(1), size_s);
  end

  // ---- T9: start cell, start level, out -------------------------------------------------------
  in_t   l;                           // the last stage
  dirs_t ld;
  assign l  = in_q[NS-1];
  assign ld = dir_q[NS-1];

  logic             outside;
  logic [LVL_W-1:0] k;
  logic [CELL_W-1:0] cx, cy;
  traverse_start_level u_start_level (
    .n_i          (cfg_i.n),
    .width_i      (cfg_i.width),
    .height_i     (cfg_i.height),
    .start_level_i(cfg_i.policy.start_level),
    .c0x_i        (c0x_q[NS-1]),
    .c0y_i        (c0y_q[NS-1]),
    .ex_i         (ipe_x),
    .ey_i         (ipe_y),
    .outside_o    (outside),
    .k_o          (k),
    .cx_o         (cx),
    .cy_o         (cy)
  );

  always_comb begin
    out_ray_o            = '0;
    out_ray_o.u0         = l.u0;
    out_ray_o.v0         = l.v0;
    out_ray_o.du         = l.du;
    out_ray_o.dv         = l.dv;
    out_ray_o.inv_du     = ld.inv_du;
    out_ray_o.inv_dv     = ld.inv_dv;
    out_ray_o.sx         = ld.sx;
    out_ray_o.sy         = ld.sy;
    out_ray_o.t_map      = t_map_q[NS-1];
    out_ray_o.k          = k;
    out_ray_o.cx         = cx;
    out_ray_o.cy         = cy;
    out_ray_o.t          = t0_q;
    out_ray_o.invalid    = invalid_q[NS-1];
    out_ray_o.done       = invalid_q[NS-1] || gone_q[NS-1] || outside;
  end

  assign out_valid_o = v_q[NS-1];
  assign out_id_o    = l.id;

  always_comb begin
    busy_o = '0;
    for (int s = 0; s < NS; s++) busy_o = busy_o + 4'(v_q[s]);
  end

endmodule
