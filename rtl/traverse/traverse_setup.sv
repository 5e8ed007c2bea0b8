// SPDX-License-Identifier: Apache-2.0
// traverse_setup: the first mode of the traverse unit (model/traverse.py: setup() and the "first
// mode" block of _trace), a fixed-depth pipeline taking one ray every 4th clock at most, never
// stalling.  A ray may enter only in the clocks in_ready_o = 1 (one clock in four, from a free
// running phase; asserted: ray_phase, bound from traverse_setup_assert.sv; traverse_unit ANDs it
// into ray_ready_o), so any two rays in the pipeline are a multiple of 4 clocks apart.  The u (x)
// and v (y) axes share the float units, u in one clock and v in the next (as view_calc computes x
// and y), and most units serve two operations of an axis, 6 stages apart: the first in the two
// clocks of the 4 that are its phases, the second in the other two (as shade_unit schedules over
// 4 clocks).
//
// In: the ray's four numbers as f24 words (the model's ar.r() of the float64 ray).  Out, SETUP_LAT
// clocks later (traverse_pkg: F24_DIV_LAT + 13 = 21): the ray record (traverse_pkg::ray_t) with
// the per-ray constants, the start time t0, the start level and the start cell, or done = 1 for
// an invalid ray or one that never enters the map (the model's "gone": no iteration).  Of an
// invalid ray's record only u0, v0, t, done and invalid are defined (traverse_loop passes such a
// ray on at once with those).
//
// Float units: 1 f24_div, 3 f24_mul (one DSP each), 3 f24_add, 2 f24_from_int and 1
// f24_to_index.  The start time t0 takes no unit of its own (below).  (The ring's fixed-point
// boundary difference, traverse_bdiff, would save about an adder's area here but limits the
// block's clock: its 35-bit difference and leading-zero count in one stage.)
//
// Axis items.  A ray is two items in one lane: its u item enters with the ray, its v item one
// clock later (the v inputs are held a clock).  Item stage Is holds the u item of the ray in
// stage Ts or the v item of the ray in T(s+1); an operation of Is runs on its unit for u in one
// clock and for v in the next.  Where the two axes meet, the u item's value is held a clock in a
// register and combined with the v item's: invalid (T10), t_map and t_end (T11), the start cell
// and the end point's cell (T18, into the start level).
//
// Shared units.  A unit that serves two operations of item stages Ia and Ia+6 is busy in the
// clocks of phase a, a+1 (mod 4) for the first and a+2, a+3 for the second: never both, as rays
// are a multiple of 4 clocks apart.  Every float unit takes its operands from registers: a
// unit's result (the same unit's for both operations: the boundary adders are fed by the same
// conversions at both stages, the position adder by the same multiplier, the crossing-time
// multipliers by the same boundary adders, the floor by the same position adder), or an operand
// register that a select loads one clock before the unit reads it (kf_q, kg_q, pu_q, md_q, mt_q,
// pa_q, mi_q, mvx_q / p0x_q), never a select in front of a unit.  The boundary adders [M], [E]
// take 3 clocks (f24_add LAT 3, for the clock), their conversions a clock earlier.
//
// Stage schedule (T0 = the clock after in_valid_i; per-axis rows give the u item's stages, the v
// item's are one later; "a -> b": a unit takes operands at Ia, result at Ib; [X] names the unit).
// The reciprocal starts at I0 and takes F24_DIV_LAT = 8 clocks (f24_pkg: the pipelined divider);
// the rest of the first mode starts C = F24_DIV_LAT - 2 = 6 clocks later, at I6, so that 1/du is
// in a register at I9 where the crossing time needs it.  Nothing before I8 depends on 1/du.
//   I0  1/du (1/dv)                                             f24_div I0 -> I8
//   I4  operand registers: the exit boundary of the map kb = du > 0 ? W : 0 [F] and W [G]
//       (H, H for v)
//   I5  kb, W as floats                                         [F], [G] f24_from_int I5 -> I6
//       operand registers: du and t0 [B], u0
//   I6  checks: NaN / Inf field, negative start
//       kb - u0, W - u0                                         [M], [E] f24_add LAT 3 I6 -> I9
//       du * t0                                                 [B] f24_mul I6 -> I7
//   I7  u0 + du t0                                              [P] f24_add I7 -> I9
//   I8  sx = sign(du) if du != 0 and 1/du finite
//   I9  u: the checks | u0 >= W (W - u0 <= 0) held; T10 (v): invalid = u's | v's
//       (kb - u0) * (1/du)                                      [A] f24_mul I9 -> I10
//       floor(position at t0) (u0 if sx = 0)                    [X] f24_to_index I9 -> I10
//   I10 tmx (inf if sx = 0) held; locate estimate c = clip(floor, -1, N), its entry / exit
//       boundary integers (operand registers of [F], [G])
//   T11 (v item in I10): t_map = min(tmx, ty); t_end = clip ? min(1, t_map) : 1
//   I11 entry, exit boundary as floats                         [F], [G] f24_from_int I11 -> I12
//       operand registers: du and t_end [B], u0
//   T12 gone = t_map <= t0
//   I12 entry - u0, exit - u0                                   [M], [E] f24_add LAT 3 I12 -> I15
//       du * t_end                                              [B] f24_mul I12 -> I13
//   I13 u0 + du t_end                                           [P] f24_add I13 -> I15
//   I15 (boundary - u0) * (1/du): crossing times                [A], [C] f24_mul I15 -> I16
//       floor(position at t_end) (u0 if sx = 0)                 [X] f24_to_index I15 -> I16
//       locate's three candidates (the estimate, one cell back, one on; clipped to [-1, N])
//   I16 locate correction: the candidate the crossing times choose (c0x, c0y registers), the
//       floor of the end point (ex, ey registers)
//   T18 start cell and end cell clipped to the map, outside, XOR     traverse_start_level
//   T19 start level k by bit length (leading-zero count)             T18 -> T20
//   T20 gone |= start cell outside the map; cell >> k: out
// Units: [A] [B] [C] f24_mul, [M] [E] [P] f24_add, [F] [G] f24_from_int, [X] f24_to_index; all
// but [C] serve two operations 6 stages apart ([P] and [B] the start time while idle).
// In the code, item stage I(C+k) is iv[C+k] / ss[k], and a name ending in the digit k (bad2_q,
// dir3_q, ...) is a value of item stage I(C+k); a ray stage Ts is v_q[s] / sl[s].
//
// Tables.  A ray's values do not move from stage to stage.  A phase counter ph_q steps every
// clock; the item or ray that entered stage 0 at phase e owns entry e of the tables of NT = 16
// entries (16-deep LUT RAM), so the entry of the ray in Ts, and of the item in Is, is
// (ph_q - s) mod NT: a ray's u item has the ray's entry, its v item the next one (free, since no
// ray enters the clock after one).  Per-axis values (u0 / v0, du / dv, 1/du / 1/dv, the
// directions, locate's estimate) are in item tables, one value wide: one read port at (ph_q - s)
// gives the u item's value in one clock and the v item's in the next.  The id, invalid, t_map
// and gone are in ray tables.  An entry is written by the stage that computes the value and read
// by the later stages that need it, at the latest in stage 15 (T15 / I15), the clock at whose
// edge the entry is reused; a value a float unit takes as an operand is read one clock early
// into a register (or passed on in registers from such a read).  Only the valid bits move, one
// stage per clock (v_q).
//
// Clock enables: a float unit advances only while an item is in it, and holds its registers
// otherwise (less switching, and less work for a simulator); likewise a stage computes what it
// writes into a table only while it holds an item.
//
// The start time t0 (0, or max(0, 1 - H_root) for the clip policy) is the same for every ray; it
// is derived from the configuration on [P] and [B] (ready 4 clocks after a change) while the
// unit is idle (idle_i), the only time the configuration may change, and held otherwise.
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
  output logic            in_ready_o,  // a ray may enter in this clock (one clock in four)
  input  logic            in_valid_i,  // a ray enters T0 (no back-pressure: the caller has room;
                                       // only while in_ready_o)
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
  localparam int unsigned NT = 16;                  // table entries (stages 0 .. 15 own one)
  localparam int unsigned SW = $clog2(NT);          // table index width
  localparam int unsigned C  = F24_DIV_LAT - 2;     // start of the paper's schedule (its T0)
  localparam int unsigned NO = NS - NT;             // output registers (T16 .. T(NS-1))
  if (NS != C + 15 || NT % 4 != 0 || C + 9 != NT - 1 || F24_DIV_LAT < 3) begin : g_check_lat
    $error("traverse_setup: stage schedule does not add up to SETUP_LAT");
  end

  typedef logic [SW-1:0] slot_idx_t;

  // Ray tables (see the header); the stage that writes each field is in brackets.
  logic [ID_W-1:0] id_q      [NT];  // [in]
  logic            invalid_q [NT];  // [T(C+4)] NaN / Inf field, negative start, start >= W / H
  f24_t            t_map_q   [NT];  // [T(C+6)] time of leaving the map's extent
  logic            gone_q    [NT];  // [T(C+6)] t_map <= t0: never enters
  // Item tables: u0 / v0, du / dv [in: u item with the ray, v item the clock after];
  // 1 / du, 1 / dv and the directions [I(C+2)]; locate's estimate of the start cell [I(C+4)].
  f24_t            p0_q      [NT];
  f24_t            d_q       [NT];
  f24_t            inv_q     [NT];
  dir_t            dir_q     [NT];
  sidx_t           est_q     [NT];
  // The v item's inputs, held from the ray's clock to its own.
  f24_t            v0_h_q, dv_h_q;
  // Values that live one clock or are held for the v item.
  logic            bad_q;           // I(C+0) -> I(C+1): NaN / Inf field, negative, >= 2^16
  logic            bad_u_q;         // T(C+3) -> T(C+4): the u item's checks
  f24_t            tmx_q;           // T(C+4) -> T(C+5): the u item's time of leaving the map
  f24_t            t_map6_q;        // T(C+5) -> T(C+6): t_map, for the table and gone
  sidx_t           c0x_q, c0y_q;    // T(C+10) / T(C+11) -> T(C+12): the corrected start cell
  logic signed [IDX_W-1:0] ipe_x_q, ipe_y_q;  // T(C+10) / T(C+11) -> T(C+12): floor of the
                                              // end point

  logic [NS-1:0]   v_q;             // v_q[s]: stage Ts holds a ray
  logic [NT-1:C-2] iv;              // iv[s]: item stage Is holds an item (u of Ts, v of T(s+1))
  slot_idx_t       ph_q;            // phase: stage s holds the entry (ph_q - s) mod NT
  slot_idx_t       sl [NT];         // sl[s] = (ph_q - s) mod NT, s = 0 .. NT-1
  slot_idx_t       ss [10];         // ss[k] = sl[C+k] (I(C+0) .. I(C+9))

  always_comb begin
    for (int s = 0; s < NT; s++) begin
      sl[s] = (ph_q >= SW'(s)) ? ph_q - SW'(s) : ph_q + SW'(NT - s);
    end
    for (int k = 0; k < 10; k++) ss[k] = sl[C+k];
    for (int s = C - 2; s < NT; s++) iv[s] = v_q[s] || v_q[s+1];
  end

  // A ray enters at phase 3 (mod 4), so that it is in T0 at phase 0 and owns an entry that is a
  // multiple of 4 (its v item the next one).
  assign in_ready_o = (ph_q[1:0] == 2'd3);

  // ---- configuration-derived constants -------------------------------------------------------
  sidx_t size_s;                      // N = 2^n
  assign size_s   = sidx_t'(1) <<< cfg_i.n;

  // t0 = clip ? max(+0, 1 - H_root) : +0 (model: np.maximum(zeros, sub(one, h_root))).  While
  // idle, [P] adds -H_root (pa_q, from the configuration's root code: f24_from_unorm's
  // conversion, as a function here) and 1 * 1 ([B] on md_q = mt_q = 1): the word of
  // f24_add(1, -H_root) (a correctly rounded sum does not depend on the operands' order), as
  // early as with units of its own.
  function automatic f24_t unorm_to_f24(input logic [15:0] k, input logic bits16);
    logic [4:0]         lz;     // leading zeros of the code (garbage for 0, which is not used)
    /* verilator lint_off UNUSEDSIGNAL */  // (its low bits are below the sticky position)
    logic [31:0]        rep;    // the code repeated, then shifted so its leading one is on top
    /* verilator lint_on UNUSEDSIGNAL */
    logic signed [11:0] e;      // biased exponent: k / (2^W - 1) in [2^-(lz+1), 2^-lz)
    logic [15:0]        kw;     // the code, left-aligned in 16 bits
    kw  = bits16 ? k : {k[7:0], 8'd0};
    lz  = f24_clz32({kw, 16'd0});
    rep = bits16 ? ({k, k} << lz) : ({k[7:0], k[7:0], k[7:0], k[7:0]} << lz);
    e   = 12'sd62 - $signed({7'd0, lz});
    return (kw == '0) ? '0 : f24_round_pack(1'b0, e, rep[31 -: 17], rep[14], 1'b1);
  endfunction
  f24_t h_root, t0_d, t0_q;
  f24_ord_t ot0;                      // t0 in comparable form
  assign h_root = unorm_to_f24(cfg_i.root_code, cfg_i.bits16);
  always_ff @(posedge clk_i) begin
    if (idle_i) t0_q <= t0_d;
  end
  assign ot0 = f24_ord(t0_q);

  // ---- operand registers and registered table reads -----------------------------------------
  // A float unit takes its operands from registers, never through a table read or a select (a
  // 16:1 read multiplexer in front of a unit's clock would cost its fmax): a value a stage
  // I(C+k) needs is read from the table one clock earlier, in I(C+k-1), into a register (name
  // ending in k, _q), passed on from such a register, or forwarded from the value the earlier
  // stage writes.  Each loads while the stage before the reader holds an item: the u item's
  // value, then the v item's the clock after.  The operand registers of the shared units load
  // for their first operation (I(C+k-1)) or their second (I(C+k+5)): never in one clock, as
  // rays are a multiple of 4 clocks apart.
  f24_t      div_b_q;                       // I0: du, then dv (from the input)
  f24_t      pu_q;                          // [M] [E] I(C+0), I(C+6): u0 (and the checks)
  logic [IDX_W-1:0] kf_q;                   // [F] I(C-1): kb; I(C+5): the entry boundary
  logic [IDX_W-1:0] kg_q;                   // [G] I(C-1): W / H; I(C+5): the exit boundary
  f24_t      md_q;                          // [B] I(C+0), I(C+6): du (1 while idle)
  f24_t      mt_q;                          // [B] I(C+0): t0; I(C+6), I(C+7): t_end (1 idle)
  f24_t      pa_q;                          // [P] I(C+1), I(C+7): u0 (-H_root while idle)
  logic      bad2_q, bad3_q;                // I(C+2), I(C+3): bad_q passed on
  f24_t      mi_q;                          // [A] [C] I(C+3), I(C+9): 1/du
  logic      mvx_q;                         // [X] I(C+3), I(C+9): the axis moves
  f24_t      p0x_q;                         // [X] I(C+3), I(C+9): u0
  dir_t      dir3_q, dir4_q;                // I(C+3), I(C+4)
  // locate's candidates: one cell back, the estimate, one cell on (each clipped to [-1, N]).
  typedef struct packed {
    sidx_t back, est, fwd;
  } cand_t;
  cand_t     loc10_q;                       // I(C+10): computed in I(C+9)
  f24_t      d_r;                           // the table read for I(C+0)
  f24_t      d_r2;                          // the table read for I(C-1)

  // ---- float units ---------------------------------------------------------------------------
  // I0: the reciprocal; the divider advances while an item is in it (I0 .. I(F24_DIV_LAT-1),
  // rays in T0 .. T(F24_DIV_LAT)).
  f24_t      inv;
  f24_div #(.LAT(F24_DIV_LAT)) u_inv (.clk_i, .en_i(|v_q[F24_DIV_LAT:0]), .a_i(F24_ONE),
                                      .b_i(div_b_q), .y_o(inv));

  // [F] kb, the entry boundary; [G] W (H), the exit boundary (I(C-1), I(C+5)) as floats
  f24_t      kf_f, kg_f;
  f24_from_int #(.W(IDX_W)) u_kf (.clk_i, .en_i(iv[C-1] || iv[C+5]), .k_i(kf_q), .y_o(kf_f));
  f24_from_int #(.W(IDX_W)) u_kg (.clk_i, .en_i(iv[C-1] || iv[C+5]), .k_i(kg_q), .y_o(kg_f));
  // [B] du * t0 (I(C+0)), du * t_end (I(C+6)); 1 * 1 while idle
  f24_t      mb;
  f24_mul u_mb (.clk_i, .en_i(iv[C] || iv[C+6] || idle_i), .a_i(md_q), .b_i(mt_q), .y_o(mb));

  // [P] u0 + du t0 (I(C+1)), u0 + du t_end (I(C+7)); -H_root + 1 while idle
  f24_t      ap;
  logic      bad0;                    // this item's NaN / Inf and negative checks
  logic      bad1;                    // all of its checks: bad0, start >= W / H
  f24_add u_ap (.clk_i, .en_i(iv[C+1] || iv[C+2] || iv[C+7] || iv[C+8] || idle_i), .a_i(pa_q),
                .b_i(mb), .y_o(ap));
  // [M] kb - u0 (I(C+0)), entry - u0 (I(C+6)); [E] W - u0 (H - v0) (I(C+0)), exit - u0
  // (I(C+6)); 3 clocks (f24_add LAT 3: the alignment's sticky bits and the sum in two stages)
  f24_t      am, ae;
  f24_add #(.LAT(3)) u_am (.clk_i,
    .en_i(iv[C] || iv[C+1] || iv[C+2] || iv[C+6] || iv[C+7] || iv[C+8]), .a_i(kf_f),
    .b_i(f24_neg(pu_q)), .y_o(am));
  f24_add #(.LAT(3)) u_ae (.clk_i,
    .en_i(iv[C] || iv[C+1] || iv[C+2] || iv[C+6] || iv[C+7] || iv[C+8]), .a_i(kg_f),
    .b_i(f24_neg(pu_q)), .y_o(ae));
  assign t0_d = cfg_i.policy.clip ? f24_max(F24_POS_ZERO, ap) : F24_POS_ZERO;
  assign bad0 = !f24_is_finite(pu_q) || !f24_is_finite(md_q) || (pu_q[23] && !f24_is_zero(pu_q));
  // I(C+3): start >= W (H) when W - u0 (H - v0) is negative or +0 (correctly rounded: a
  // difference of a finite u0 and an integer is never rounded to zero)
  assign bad1 = bad3_q || ae[23] || (ae[22:0] == '0);

  // I(C+2): the direction (written to the table and forwarded to I(C+3))
  f24_t      d2;
  dir_t      dir2;
  assign d2   = d_q[ss[2]];
  assign dir2 = '{mv: !f24_is_zero(d2) && f24_is_finite(inv), neg: d2[23]};

  // [A] (kb - u0) / du (I(C+3)), (entry - u0) / du (I(C+9)); [C] (exit - u0) / du (I(C+9));
  // [X] floor of the position at t0 (I(C+3)), at t_end (I(C+9)) (u0 if the axis does not move)
  f24_t      ma, mc;
  logic signed [IDX_W-1:0] ix;
  logic unused_sat_x;
  f24_mul u_ma (.clk_i, .en_i(iv[C+3] || iv[C+9]), .a_i(am), .b_i(mi_q), .y_o(ma));
  f24_mul u_mc (.clk_i, .en_i(iv[C+9]), .a_i(ae), .b_i(mi_q), .y_o(mc));
  f24_to_index #(.W(IDX_W)) u_ix (.clk_i, .en_i(iv[C+3] || iv[C+9]),
    .a_i(mvx_q ? ap : p0x_q), .idx_o(ix), .sat_o(unused_sat_x));

  // I(C+4): the item's time of leaving the map (inf on an axis that does not move), the
  // estimated start cell (level 0) and the integers of its entry / exit boundaries (converted
  // in I(C+6)); T(C+5), with the v item here and the u item's time held in tmx_q: t_map and
  // t_end.
  sidx_t    est4;
  f24_t     tm4;
  assign est4 = clip_idx(sidx_t'(ix), -sidx_t'(1), size_s);
  assign tm4  = dir4_q.mv ? ma : F24_POS_INF;
  // t_map = min(tx, ty); t_end = t_map unless 1 < t_map.  Whether 1 < t_map is taken from
  // 1 < tx and 1 < ty beside the comparison of tx and ty (the three comparisons side by side,
  // not two in series).
  f24_ord_t otmx5, otmy5;
  logic     x_first5;                 // t_map is tx
  f24_t     t_map5, t_end5;
  assign otmx5    = f24_ord(tmx_q);
  assign otmy5    = f24_ord(tm4);
  assign x_first5 = ord_min_first(otmx5, otmy5);
  assign t_map5   = x_first5 ? tmx_q : tm4;
  assign t_end5   = (cfg_i.policy.clip && !(x_first5 ? ord_lt(f24_ord(F24_ONE), otmx5)
                                                     : ord_lt(f24_ord(F24_ONE), otmy5)))
                  ? t_map5 : F24_ONE;

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
  sidx_t c0_10;
  assign c0_10 = correct(loc10_q, f24_ord(ma), f24_ord(mc), ot0);

  // The registered reads, the operand registers and the per-item registers.
  assign d_r  = d_q[sl[C-1]];
  assign d_r2 = d_q[sl[C-2]];
  always_ff @(posedge clk_i) begin
    if (in_valid_i) begin
      v0_h_q <= in_v0_i;
      dv_h_q <= in_dv_i;
    end
    if (in_valid_i || v_q[0]) div_b_q <= in_valid_i ? in_du_i : dv_h_q;
    // I(C-1) (first operations) / I(C+5) (second operations); constants for t0 while idle
    if (iv[C+5]) begin
      pu_q <= p0_q[ss[5]];
      md_q <= d_q[ss[5]];
    end else if (iv[C-1]) begin
      pu_q <= p0_q[sl[C-1]];
      md_q <= d_r;
    end else if (idle_i) begin
      md_q <= F24_ONE;
    end
    // I(C-2) / I(C+4): the boundaries for [F] and [G] (the estimate's entry and exit from the
    // floor this clock)
    if (iv[C+4]) begin
      kf_q <= IDX_W'(est4 + sidx_t'(dir4_q.mv && dir4_q.neg));
      kg_q <= IDX_W'(est4 + sidx_t'(dir4_q.mv && !dir4_q.neg));
    end else if (iv[C-2]) begin
      kf_q <= (!d_r2[23] && !f24_is_zero(d_r2)) ? IDX_W'(v_q[C-1] ? cfg_i.height : cfg_i.width)
                                                 : '0;
      kg_q <= IDX_W'(v_q[C-1] ? cfg_i.height : cfg_i.width);
    end
    // t0 for I(C+0) (loaded in the clocks of I(C-1)), t_end for both items of I(C+6) (loaded
    // in T(C+5), where the v item's time arrives)
    if (v_q[C+5])     mt_q <= t_end5;
    else if (iv[C-1]) mt_q <= t0_q;
    else if (idle_i)  mt_q <= F24_ONE;
    // I(C+0) / I(C+6)
    if (iv[C] || iv[C+6]) pa_q <= pu_q;
    else if (idle_i)      pa_q <= f24_neg(h_root);
    if (iv[C])   bad_q  <= bad0;
    if (iv[C+1]) bad2_q <= bad_q;
    if (iv[C+2]) bad3_q <= bad2_q;
    if (v_q[C+3]) bad_u_q <= bad1;
    // I(C+2) / I(C+8)
    if (iv[C+8]) begin
      mi_q  <= inv_q[ss[8]];
      mvx_q <= dir_q[ss[8]].mv;
      p0x_q <= p0_q[ss[8]];
    end else if (iv[C+2]) begin
      mi_q  <= inv;
      mvx_q <= dir2.mv;
      p0x_q <= p0_q[ss[2]];
    end
    if (iv[C+2]) dir3_q <= dir2;
    if (iv[C+3]) dir4_q <= dir3_q;
    if (v_q[C+4]) tmx_q <= tm4;
    if (v_q[C+5]) t_map6_q <= t_map5;
    if (iv[C+9]) loc10_q <= candidates(est_q[ss[9]], dir_q[ss[9]], -sidx_t'(1), size_s);
    if (v_q[C+10]) begin
      c0x_q   <= c0_10;
      ipe_x_q <= ix;
    end
    if (v_q[C+11]) begin
      c0y_q   <= c0_10;
      ipe_y_q <= ix;
    end
  end

  // ---- pipeline and tables -------------------------------------------------------------------
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
    // in: the ray and its u item take the entry of stage NT-1, whose last reads are at this
    // clock's edge (that entry is stage 0's next clock); the v item the next entry, the clock
    // after, from the held inputs
    if (in_valid_i) id_q[sl[NT-1]] <= in_id_i;
    if (in_valid_i || v_q[0]) begin
      p0_q[sl[NT-1]] <= in_valid_i ? in_u0_i : v0_h_q;
      d_q[sl[NT-1]]  <= in_valid_i ? in_du_i : dv_h_q;
    end
    // A stage computes and writes only while it holds an item.
    // T(C+4): invalid = the u item's checks or the v item's (the v item in I(C+3))
    if (v_q[C+4]) invalid_q[sl[C+4]] <= bad_u_q || bad1;
    // I(C+2) -> I(C+3): reciprocal and direction
    if (iv[C+2]) begin
      inv_q[ss[2]] <= inv;
      dir_q[ss[2]] <= dir2;
    end
    // I(C+4) -> I(C+5): the start cell's estimate
    if (iv[C+4]) est_q[ss[4]] <= est4;
    // T(C+6): time of leaving the map; never enters
    if (v_q[C+6]) begin
      t_map_q[sl[C+6]] <= t_map6_q;
      gone_q[sl[C+6]]  <= ord_le(f24_ord(t_map6_q), ot0);
    end
  end

  // ---- T(C+12) .. T(C+14) = T(NS-1): start level (2 clocks), start cell, out -----------------
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
    .ex_i         (ipe_x_q),
    .ey_i         (ipe_y_q),
    .outside_o    (outside),
    .k_o          (k),
    .cx_o         (cx),
    .cy_o         (cy)
  );

  // The ray's table fields for the output: the ray's and its u item's read in T(NT-1) = T15
  // (the last stage that owns an entry), its v item's in I15 (T16), and carried to T(NS-1) in
  // registers.
  typedef struct packed {
    f24_t p0, d, inv;
    dir_t dir;
  } item_fields_t;
  typedef struct packed {
    logic [ID_W-1:0] id;
    item_fields_t    u, v;
    f24_t            t_map;
    logic            invalid, gone;
  } out_fields_t;
  item_fields_t it_r;       // the item in I15
  out_fields_t  out_q [NO]; // the fields of the ray in T16 (v item not yet) .. T(NS-1)
  assign it_r = '{p0: p0_q[sl[NT-1]], d: d_q[sl[NT-1]], inv: inv_q[sl[NT-1]],
                  dir: dir_q[sl[NT-1]]};
  always_ff @(posedge clk_i) begin
    if (v_q[NT-1]) begin
      out_q[0].id      <= id_q[sl[NT-1]];
      out_q[0].u       <= it_r;
      out_q[0].t_map   <= t_map_q[sl[NT-1]];
      out_q[0].invalid <= invalid_q[sl[NT-1]];
      out_q[0].gone    <= gone_q[sl[NT-1]];
    end
    if (v_q[NT]) out_q[1] <= '{id: out_q[0].id, u: out_q[0].u, v: it_r, t_map: out_q[0].t_map,
                               invalid: out_q[0].invalid, gone: out_q[0].gone};
    for (int o = 2; o < NO; o++) begin
      if (v_q[NT+o-1]) out_q[o] <= out_q[o-1];
    end
  end

  // One expression (not field by field), so that a simulator can evaluate it where it is used.
  assign out_ray_o = '{u0: out_q[NO-1].u.p0, v0: out_q[NO-1].v.p0, du: out_q[NO-1].u.d,
                       dv: out_q[NO-1].v.d, inv_du: out_q[NO-1].u.inv, inv_dv: out_q[NO-1].v.inv,
                       sx: out_q[NO-1].u.dir, sy: out_q[NO-1].v.dir, t_map: out_q[NO-1].t_map,
                       k: k, cx: cx, cy: cy, t: t0_q, crossed: 1'b0, prev_cross: 1'b0,
                       iters: '0, done: out_q[NO-1].invalid || out_q[NO-1].gone || outside,
                       hit: 1'b0, invalid: out_q[NO-1].invalid, capped: 1'b0, err: 1'b0};

  assign out_valid_o = v_q[NS-1];
  assign out_id_o    = out_q[NO-1].id;
  assign busy_o      = SETUP_BUSY_W'($countones(v_q));

  // The simulation checks are in traverse_setup_assert.sv (bound into every instance).

endmodule
