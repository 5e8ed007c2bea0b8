// SPDX-License-Identifier: Apache-2.0
// traverse_setup: the first mode of the traverse unit (model/traverse.py: setup() and the "first
// mode" block of _trace), a fixed-depth pipeline taking one ray every 4th clock at most, never
// stalling.  A ray may enter only in the clocks in_ready_o = 1 (one clock in four, from a free
// running phase; asserted: ray_phase, bound from traverse_setup_assert.sv; traverse_unit ANDs it
// into ray_ready_o), so any two rays in the pipeline are a multiple of 4 clocks apart.  The u (x)
// and v (y) axes share the float units, u in one clock and v in the next (as view_calc computes x
// and y), and most units serve two operations of an axis, KB stages apart (KB = 2 mod 4): the
// first in the two clocks of the 4 that are its phases, the second in the other two (as
// shade_unit schedules over 4 clocks).
//
// In: the ray's four numbers as f24 words (the model's ar.r() of the float64 ray).  Out,
// NS = traverse_pkg::setup_lat(ADD_LAT, MUL_LAT) clocks later (21 at (ADD_LAT, MUL_LAT) = (2, 1),
// 26 at (3, 2); SETUP_LAT at the package defaults): the ray record (traverse_pkg::ray_t) with
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
// register and combined with the v item's: invalid, t_map and t_end, the start cell and the end
// point's cell (into the start level).
//
// Shared units.  A unit that serves two operations of item stages Ia and Ia+KB is busy in the
// clocks of phase a, a+1 (mod 4) for the first and a+2, a+3 for the second: never both, as rays
// are a multiple of 4 clocks apart.  Every float unit takes its operands from registers: a
// unit's result (the same unit's for both operations: the boundary adders are fed by the same
// conversions at both stages, the position adder by the same multiplier, the crossing-time
// multipliers by the same boundary adders, the floor by the same position adder), or an operand
// register that a select loads one clock before the unit reads it (kf_q, kg_q, pu_q, md_q, mt_q,
// the last of pa_c_q, mi_q, mvx_q / p0x_q), never a select in front of a unit.  The boundary
// adders [M], [E] take ADD_LAT + 1 clocks (one more than [P], for the clock), their conversions
// CL clocks (f24_from_int LAT 2 where the schedule has a spare clock) before them.
//
// Stage schedule, from the units' latencies (localparams of the same names; T0 = the clock after
// in_valid_i; per-axis rows give the u item's stages, the v item's are one later; "a -> b": a
// unit takes operands at Ia, result at Ib; [X] names the unit).  The reciprocal starts at I0 and
// takes F24_DIV_LAT = 8 clocks (f24_pkg: the pipelined divider); the rest of the first mode
// starts C = F24_DIV_LAT - ADD_LAT clocks later, at I(C), so that 1/du is there (I(C+ADD_LAT))
// one stage before the crossing time [A] needs it.  Stages relative to I(C), then absolute at
// (ADD_LAT, MUL_LAT) = (2, 1) / (3, 2):
//   KA = ADD_LAT + 1          [A]'s first operation                        3 / 4
//   KX = ADD_LAT + MUL_LAT    [X]'s first operation (after [B] and [P])    3 / 5
//   KR = KX + 1               the first results of [A] and [X]             4 / 6
//   KB = setup_gap(ADD_LAT, MUL_LAT): the second operations, KR + 2 rounded up to 2 mod 4
//                                                                          6 / 10
//   KH = KB - 2               the first results, PAD = KH - KR clocks later 4 / 8 (PAD 0 / 2)
//   CL = PAD > 0 ? 2 : 1      [F], [G]: f24_from_int LAT (a spare clock)   1 / 2
//   KF = KB - 1 - CL          the estimate, PAD_E = KF - KR clocks later    4 / 7 (PAD_E 0 / 1)
//   KE = KR + KB              the second results                           10 / 16
//                                                                          (2, 1)      (3, 2)
//   I0        1/du (1/dv)                     f24_div                     I0 -> I8    I0 -> I8
//   I(C-1-CL) operand registers: the exit boundary of the map kb = du > 0 ? W : 0 [F] and W [G]
//             (H, H for v)                                                I4          I2
//   I(C-CL)   kb, W as floats [F], [G] f24_from_int LAT CL                I5 -> I6    I3 -> I5
//   I(C-1)    operand registers: du and t0 [B], u0                        I5          I4
//   I(C)      checks: NaN / Inf field, negative start                     I6          I5
//             kb - u0, W - u0 [M], [E] f24_add LAT ADD_LAT + 1            I6 -> I9    I5 -> I9
//             du * t0 [B] f24_mul LAT MUL_LAT                             I6 -> I7    I5 -> I7
//   I(C+MUL_LAT)  u0 + du t0 [P] f24_add LAT ADD_LAT (u0 passed on in pa_c_q)
//                                                                         I7 -> I9    I7 -> I10
//   I(C+ADD_LAT)  sx = sign(du) if du != 0 and 1/du finite                I8          I8
//   I(C+ADD_LAT+1): the checks | u0 >= W (W - u0 <= 0), held; the v item's a stage later:
//             invalid = u's | v's                                         I9, T10     I9, T10
//   I(C+KA)   (kb - u0) * (1/du) [A] f24_mul                              I9 -> I10   I9 -> I11
//   I(C+KX)   floor(position at t0) (u0 if sx = 0) [X] f24_to_index       I9 -> I10   I10 -> I11
//   I(C+KR)   tmx (inf if sx = 0); locate estimate c = clip(floor, -1, N) I10         I11
//   I(C+KF)   c, PAD_E clocks later: its entry / exit boundary integers (operand registers of
//             [F], [G])                                                   I10         I12
//   I(C+KH)   tmx, PAD clocks later, held a clock                         I10         I13
//   T(C+KH+1) (v item in I(C+KH)): t_map = min(tmx, ty); t_end = clip ? min(1, t_map) : 1
//                                                                         T11         T14
//   I(C+KB-CL) entry, exit boundary as floats [F], [G]                    I11 -> I12  I13 -> I15
//   I(C+KB-1) operand registers: du and t_end [B], u0                     I11         I14
//   T(C+KB)   gone = t_map <= t0                                          T12         T15
//   I(C+KB)   entry - u0, exit - u0 [M], [E]                              I12 -> I15  I15 -> I19
//             du * t_end [B]                                              I12 -> I13  I15 -> I17
//   I(C+KB+MUL_LAT)  u0 + du t_end [P]                                    I13 -> I15  I17 -> I20
//   I(C+KA+KB) (boundary - u0) * (1/du): crossing times [A], [C]          I15 -> I16  I19 -> I21
//   I(C+KX+KB) floor(position at t_end) (u0 if sx = 0) [X]                I15 -> I16  I20 -> I21
//   I(C+KE-1) locate's three candidates (the estimate, one cell back, one on; clipped to
//             [-1, N])                                                    I15         I20
//   I(C+KE)   locate correction: the candidate the crossing times choose (c0x, c0y registers),
//             the floor of the end point (ex, ey registers)               I16         I21
//   T(C+KE+2) start cell and end cell clipped to the map, outside, XOR  (traverse_start_level,
//   T(C+KE+3) start level k by bit length (leading-zero count)           T18 -> T20  T23 -> T25)
//   T(C+KE+4) = T(NS-1): gone |= start cell outside the map; cell >> k: out
// Units: [A] [B] [C] f24_mul, [M] [E] [P] f24_add, [F] [G] f24_from_int, [X] f24_to_index; all
// but [C] serve two operations KB stages apart ([P] and [B] the start time while idle).
// In the code, item stage I(C+k) is iv[C+k]; a ray stage Ts is v_q[s].
//
// Stage registers.  A ray's values move with it, one register per field and stage (f_s[s]: the
// field of the ray in Ts, or of the item in Is), as in traverse_loop's ring: a stage reads the
// fields it needs from its own stage's registers, and the stage that computes a value writes it
// into the next stage's register, from where it moves on every clock up to stage NT-1 (NT: the
// multiple of 4 from C + KE, 16 at (2, 1), 24 at (3, 2)); the output registers out_q carry it
// from T(NT) on.  Per-axis values (u0 / v0, du / dv, 1/du / 1/dv, the directions, locate's
// estimate) are item registers: the u item's value in a stage in one clock, the v item's in the
// next.  The id, invalid, t_map and gone are ray registers (the v item's clock carries nothing
// of use there).  A value a float unit takes as an operand is copied one clock early into a
// register (or passed on in registers from such a copy).  (Tables of NT entries in LUT RAM,
// indexed by a phase, would need a read port per reading stage, each a copy of the table and a
// multiplexer: up to five for u0, about 1,400 LUT4 more than the registers.)  A phase
// counter ph_q (mod 4) gives the clocks a ray may enter in.
//
// Clock enables: a float unit advances only while an item is in it, and holds its registers
// otherwise (less switching, and less work for a simulator).
//
// The start time t0 (0, or max(0, 1 - H_root) for the clip policy) is the same for every ray; it
// is derived from the configuration on [P] and [B] while the unit is idle (idle_i), the only
// time the configuration may change: t0_d is right 3 + ADD_LAT clocks after a change of cfg_i
// (6 at (3, 2)); t0_q loads it only after 1 + MUL_LAT + ADD_LAT idle clocks in a row (the last
// ray's operations leave [B] and [P] first) and holds otherwise.
module traverse_setup
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W    = 8,
  // Latencies of the float units (f24_add / f24_mul LAT): [P] runs at ADD_LAT (2 .. 3) and the
  // boundary adders [M], [E] at ADD_LAT + 1; [A], [B], [C] at MUL_LAT (1 .. 3).  The stage
  // schedule follows from them (the header); SETUP_LAT = setup_lat(ADD_LAT, MUL_LAT) clocks.
  parameter int unsigned ADD_LAT = pipe_pkg::F24_ADD_LAT,
  parameter int unsigned MUL_LAT = pipe_pkg::F24_MUL_LAT
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

  // The schedule (the header's stage table): item stage I(C+k) is "k" below.
  localparam int unsigned NS  = setup_lat(ADD_LAT, MUL_LAT);  // stages T0 .. T(NS-1)
  localparam int unsigned LE  = ADD_LAT + 1;                  // [M] [E]: f24_add LAT
  localparam int unsigned C   = F24_DIV_LAT - ADD_LAT;        // start of the paper's schedule
  localparam int unsigned KA  = ADD_LAT + 1;                  // [A] first operation (= LE)
  localparam int unsigned KX  = ADD_LAT + MUL_LAT;            // [X] first operation ([P] done)
  localparam int unsigned KR  = KX + 1;                       // results of [A] and [X]
  localparam int unsigned KB  = setup_gap(ADD_LAT, MUL_LAT);  // second operations (2 mod 4)
  localparam int unsigned KH  = KB - 2;                       // first results, delayed PAD
  localparam int unsigned PAD = KH - KR;                      // delay to keep KB = 2 mod 4
  localparam int unsigned CL  = (PAD > 0) ? 2 : 1;            // [F] [G]: f24_from_int LAT
  localparam int unsigned KF  = KB - 1 - CL;                  // [F] [G]'s second operands
  localparam int unsigned PAD_E = KF - KR;                    // the estimate's delay to KF
  localparam int unsigned KE  = KR + KB;                      // results of the second operations
  localparam int unsigned NT  = (C + KE + 3) / 4 * 4;         // stages with stage registers
  localparam int unsigned NO  = NS - NT;                      // output registers (T(NT) ..)
  if (ADD_LAT < 2 || ADD_LAT > 3 || MUL_LAT < 1 || MUL_LAT > 3 || F24_DIV_LAT < ADD_LAT + 2
      || KB % 4 != 2 || KH < KR || NS != C + KE + 5 || NO < 2 || (NS + 3) / 4 >= 2 ** SETUP_BUSY_W
      || (ADD_LAT == pipe_pkg::F24_ADD_LAT && MUL_LAT == pipe_pkg::F24_MUL_LAT
          && NS != SETUP_LAT)) begin : g_check_lat
    $error("traverse_setup: stage schedule does not add up to setup_lat(ADD_LAT, MUL_LAT)");
  end

  // Stage registers (see the header): f_s[s] is the field of the ray in Ts (the item in Is),
  // from the stage after the one that writes it (in brackets) to NT-1.
  logic [ID_W-1:0] id_s      [NT];             // [in]
  logic            invalid_s [C+LE+2:NT-1];    // [T(C+LE+1)] NaN / Inf field, negative start,
                                               // start >= W / H
  f24_t            t_map_s   [C+KB+1:NT-1];    // [T(C+KB)] time of leaving the map's extent
  logic            gone_s    [C+KB+1:NT-1];    // [T(C+KB)] t_map <= t0: never enters
  // Item registers: u0 / v0, du / dv [in: u item with the ray, v item the clock after];
  // 1 / du, 1 / dv and the directions [I(C+ADD_LAT)]; locate's estimate of the start cell
  // [I(C+KR)].
  f24_t            p0_s      [NT];
  f24_t            d_s       [NT];
  f24_t            inv_s     [C+ADD_LAT+1:NT-1];
  dir_t            dir_s     [C+ADD_LAT+1:NT-1];
  sidx_t           est_s     [C+KR+1:C+KE-1];
  // The v item's inputs, held from the ray's clock to its own.
  f24_t            v0_h_q, dv_h_q;
  // Values that live one clock or are held for the v item.
  logic            bad_c_q [LE];    // bad_c_q[j]: I(C+j+1): NaN / Inf field, negative, >= 2^16
  logic            bad_u_q;         // T(C+LE) -> T(C+LE+1): the u item's checks
  f24_t            tmx_q;           // T(C+KH) -> T(C+KH+1): the u item's time of leaving the map
  f24_t            t_map_b_q;       // T(C+KB-1) -> T(C+KB): t_map, for t_map_s and gone
  sidx_t           c0x_q, c0y_q;    // T(C+KE) / T(C+KE+1) -> T(C+KE+2): the corrected start cell
  logic signed [IDX_W-1:0] ipe_x_q, ipe_y_q;  // T(C+KE) / T(C+KE+1) -> T(C+KE+2): floor of the
                                              // end point

  logic [NS-1:0]   v_q;             // v_q[s]: stage Ts holds a ray
  logic [NT-1:C-1-CL] iv;           // iv[s]: item stage Is holds an item (u of Ts, v of T(s+1))
  logic [1:0]      ph_q;            // phase: steps every clock (mod 4)

  always_comb begin
    for (int s = C - 1 - CL; s < NT; s++) iv[s] = v_q[s] || v_q[s+1];
  end

  // A ray enters at phase 3 (mod 4), so that it is in Ts at phase s mod 4.
  assign in_ready_o = (ph_q == 2'd3);

  // ---- configuration-derived constants -------------------------------------------------------
  sidx_t size_s;                      // N = 2^n
  assign size_s   = sidx_t'(1) <<< cfg_i.n;

  // t0 = clip ? max(+0, 1 - H_root) : +0 (model: np.maximum(zeros, sub(one, h_root))).  While
  // idle, [P] adds -H_root (pa_c_q, from the configuration's root code: f24_from_unorm's word,
  // computed here in two registered steps) and 1 * 1 ([B] on md_q = mt_q = 1): the word of
  // f24_add(1, -H_root) (a correctly rounded sum does not depend on the operands' order), as
  // early as with units of its own.  H_root: the code's leading zeros and the code repeated to
  // 32 bits (hr_*_q), then the normalising shift and the rounding (h_root_q), so neither the
  // configuration register's wires nor the leading-zero count are in series with the shift and
  // the rounding's carry chain.  The code is static while rays are in flight; a new one reaches
  // t0_d in 3 + ADD_LAT clocks.  The sum of 1 * 1 and -H_root reaches t0_d once the unit has
  // been idle T0_WAIT = 1 + MUL_LAT + ADD_LAT clocks: before that [B] and [P] still deliver the
  // last ray's operations, so t0_q loads only after T0_WAIT idle clocks in a row and otherwise
  // keeps the start time of the last idle stretch that was long enough (a unit idle for a few
  // clocks between two rays keeps its t0; tb/traverse_setup's setup_idle_gaps).
  logic [15:0] hr_kw;                 // the code, left-aligned in 16 bits
  logic [4:0]  hr_lz_q;               // its leading zeros (garbage for 0, which is not used)
  logic        hr_zero_q;             // the code is 0
  logic [31:0] hr_rep_q;              // the code repeated to 32 bits
  /* verilator lint_off UNUSEDSIGNAL */  // (its low bits are below the sticky position)
  logic [31:0] hr_sh;                 // ... shifted so its leading one is on top
  /* verilator lint_on UNUSEDSIGNAL */
  f24_t        h_root_q;              // H_root = code / (2^W - 1), in [2^-(lz+1), 2^-lz)
  assign hr_kw = cfg_i.bits16 ? cfg_i.root_code : {cfg_i.root_code[7:0], 8'd0};
  assign hr_sh = hr_rep_q << hr_lz_q;
  always_ff @(posedge clk_i) begin
    hr_lz_q   <= f24_clz32({hr_kw, 16'd0});
    hr_zero_q <= (hr_kw == '0);
    hr_rep_q  <= cfg_i.bits16 ? {cfg_i.root_code, cfg_i.root_code} : {4{cfg_i.root_code[7:0]}};
    h_root_q  <= hr_zero_q ? '0 : f24_round_pack(1'b0, 12'sd62 - $signed({7'd0, hr_lz_q}),
                                                 hr_sh[31 -: 17], hr_sh[14], 1'b1);
  end
  localparam int unsigned T0_WAIT = 1 + MUL_LAT + ADD_LAT;  // idle clocks before t0_d is right
  localparam int unsigned T0_W    = $clog2(T0_WAIT + 1);
  logic [T0_W-1:0] t0_wait_q;         // idle clocks in a row before this one, up to T0_WAIT
  f24_t t0_d, t0_q;
  f24_ord_t ot0;                      // t0 in comparable form
  always_ff @(posedge clk_i) begin
    if (!rst_ni || !idle_i)                 t0_wait_q <= '0;
    else if (t0_wait_q != T0_W'(T0_WAIT))   t0_wait_q <= t0_wait_q + T0_W'(1);
    if (idle_i && t0_wait_q == T0_W'(T0_WAIT)) t0_q <= t0_d;
  end
  assign ot0 = f24_ord(t0_q);

  // ---- operand registers -------------------------------------------------------------------
  // A float unit takes its operands from registers, never through a select (a multiplexer in
  // front of a unit's clock would cost its fmax): a value a stage I(C+k) needs is copied from the
  // stage registers one clock earlier, in I(C+k-1), into a register, passed on from such a
  // register, or forwarded from the value the earlier stage writes.  Each loads
  // while the stage before the reader holds an item: the u item's value, then the v item's the
  // clock after.  The operand registers of the shared units load for their first operation
  // (I(C+k-1)) or their second (I(C+KB+k-1)): never in one clock, as rays are a multiple of 4
  // clocks apart and KB = 2 mod 4.
  f24_t      div_b_q;                       // I0: du, then dv (from the input)
  f24_t      pu_q;                          // [M] [E] I(C+0), I(C+KB): u0 (and the checks)
  logic [IDX_W-1:0] kf_q;                   // [F] I(C-CL): kb; I(C+KB-CL): the entry boundary
  logic [IDX_W-1:0] kg_q;                   // [G] I(C-CL): W / H; I(C+KB-CL): the exit boundary
  f24_t      md_q;                          // [B] I(C+0), I(C+KB): du (1 while idle)
  f24_t      mt_q;                          // [B] I(C+0): t0; I(C+KB), I(C+KB+1): t_end (1 idle)
  f24_t      pa_c_q [MUL_LAT];              // pa_c_q[j]: I(C+j+1), I(C+KB+j+1): u0, passed on
                                            // to [P] (pa_c_q[MUL_LAT-1]; -H_root while idle)
  f24_t      mi_q;                          // [A] [C] I(C+KA), I(C+KA+KB): 1/du
  logic      mvx_q;                         // [X] I(C+KX), I(C+KX+KB): the axis moves
  f24_t      p0x_q;                         // [X] I(C+KX), I(C+KX+KB): u0
  dir_t      dir_c_q [KH-ADD_LAT];          // dir_c_q[j]: the direction in I(C+ADD_LAT+1+j)
  dir_t      dir_k [ADD_LAT:KH];            // dir_k[k]: the direction of the item in I(C+k)
  // locate's candidates: one cell back, the estimate, one cell on (each clipped to [-1, N]).
  typedef struct packed {
    sidx_t back, est, fwd;
  } cand_t;
  cand_t     loc_q;                         // I(C+KE): computed in I(C+KE-1)
  f24_t      d_r;                           // du (dv) for I(C+0), in I(C-1)
  f24_t      d_r2;                          // du (dv) for I(C-CL), in I(C-1-CL)

  // ---- float units ---------------------------------------------------------------------------
  // Clock enables: OR of the item stages in which an operation of the unit is under way.
  logic en_fg, en_me, en_b, en_p, en_a, en_c, en_x;
  always_comb begin
    en_fg = 1'b0;
    for (int j = 0; j < CL; j++)      en_fg = en_fg || iv[C-CL+j] || iv[C+KB-CL+j];
    en_x  = iv[C+KX] || iv[C+KX+KB];
    en_me = 1'b0;
    en_b  = idle_i;
    en_p  = idle_i;
    en_a  = 1'b0;
    en_c  = 1'b0;
    for (int j = 0; j < LE; j++)      en_me = en_me || iv[C+j] || iv[C+KB+j];
    for (int j = 0; j < MUL_LAT; j++) begin
      en_b = en_b || iv[C+j] || iv[C+KB+j];
      en_a = en_a || iv[C+KA+j] || iv[C+KA+KB+j];
      en_c = en_c || iv[C+KA+KB+j];
    end
    for (int j = 0; j < ADD_LAT; j++) en_p = en_p || iv[C+MUL_LAT+j] || iv[C+KB+MUL_LAT+j];
  end

  // I0: the reciprocal; the divider advances while an item is in it (I0 .. I(F24_DIV_LAT-1),
  // rays in T0 .. T(F24_DIV_LAT)).
  f24_t      inv;
  f24_div #(.LAT(F24_DIV_LAT)) u_inv (.clk_i, .en_i(|v_q[F24_DIV_LAT:0]), .a_i(F24_ONE),
                                      .b_i(div_b_q), .y_o(inv));

  // [F] kb, the entry boundary; [G] W (H), the exit boundary (I(C-CL), I(C+KB-CL)) as floats;
  // CL = 2 clocks where the schedule has a spare one (PAD > 0), else 1
  f24_t      kf_f, kg_f;
  f24_from_int #(.W(IDX_W), .LAT(CL)) u_kf (.clk_i, .en_i(en_fg), .k_i(kf_q), .y_o(kf_f));
  f24_from_int #(.W(IDX_W), .LAT(CL)) u_kg (.clk_i, .en_i(en_fg), .k_i(kg_q), .y_o(kg_f));
  // [B] du * t0 (I(C+0)), du * t_end (I(C+KB)); 1 * 1 while idle
  f24_t      mb;
  f24_mul #(.LAT(MUL_LAT)) u_mb (.clk_i, .en_i(en_b), .a_i(md_q), .b_i(mt_q), .y_o(mb));

  // [P] u0 + du t0 (I(C+MUL_LAT)), u0 + du t_end (I(C+KB+MUL_LAT)); -H_root + 1 while idle
  f24_t      ap;
  logic      bad0;                    // this item's NaN / Inf and negative checks
  logic      bad1;                    // all of its checks: bad0, start >= W / H
  f24_add #(.LAT(ADD_LAT)) u_ap (.clk_i, .en_i(en_p), .a_i(pa_c_q[MUL_LAT-1]), .b_i(mb),
                                 .y_o(ap));
  // [M] kb - u0 (I(C+0)), entry - u0 (I(C+KB)); [E] W - u0 (H - v0) (I(C+0)), exit - u0
  // (I(C+KB)); ADD_LAT + 1 clocks (one more than [P], for the clock: the alignment's sticky
  // bits and the sum in two stages at ADD_LAT 2)
  f24_t      am, ae;
  f24_add #(.LAT(LE)) u_am (.clk_i, .en_i(en_me), .a_i(kf_f), .b_i(f24_neg(pu_q)), .y_o(am));
  f24_add #(.LAT(LE)) u_ae (.clk_i, .en_i(en_me), .a_i(kg_f), .b_i(f24_neg(pu_q)), .y_o(ae));
  assign t0_d = cfg_i.policy.clip ? f24_max(F24_POS_ZERO, ap) : F24_POS_ZERO;
  assign bad0 = !f24_is_finite(pu_q) || !f24_is_finite(md_q) || (pu_q[23] && !f24_is_zero(pu_q));
  // I(C+LE): start >= W (H) when W - u0 (H - v0) is negative or +0 (correctly rounded: a
  // difference of a finite u0 and an integer is never rounded to zero)
  assign bad1 = bad_c_q[LE-1] || ae[23] || (ae[22:0] == '0);

  // I(C+ADD_LAT) = I(F24_DIV_LAT): the direction (written to dir_s and passed on in
  // dir_c_q)
  f24_t      d2;
  dir_t      dir2;
  assign d2   = d_s[C+ADD_LAT];
  assign dir2 = '{mv: !f24_is_zero(d2) && f24_is_finite(inv), neg: d2[23]};
  always_comb begin
    dir_k[ADD_LAT] = dir2;
    for (int j = 0; j < KH - ADD_LAT; j++) dir_k[ADD_LAT+1+j] = dir_c_q[j];
  end

  // [A] (kb - u0) / du (I(C+KA)), (entry - u0) / du (I(C+KA+KB)); [C] (exit - u0) / du
  // (I(C+KA+KB)); [X] floor of the position at t0 (I(C+KX)), at t_end (I(C+KX+KB)) (u0 if the
  // axis does not move)
  f24_t      ma, mc;
  logic signed [IDX_W-1:0] ix;
  logic unused_sat_x;
  f24_mul #(.LAT(MUL_LAT)) u_ma (.clk_i, .en_i(en_a), .a_i(am), .b_i(mi_q), .y_o(ma));
  f24_mul #(.LAT(MUL_LAT)) u_mc (.clk_i, .en_i(en_c), .a_i(ae), .b_i(mi_q), .y_o(mc));
  f24_to_index #(.W(IDX_W)) u_ix (.clk_i, .en_i(en_x), .a_i(mvx_q ? ap : p0x_q), .idx_o(ix),
                                  .sat_o(unused_sat_x));

  // I(C+KR): the item's time of leaving the map (inf on an axis that does not move) and the
  // estimated start cell (level 0); I(C+KF), PAD_E clocks later: its entry / exit boundary
  // integers (converted in I(C+KB-CL) .. I(C+KB-1)); I(C+KH), PAD clocks later, and T(C+KH+1),
  // with the v item there and the u item's time held in tmx_q: t_map and t_end.
  sidx_t    est_r, est_h;
  f24_t     tm_r, tm_h;
  assign est_r = clip_idx(sidx_t'(ix), -sidx_t'(1), size_s);
  assign tm_r  = dir_k[KR].mv ? ma : F24_POS_INF;
  // KB = 2 mod 4 (the shared units' second operations in the other two clocks of the four):
  // the first results wait PAD clocks (the estimate PAD_E: [F] [G] take one of them)
  if (PAD > 0) begin : g_pad
    f24_t  tm_d_q  [PAD];
    always_ff @(posedge clk_i) begin
      for (int j = 0; j < PAD; j++) begin
        if (iv[C+KR+j]) tm_d_q[j] <= (j == 0) ? tm_r : tm_d_q[(j == 0) ? 0 : j-1];
      end
    end
    assign tm_h = tm_d_q[PAD-1];
  end else begin : g_no_pad
    assign tm_h = tm_r;
  end
  if (PAD_E > 0) begin : g_pad_e
    sidx_t est_d_q [PAD_E];
    always_ff @(posedge clk_i) begin
      for (int j = 0; j < PAD_E; j++) begin
        if (iv[C+KR+j]) est_d_q[j] <= (j == 0) ? est_r : est_d_q[(j == 0) ? 0 : j-1];
      end
    end
    assign est_h = est_d_q[PAD_E-1];
  end else begin : g_no_pad_e
    assign est_h = est_r;
  end
  // t_map = min(tx, ty); t_end = t_map unless 1 < t_map.  Whether 1 < t_map is taken from
  // 1 < tx and 1 < ty beside the comparison of tx and ty (the three comparisons side by side,
  // not two in series).
  f24_ord_t otmx, otmy;
  logic     x_first;                  // t_map is tx
  f24_t     t_map_c, t_end_c;
  assign otmx    = f24_ord(tmx_q);
  assign otmy    = f24_ord(tm_h);
  assign x_first = ord_min_first(otmx, otmy);
  assign t_map_c = x_first ? tmx_q : tm_h;
  assign t_end_c = (cfg_i.policy.clip && !(x_first ? ord_lt(f24_ord(F24_ONE), otmx)
                                                   : ord_lt(f24_ord(F24_ONE), otmy)))
                 ? t_map_c : F24_ONE;

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
  sidx_t c0_e;
  assign c0_e = correct(loc_q, f24_ord(ma), f24_ord(mc), ot0);

  // The operand registers and the per-item registers.
  assign d_r  = d_s[C-1];
  assign d_r2 = d_s[C-1-CL];
  always_ff @(posedge clk_i) begin
    if (in_valid_i) begin
      v0_h_q <= in_v0_i;
      dv_h_q <= in_dv_i;
    end
    if (in_valid_i || v_q[0]) div_b_q <= in_valid_i ? in_du_i : dv_h_q;
    // I(C-1) (first operations) / I(C+KB-1) (second operations); constants for t0 while idle
    if (iv[C+KB-1]) begin
      pu_q <= p0_s[C+KB-1];
      md_q <= d_s[C+KB-1];
    end else if (iv[C-1]) begin
      pu_q <= p0_s[C-1];
      md_q <= d_r;
    end else if (idle_i) begin
      md_q <= F24_ONE;
    end
    // I(C-1-CL) / I(C+KF): the boundaries for [F] and [G] (the estimate's entry and exit)
    if (iv[C+KF]) begin
      kf_q <= IDX_W'(est_h + sidx_t'(dir_k[KF].mv && dir_k[KF].neg));
      kg_q <= IDX_W'(est_h + sidx_t'(dir_k[KF].mv && !dir_k[KF].neg));
    end else if (iv[C-1-CL]) begin
      kf_q <= (!d_r2[23] && !f24_is_zero(d_r2)) ? IDX_W'(v_q[C-CL] ? cfg_i.height : cfg_i.width)
                                                 : '0;
      kg_q <= IDX_W'(v_q[C-CL] ? cfg_i.height : cfg_i.width);
    end
    // t0 for I(C+0) (loaded in the clocks of I(C-1)), t_end for both items of I(C+KB) (loaded
    // in T(C+KB-1), where the v item's time arrives)
    if (v_q[C+KB-1])  mt_q <= t_end_c;
    else if (iv[C-1]) mt_q <= t0_q;
    else if (idle_i)  mt_q <= F24_ONE;
    // I(C+0) .. I(C+MUL_LAT-1) / I(C+KB) .. : u0 passed on to [P]
    for (int j = 0; j < MUL_LAT; j++) begin
      if (iv[C+j] || iv[C+KB+j]) pa_c_q[j] <= (j == 0) ? pu_q : pa_c_q[(j == 0) ? 0 : j-1];
      else if (idle_i && j == MUL_LAT - 1) pa_c_q[j] <= f24_neg(h_root_q);
    end
    for (int j = 0; j < LE; j++) begin
      if (iv[C+j]) bad_c_q[j] <= (j == 0) ? bad0 : bad_c_q[(j == 0) ? 0 : j-1];
    end
    if (v_q[C+LE]) bad_u_q <= bad1;
    // I(C+KA-1) / I(C+KA+KB-1): 1/du for [A] and [C] (from the divider the first time)
    if (iv[C+KA+KB-1])  mi_q <= inv_s[C+KA+KB-1];
    else if (iv[C+KA-1]) mi_q <= inv;
    // I(C+KX-1) / I(C+KX+KB-1): the operands of [X]
    if (iv[C+KX+KB-1]) begin
      mvx_q <= dir_s[C+KX+KB-1].mv;
      p0x_q <= p0_s[C+KX+KB-1];
    end else if (iv[C+KX-1]) begin
      mvx_q <= dir_k[KX-1].mv;
      p0x_q <= p0_s[C+KX-1];
    end
    for (int j = 0; j < KH - ADD_LAT; j++) begin
      if (iv[C+ADD_LAT+j]) dir_c_q[j] <= dir_k[ADD_LAT+j];
    end
    if (v_q[C+KH]) tmx_q <= tm_h;
    if (v_q[C+KB-1]) t_map_b_q <= t_map_c;
    if (iv[C+KE-1]) loc_q <= candidates(est_s[C+KE-1], dir_s[C+KE-1], -sidx_t'(1), size_s);
    if (v_q[C+KE]) begin
      c0x_q   <= c0_e;
      ipe_x_q <= ix;
    end
    if (v_q[C+KE+1]) begin
      c0y_q   <= c0_e;
      ipe_y_q <= ix;
    end
  end

  // ---- pipeline and stage registers ---------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      v_q  <= '0;
      ph_q <= '0;
    end else begin
      v_q  <= {v_q[NS-2:0], in_valid_i};
      ph_q <= ph_q + 2'd1;
    end
  end

  // Every field moves on one stage per clock; the stage that computes a field writes the next
  // stage's register (what it writes in a clock without an item, or for the v item of a ray
  // field, is never read).
  always_ff @(posedge clk_i) begin
    // in: the ray and its u item enter T0 / I0; the v item the clock after, from the held inputs
    id_s[0] <= in_id_i;
    p0_s[0] <= in_valid_i ? in_u0_i : v0_h_q;
    d_s[0]  <= in_valid_i ? in_du_i : dv_h_q;
    for (int t = 1; t < NT; t++) begin
      id_s[t] <= id_s[t-1];
      p0_s[t] <= p0_s[t-1];
      d_s[t]  <= d_s[t-1];
    end
    // T(C+LE+1): invalid = the u item's checks or the v item's (the v item in I(C+LE))
    invalid_s[C+LE+2] <= bad_u_q || bad1;
    for (int t = C + LE + 3; t < NT; t++) invalid_s[t] <= invalid_s[t-1];
    // I(C+ADD_LAT) -> I(C+ADD_LAT+1): reciprocal and direction
    inv_s[C+ADD_LAT+1] <= inv;
    dir_s[C+ADD_LAT+1] <= dir2;
    for (int t = C + ADD_LAT + 2; t < NT; t++) begin
      inv_s[t] <= inv_s[t-1];
      dir_s[t] <= dir_s[t-1];
    end
    // I(C+KR) -> I(C+KR+1): the start cell's estimate
    est_s[C+KR+1] <= est_r;
    for (int t = C + KR + 2; t < C + KE; t++) est_s[t] <= est_s[t-1];
    // T(C+KB): time of leaving the map; never enters
    t_map_s[C+KB+1] <= t_map_b_q;
    gone_s[C+KB+1]  <= ord_le(f24_ord(t_map_b_q), ot0);
    for (int t = C + KB + 2; t < NT; t++) begin
      t_map_s[t] <= t_map_s[t-1];
      gone_s[t]  <= gone_s[t-1];
    end
  end

  // ---- T(C+KE+2) .. T(C+KE+4) = T(NS-1): start level (2 clocks), start cell, out -------------
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

  // The ray's fields for the output: the ray's and its u item's from T(NT-1) (the last stage
  // with stage registers), its v item's from I(NT-1) (T(NT)), carried to T(NS-1) in the output
  // registers (the id in out_id_q beside them).
  typedef struct packed {
    f24_t p0, d, inv;
    dir_t dir;
  } item_fields_t;
  typedef struct packed {
    item_fields_t    u, v;
    f24_t            t_map;
    logic            invalid, gone;
  } out_fields_t;
  item_fields_t    it_r;            // the item in I(NT-1)
  out_fields_t     out_q    [NO];   // the fields of the ray in T(NT) (v item not yet) .. T(NS-1)
  logic [ID_W-1:0] out_id_q [NO];   // its id
  assign it_r = '{p0: p0_s[NT-1], d: d_s[NT-1], inv: inv_s[NT-1], dir: dir_s[NT-1]};
  always_ff @(posedge clk_i) begin
    if (v_q[NT-1]) begin
      out_id_q[0]      <= id_s[NT-1];
      out_q[0].u       <= it_r;
      out_q[0].t_map   <= t_map_s[NT-1];
      out_q[0].invalid <= invalid_s[NT-1];
      out_q[0].gone    <= gone_s[NT-1];
    end
    if (v_q[NT]) begin
      out_id_q[1] <= out_id_q[0];
      out_q[1]    <= '{u: out_q[0].u, v: it_r, t_map: out_q[0].t_map,
                       invalid: out_q[0].invalid, gone: out_q[0].gone};
    end
    for (int o = 2; o < NO; o++) begin
      if (v_q[NT+o-1]) begin
        out_id_q[o] <= out_id_q[o-1];
        out_q[o]    <= out_q[o-1];
      end
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
  assign out_id_o    = out_id_q[NO-1];
  assign busy_o      = SETUP_BUSY_W'($countones(v_q));

  // The simulation checks are in traverse_setup_assert.sv (bound into every instance).

endmodule
