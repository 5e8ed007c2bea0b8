// traverse_setup: the first mode of the traverse unit (model/traverse.py: setup() and the "first
// mode" block of _trace), a fixed-depth pipeline taking one ray per clock, never stalling.
//
// In: the ray's four numbers as f24 words (the model's ar.r() of the float64 ray).  Out, SETUP_LAT
// clocks later (traverse_pkg: F24_DIV_LAT + 11 = 19): the ray record (traverse_pkg::ray_t) with
// the per-ray constants, the start time t0, the start level and the start cell, or done = 1 for
// an invalid ray or one that never enters the map (the model's "gone": no iteration).
//
// Stage schedule (T0 = the clock after in_valid_i; "a -> b": a unit takes operands at Ta, result
// at Tb).  The reciprocals start at T0 and take F24_DIV_LAT = 8 clocks (f24_pkg: the pipelined
// divider); the rest of the first mode starts C = F24_DIV_LAT - 2 = 6 clocks later, at T6, so
// that 1/du is ready at T8 where the directions need it.  Nothing before T8 depends on 1/du.
// Every float unit takes its operands from registers (a unit's result, or a registered table
// read, below), and integer logic that feeds a unit has a stage of its own (T10: the boundary
// integers); the start decision takes two clocks (T16, T17: traverse_start_level) and the
// shift to the start node a third (T18).
//   T0  1/du, 1/dv                                              f24_div T0 -> T8
//   T6  invalid checks (NaN / Inf field, negative start)
//       exit boundary of the map b = du > 0 ? W : 0             f24_from_int T6 -> T7
//       position at t0: du * t0                                 f24_mul T6 -> T7
//       floor(u0), floor(v0) (start < W, < H)                   f24_to_index T6 -> T7
//   T7  invalid = ... | floor(u0) >= W | floor(v0) >= H
//       b - u0                                                  f24_add T7 -> T9
//       u0 + du t0                                              f24_add T7 -> T9
//   T8  sx = sign(du) if du != 0 and 1/du finite
//   T9  (b - u0) * (1/du)                                       f24_mul T9 -> T10
//       floor(position at t0) (u0 if sx = 0)                    f24_to_index T9 -> T10
//   T10 t_map = min(tmx, tmy); t_end = clip ? min(1, t_map) : 1; locate estimate
//       c = clip(floor, -1, N) and its entry / exit boundary integers
//   T11 gone = t_map <= t0
//       entry / exit boundary of c                              f24_from_int T11 -> T12
//       du * t_end                                              f24_mul T11 -> T12
//   T12 boundary - u0                                           f24_add T12 -> T14
//       u0 + du t_end                                           f24_add T12 -> T14
//   T14 (boundary - u0) * (1/du): crossing times                f24_mul T14 -> T15
//       floor(position at t_end) (u0 if sx = 0)                 f24_to_index T14 -> T15
//       locate's three candidates (the estimate, one cell back, one on; clipped to [-1, N])
//   T15 locate correction: the candidate the crossing times choose
//   T16 start cell and end cell clipped to the map, outside, XOR     traverse_start_level
//   T17 start level k by bit length (leading-zero count)             T16 -> T18
//   T18 gone |= start cell outside the map; cell >> k: out
// In the code, stage T(C+k) is vs[k] / ss[k], and a name ending in the digit k (uv3, dir8, ...)
// is a value of stage T(C+k).
//
// Ray table: a ray's values do not move from stage to stage.  Every ray in stages T0 .. T(NS-4)
// owns one entry of a table of NT = NS - 3 = 16 entries (16-deep LUT RAM; the last three stages
// read nothing from the table: what they output was read in T(NS-4)); since the pipeline
// advances every clock, the entry of the ray in stage Ts is (ph_q - s) mod NT, with ph_q a phase
// counter that steps every clock.  A value is written into the ray's entry by the stage that
// computes it and read by the later stages that need it (before the entry is reused, NT clocks
// after the ray came in); a value a float unit takes as an operand is read one clock early into a
// register.  Only the valid bits move, one stage per clock (v_q).
//
// Clock enables: a float unit advances only while a ray is in it, and holds its registers
// otherwise (less switching, and less work for a simulator); likewise a stage computes what it
// writes into the table only while it holds a ray.
//
// The start time t0 (0, or max(0, 1 - H_root) for the clip policy) is the same for every ray; a
// small pipeline derives it from the configuration (ready 4 clocks after a change).  It runs while
// the unit is idle (idle_i), the only time the configuration may change, and holds otherwise.
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
  input  logic            idle_i,      // the unit holds no ray (the configuration may change)
  input  logic            in_valid_i,  // a ray enters T0 (no back-pressure: the caller has room)
  input  logic [ID_W-1:0] in_id_i,
  input  f24_t            in_u0_i,
  input  f24_t            in_v0_i,
  input  f24_t            in_du_i,
  input  f24_t            in_dv_i,
  output logic            out_valid_o,
  output logic [ID_W-1:0] out_id_o,
  output ray_t            out_ray_o,
  output logic [SETUP_BUSY_W-1:0] busy_o  // rays in the pipeline (for slot accounting)
);

  localparam int unsigned NS = SETUP_LAT;           // stages T0 .. T(NS-1)
  localparam int unsigned NT = NS - 3;              // ray-table entries (T0 .. T(NS-4))
  localparam int unsigned SW = $clog2(NT);          // ray-table index width
  localparam int unsigned C  = F24_DIV_LAT - 2;     // start of the paper's schedule (its T0)
  if (NS != C + 13 || NT != 16 || F24_DIV_LAT < 3) begin : g_check_lat
    $error("traverse_setup: stage schedule does not add up to SETUP_LAT");
  end

  typedef logic [SW-1:0] slot_idx_t;
  typedef struct packed {
    f24_t u, v;                     // a value per axis
  } f24_pair_t;
  typedef struct packed {
    dir_t sx, sy;                   // directions of motion
  } dirs_t;

  // The ray table (see the header); the stage that writes each field is in brackets.
  logic [ID_W-1:0] id_q      [NT];  // [in]
  f24_pair_t       uv_q      [NT];  // [in] u0, v0
  f24_pair_t       duv_q     [NT];  // [in] du, dv
  logic            invalid_q [NT];  // [T(C+1)] NaN / Inf field, negative start, start >= W / H
  f24_pair_t       inv_q     [NT];  // [T(C+2)] 1 / du, 1 / dv
  dirs_t           dir_q     [NT];  // [T(C+2)]
  f24_t            t_map_q   [NT];  // [T(C+4)] time of leaving the map's extent
  sidx_t           estx_q    [NT];  // [T(C+4)] locate's estimate of the start cell (level 0)
  sidx_t           esty_q    [NT];
  logic            gone_q    [NT];  // [T(C+5)] t_map <= t0: never enters
  // Values that live one clock.
  logic            bad_q;           // T(C+0) -> T(C+1): NaN / Inf field or a negative start
  sidx_t           c0x_q, c0y_q;    // T(C+9) -> T(C+10): the corrected start cell

  logic [NS-1:0]   v_q;             // v_q[s]: stage Ts holds a ray
  slot_idx_t       ph_q;            // phase: stage Ts holds the ray of entry (ph_q - s) mod NT
  slot_idx_t       sl [NT];         // sl[s] = (ph_q - s) mod NT, s = 0 .. NS-4
  logic [9:0]      vs;              // vs[k] = v_q[C+k]: the working stages of the schedule
  slot_idx_t       ss [10];         // (T(C+0) .. T(C+9); T(C+10) is the last); ss[k] = sl[C+k]

  always_comb begin
    for (int s = 0; s < NT; s++) begin
      sl[s] = (ph_q >= SW'(s)) ? ph_q - SW'(s) : ph_q + SW'(NT - s);
    end
    for (int k = 0; k < 10; k++) ss[k] = sl[C+k];
  end
  assign vs = v_q[C +: 10];

  // ---- configuration-derived constants -------------------------------------------------------
  sidx_t width_s, height_s, size_s;   // W, H, N = 2^n
  assign width_s  = sidx_t'(cfg_i.width);
  assign height_s = sidx_t'(cfg_i.height);
  assign size_s   = sidx_t'(1) <<< cfg_i.n;

  // t0 = clip ? max(+0, 1 - H_root) : +0 (model: np.maximum(zeros, sub(one, h_root))).
  f24_t h_root8, h_root16, t0_raw, t0_d, t0_q;
  f24_ord_t ot0;                      // t0 in comparable form
  f24_from_unorm #(.W(8))  u_root8  (.clk_i, .en_i(idle_i), .k_i(cfg_i.root_code[7:0]),
                                     .y_o(h_root8));
  f24_from_unorm #(.W(16)) u_root16 (.clk_i, .en_i(idle_i), .k_i(cfg_i.root_code), .y_o(h_root16));
  f24_add u_root_plane (.clk_i, .en_i(idle_i), .a_i(F24_ONE),
                        .b_i(f24_neg(cfg_i.bits16 ? h_root16 : h_root8)), .y_o(t0_raw));
  assign t0_d = cfg_i.policy.clip ? f24_max(F24_POS_ZERO, t0_raw) : F24_POS_ZERO;
  always_ff @(posedge clk_i) begin
    if (idle_i) t0_q <= t0_d;
  end
  assign ot0 = f24_ord(t0_q);

  // ---- registered table reads --------------------------------------------------------------
  // A float unit takes its operands from registers, never through a table read (a 16:1 read
  // multiplexer in front of a unit's clock would cost its fmax): a value a stage T(C+k) needs
  // is read from the table one clock earlier, in T(C+k-1), into a register (name ending in k,
  // _q), or forwarded from the value the earlier stage writes.
  f24_pair_t duv_div_q;                     // T0 (from the input)
  f24_pair_t uv0_q, duv0_q;                 // T(C+0)
  logic [IDX_W-1:0] kbm_x_q, kbm_y_q;       // T(C+0): exit boundary W / H or 0, as an integer
  f24_pair_t uv1_q;                         // T(C+1)
  f24_pair_t uv3_q, inv3_q;                 // T(C+3)
  dirs_t     dir3_q, dir4_q;                // T(C+3), T(C+4)
  f24_pair_t duv5_q;                        // T(C+5)
  f24_t      t_end5_q;                      // T(C+5): computed in T(C+4)
  logic [IDX_W-1:0] kben_x_q, kbex_x_q, kben_y_q, kbex_y_q;  // T(C+5): computed in T(C+4)
  f24_pair_t uv6_q;                         // T(C+6)
  f24_pair_t uv8_q, inv8_q;                 // T(C+8)
  dirs_t     dir8_q;                        // T(C+8)
  // locate's candidates: one cell back, the estimate, one cell on (each clipped to [-1, N]).
  typedef struct packed {
    sidx_t back, est, fwd;
  } cand_t;
  cand_t     locx9_q, locy9_q;              // T(C+9): computed in T(C+8)
  logic signed [IDX_W-1:0] ipe_x10_q, ipe_y10_q;  // T(C+10)
  f24_pair_t duv_r;                         // the table read for T(C+0)

  // ---- float units -------------------------------------------------------------------------
  // T0: the reciprocals; a divider advances while a ray is in it (T0 .. T(F24_DIV_LAT-1)).
  f24_t      inv_x, inv_y;
  f24_div #(.LAT(F24_DIV_LAT)) u_inv_x (.clk_i, .en_i(|v_q[F24_DIV_LAT-1:0]), .a_i(F24_ONE),
                                        .b_i(duv_div_q.u), .y_o(inv_x));
  f24_div #(.LAT(F24_DIV_LAT)) u_inv_y (.clk_i, .en_i(|v_q[F24_DIV_LAT-1:0]), .a_i(F24_ONE),
                                        .b_i(duv_div_q.v), .y_o(inv_y));

  // T(C+0)
  f24_t      bmx_f, bmy_f, dut0_x, dut0_y;
  logic signed [IDX_W-1:0] iu0, iv0;
  logic unused_sat_u0, unused_sat_v0;
  f24_from_int #(.W(IDX_W)) u_bmx (.clk_i, .en_i(vs[0]), .k_i(kbm_x_q), .y_o(bmx_f));
  f24_from_int #(.W(IDX_W)) u_bmy (.clk_i, .en_i(vs[0]), .k_i(kbm_y_q), .y_o(bmy_f));
  f24_mul u_dut0_x (.clk_i, .en_i(vs[0]), .a_i(duv0_q.u), .b_i(t0_q), .y_o(dut0_x));
  f24_mul u_dut0_y (.clk_i, .en_i(vs[0]), .a_i(duv0_q.v), .b_i(t0_q), .y_o(dut0_y));
  f24_to_index #(.W(IDX_W)) u_iu0 (.clk_i, .en_i(vs[0]), .a_i(uv0_q.u), .idx_o(iu0),
                                   .sat_o(unused_sat_u0));
  f24_to_index #(.W(IDX_W)) u_iv0 (.clk_i, .en_i(vs[0]), .a_i(uv0_q.v), .idx_o(iv0),
                                   .sat_o(unused_sat_v0));

  // T(C+1)
  f24_t      dmx, dmy, pos0_x, pos0_y;
  f24_add u_dmx (.clk_i, .en_i(vs[1] || vs[2]), .a_i(bmx_f), .b_i(f24_neg(uv1_q.u)), .y_o(dmx));
  f24_add u_dmy (.clk_i, .en_i(vs[1] || vs[2]), .a_i(bmy_f), .b_i(f24_neg(uv1_q.v)), .y_o(dmy));
  f24_add u_pos0_x (.clk_i, .en_i(vs[1] || vs[2]), .a_i(uv1_q.u), .b_i(dut0_x), .y_o(pos0_x));
  f24_add u_pos0_y (.clk_i, .en_i(vs[1] || vs[2]), .a_i(uv1_q.v), .b_i(dut0_y), .y_o(pos0_y));

  // T(C+2): directions (written to the table and forwarded to T(C+3))
  f24_pair_t duv2;
  dirs_t     dir2;
  assign duv2 = duv_q[ss[2]];
  assign dir2 = '{sx: '{mv: !f24_is_zero(duv2.u) && f24_is_finite(inv_x), neg: duv2.u[23]},
                  sy: '{mv: !f24_is_zero(duv2.v) && f24_is_finite(inv_y), neg: duv2.v[23]}};

  // T(C+3)
  f24_t      tmx_raw, tmy_raw;
  logic signed [IDX_W-1:0] ip0x, ip0y;
  logic unused_sat_p0x, unused_sat_p0y;
  f24_mul u_tmx (.clk_i, .en_i(vs[3]), .a_i(dmx), .b_i(inv3_q.u), .y_o(tmx_raw));
  f24_mul u_tmy (.clk_i, .en_i(vs[3]), .a_i(dmy), .b_i(inv3_q.v), .y_o(tmy_raw));
  f24_to_index #(.W(IDX_W)) u_ip0x (.clk_i, .en_i(vs[3]),
    .a_i(dir3_q.sx.mv ? pos0_x : uv3_q.u), .idx_o(ip0x), .sat_o(unused_sat_p0x));
  f24_to_index #(.W(IDX_W)) u_ip0y (.clk_i, .en_i(vs[3]),
    .a_i(dir3_q.sy.mv ? pos0_y : uv3_q.v), .idx_o(ip0y), .sat_o(unused_sat_p0y));

  // T(C+4): the time of leaving the map and t_end; the estimated start cell (level 0) and the
  // integers of its entry / exit boundaries (converted in T(C+5))
  sidx_t est_x, est_y;
  f24_t  t_map4, t_end4;
  assign est_x  = clip_idx(sidx_t'(ip0x), -sidx_t'(1), size_s);
  assign est_y  = clip_idx(sidx_t'(ip0y), -sidx_t'(1), size_s);
  // t_map = min(tx, ty) (inf on an axis that does not move); t_end = t_map unless 1 < t_map.
  // Whether 1 < t_map is taken from 1 < tx and 1 < ty beside the comparison of tx and ty (the
  // three comparisons side by side, not two in series).
  f24_t     tmx4, tmy4;
  f24_ord_t otmx4, otmy4;
  logic     x_first4;                 // t_map is tx
  assign tmx4     = dir4_q.sx.mv ? tmx_raw : F24_POS_INF;
  assign tmy4     = dir4_q.sy.mv ? tmy_raw : F24_POS_INF;
  assign otmx4    = f24_ord(tmx4);
  assign otmy4    = f24_ord(tmy4);
  assign x_first4 = ord_min_first(otmx4, otmy4);
  assign t_map4   = x_first4 ? tmx4 : tmy4;
  assign t_end4   = (cfg_i.policy.clip && !(x_first4 ? ord_lt(f24_ord(F24_ONE), otmx4)
                                                     : ord_lt(f24_ord(F24_ONE), otmy4)))
                  ? t_map4 : F24_ONE;

  // T(C+5)
  f24_t      due_x, due_y, ben_x, bex_x, ben_y, bex_y;
  f24_mul u_due_x (.clk_i, .en_i(vs[5]), .a_i(duv5_q.u), .b_i(t_end5_q), .y_o(due_x));
  f24_mul u_due_y (.clk_i, .en_i(vs[5]), .a_i(duv5_q.v), .b_i(t_end5_q), .y_o(due_y));
  f24_from_int #(.W(IDX_W)) u_ben_x (.clk_i, .en_i(vs[5]), .k_i(kben_x_q), .y_o(ben_x));
  f24_from_int #(.W(IDX_W)) u_bex_x (.clk_i, .en_i(vs[5]), .k_i(kbex_x_q), .y_o(bex_x));
  f24_from_int #(.W(IDX_W)) u_ben_y (.clk_i, .en_i(vs[5]), .k_i(kben_y_q), .y_o(ben_y));
  f24_from_int #(.W(IDX_W)) u_bex_y (.clk_i, .en_i(vs[5]), .k_i(kbex_y_q), .y_o(bex_y));

  // T(C+6)
  f24_t      den_x, dex_x, den_y, dex_y, pose_x, pose_y;
  f24_add u_den_x (.clk_i, .en_i(vs[6] || vs[7]), .a_i(ben_x), .b_i(f24_neg(uv6_q.u)), .y_o(den_x));
  f24_add u_dex_x (.clk_i, .en_i(vs[6] || vs[7]), .a_i(bex_x), .b_i(f24_neg(uv6_q.u)), .y_o(dex_x));
  f24_add u_den_y (.clk_i, .en_i(vs[6] || vs[7]), .a_i(ben_y), .b_i(f24_neg(uv6_q.v)), .y_o(den_y));
  f24_add u_dex_y (.clk_i, .en_i(vs[6] || vs[7]), .a_i(bex_y), .b_i(f24_neg(uv6_q.v)), .y_o(dex_y));
  f24_add u_pose_x (.clk_i, .en_i(vs[6] || vs[7]), .a_i(uv6_q.u), .b_i(due_x), .y_o(pose_x));
  f24_add u_pose_y (.clk_i, .en_i(vs[6] || vs[7]), .a_i(uv6_q.v), .b_i(due_y), .y_o(pose_y));

  // T(C+8)
  f24_t      ten_x, tex_x, ten_y, tex_y;
  logic signed [IDX_W-1:0] ipe_x, ipe_y;
  logic unused_sat_pex, unused_sat_pey;
  f24_mul u_ten_x (.clk_i, .en_i(vs[8]), .a_i(den_x), .b_i(inv8_q.u), .y_o(ten_x));
  f24_mul u_tex_x (.clk_i, .en_i(vs[8]), .a_i(dex_x), .b_i(inv8_q.u), .y_o(tex_x));
  f24_mul u_ten_y (.clk_i, .en_i(vs[8]), .a_i(den_y), .b_i(inv8_q.v), .y_o(ten_y));
  f24_mul u_tex_y (.clk_i, .en_i(vs[8]), .a_i(dex_y), .b_i(inv8_q.v), .y_o(tex_y));
  f24_to_index #(.W(IDX_W)) u_ipe_x (.clk_i, .en_i(vs[8]),
    .a_i(dir8_q.sx.mv ? pose_x : uv8_q.u), .idx_o(ipe_x), .sat_o(unused_sat_pex));
  f24_to_index #(.W(IDX_W)) u_ipe_y (.clk_i, .en_i(vs[8]),
    .a_i(dir8_q.sy.mv ? pose_y : uv8_q.v), .idx_o(ipe_y), .sat_o(unused_sat_pey));

  // locate's correction: the cell whose crossing times bracket t (cells are half-open in t),
  // from the estimate c: c - s if t is before the estimate's entry, c + s if at or after its
  // exit, else c, clipped to [lo, hi].  The candidates are formed a stage before the choice
  // (the crossing times arrive in the choosing stage); the estimate is already in [lo, hi].
  function automatic cand_t candidates(input sidx_t c, input dir_t s, input sidx_t lo,
                                       input sidx_t hi);
    return '{back: clip_idx(c - dir_val(s), lo, hi), est: c, fwd: clip_idx(c + dir_val(s), lo, hi)};
  endfunction
  function automatic sidx_t correct(input cand_t c, input f24_ord_t t_entry,
                                    input f24_ord_t t_exit, input f24_ord_t t);
    return ord_lt(t, t_entry) ? c.back : ord_le(t_exit, t) ? c.fwd : c.est;
  endfunction

  // The registered reads.  Each loads while the stage before the reader holds a ray.
  assign duv_r = duv_q[sl[C-1]];
  always_ff @(posedge clk_i) begin
    if (in_valid_i) duv_div_q <= '{u: in_du_i, v: in_dv_i};
    if (v_q[C-1]) begin
      uv0_q   <= uv_q[sl[C-1]];
      duv0_q  <= duv_r;
      kbm_x_q <= (!duv_r.u[23] && !f24_is_zero(duv_r.u)) ? IDX_W'(cfg_i.width) : '0;
      kbm_y_q <= (!duv_r.v[23] && !f24_is_zero(duv_r.v)) ? IDX_W'(cfg_i.height) : '0;
    end
    if (vs[0]) uv1_q <= uv_q[ss[0]];
    if (vs[2]) begin
      uv3_q  <= uv_q[ss[2]];
      inv3_q <= '{u: inv_x, v: inv_y};
      dir3_q <= dir2;
    end
    if (vs[3]) dir4_q <= dir3_q;
    if (vs[4]) begin
      duv5_q   <= duv_q[ss[4]];
      t_end5_q <= t_end4;
      kben_x_q <= IDX_W'(est_x + sidx_t'(dir4_q.sx.mv && dir4_q.sx.neg));
      kbex_x_q <= IDX_W'(est_x + sidx_t'(dir4_q.sx.mv && !dir4_q.sx.neg));
      kben_y_q <= IDX_W'(est_y + sidx_t'(dir4_q.sy.mv && dir4_q.sy.neg));
      kbex_y_q <= IDX_W'(est_y + sidx_t'(dir4_q.sy.mv && !dir4_q.sy.neg));
    end
    if (vs[5]) uv6_q <= uv_q[ss[5]];
    if (vs[7]) begin
      uv8_q  <= uv_q[ss[7]];
      inv8_q <= inv_q[ss[7]];
      dir8_q <= dir_q[ss[7]];
    end
    if (vs[8]) begin
      locx9_q <= candidates(estx_q[ss[8]], dir8_q.sx, -sidx_t'(1), size_s);
      locy9_q <= candidates(esty_q[ss[8]], dir8_q.sy, -sidx_t'(1), size_s);
    end
    if (vs[9]) begin
      ipe_x10_q <= ipe_x;
      ipe_y10_q <= ipe_y;
    end
  end

  // ---- pipeline and ray table ----------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      v_q  <= '0;
      ph_q <= '0;
    end else begin
      v_q  <= {v_q[NS-2:0], in_valid_i};
      ph_q <= (ph_q == SW'(NT - 1)) ? '0 : ph_q + SW'(1);
    end
  end

  always_ff @(posedge clk_i) begin
    // in: the ray takes the entry of the one in T(NT-1), whose last reads are at this clock's
    // edge (that entry is T0's next clock)
    if (in_valid_i) begin
      id_q[sl[NT-1]]  <= in_id_i;
      uv_q[sl[NT-1]]  <= '{u: in_u0_i, v: in_v0_i};
      duv_q[sl[NT-1]] <= '{u: in_du_i, v: in_dv_i};
    end
    // A stage computes and writes only while it holds a ray.
    // T(C+0) -> T(C+1): NaN / Inf field, negative start
    if (vs[0]) begin
      bad_q <= !f24_is_finite(uv0_q.u) || !f24_is_finite(uv0_q.v) ||
               !f24_is_finite(duv0_q.u) || !f24_is_finite(duv0_q.v) ||
               (uv0_q.u[23] && !f24_is_zero(uv0_q.u)) || (uv0_q.v[23] && !f24_is_zero(uv0_q.v));
    end
    // T(C+1) -> T(C+2): or a start at or beyond W / H
    if (vs[1]) begin
      invalid_q[ss[1]] <= bad_q || (sidx_t'(iu0) >= width_s) || (sidx_t'(iv0) >= height_s);
    end
    // T(C+2) -> T(C+3): reciprocals and directions
    if (vs[2]) begin
      inv_q[ss[2]] <= '{u: inv_x, v: inv_y};
      dir_q[ss[2]] <= dir2;
    end
    // T(C+4) -> T(C+5): time of leaving the map, the start cell's estimate
    if (vs[4]) begin
      t_map_q[ss[4]] <= t_map4;
      estx_q[ss[4]]  <= est_x;
      esty_q[ss[4]]  <= est_y;
    end
    // T(C+5) -> T(C+6): never enters
    if (vs[5]) gone_q[ss[5]] <= ord_le(f24_ord(t_map_q[ss[5]]), ot0);
    // T(C+9) -> T(C+10): locate's correction
    if (vs[9]) begin
      c0x_q <= correct(locx9_q, f24_ord(ten_x), f24_ord(tex_x), ot0);
      c0y_q <= correct(locy9_q, f24_ord(ten_y), f24_ord(tex_y), ot0);
    end
  end

  // ---- T(C+10) .. T(C+12) = T(NS-1): start level (2 clocks), start cell, out -----------------
  logic              outside;
  logic [LVL_W-1:0]  k;
  logic [CELL_W-1:0] cx, cy;
  traverse_start_level u_start_level (
    .clk_i        (clk_i),
    .en_i         (v_q[NS-3] || v_q[NS-2]),
    .n_i          (cfg_i.n),
    .width_i      (cfg_i.width),
    .height_i     (cfg_i.height),
    .start_level_i(cfg_i.policy.start_level),
    .c0x_i        (c0x_q),
    .c0y_i        (c0y_q),
    .ex_i         (ipe_x10_q),
    .ey_i         (ipe_y10_q),
    .outside_o    (outside),
    .k_o          (k),
    .cx_o         (cx),
    .cy_o         (cy)
  );

  // The ray's table fields for the output, read in T(NT-1) = T(NS-4) (the last stage that owns
  // an entry) and carried to T(NS-1) in registers.
  typedef struct packed {
    logic [ID_W-1:0] id;
    f24_pair_t       uv, duv, inv;
    dirs_t           dir;
    f24_t            t_map;
    logic            invalid, gone;
  } out_fields_t;
  out_fields_t out_q [3];  // the fields of the ray in T(NS-3), T(NS-2), T(NS-1)
  always_ff @(posedge clk_i) begin
    if (v_q[NS-4]) begin
      out_q[0] <= '{id: id_q[sl[NT-1]], uv: uv_q[sl[NT-1]], duv: duv_q[sl[NT-1]],
                    inv: inv_q[sl[NT-1]], dir: dir_q[sl[NT-1]], t_map: t_map_q[sl[NT-1]],
                    invalid: invalid_q[sl[NT-1]], gone: gone_q[sl[NT-1]]};
    end
    if (v_q[NS-3]) out_q[1] <= out_q[0];
    if (v_q[NS-2]) out_q[2] <= out_q[1];
  end

  // One expression (not field by field), so that a simulator can evaluate it where it is used.
  assign out_ray_o = '{u0: out_q[2].uv.u, v0: out_q[2].uv.v, du: out_q[2].duv.u, dv: out_q[2].duv.v,
                       inv_du: out_q[2].inv.u, inv_dv: out_q[2].inv.v, sx: out_q[2].dir.sx,
                       sy: out_q[2].dir.sy, t_map: out_q[2].t_map, k: k, cx: cx, cy: cy,
                       t: t0_q, crossed: 1'b0, prev_cross: 1'b0, iters: '0,
                       done: out_q[2].invalid || out_q[2].gone || outside, hit: 1'b0,
                       invalid: out_q[2].invalid, capped: 1'b0, err: 1'b0};

  assign out_valid_o = v_q[NS-1];
  assign out_id_o    = out_q[2].id;
  assign busy_o      = SETUP_BUSY_W'($countones(v_q));

endmodule
