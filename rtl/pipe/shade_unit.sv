// SPDX-License-Identifier: Apache-2.0
// shade_unit: the colour-calculation unit (Park et al. 2013, Fig. 6, after the bilinear filter):
// normal-mapped Blinn-Phong shading of one hit pixel.  Specification: model/shade.py shade() in
// the f24 engine, bit for bit, with its 14-step op sequence (same ops, same order, same
// association):
//    1. n_c = sub(mul(M_c, 2), 1)
//    2. nn  = add(add(mul(nx, nx), mul(ny, ny)), mul(nz, nz));   3. nn = max(nn, EPS)
//    4. rn  = rsqrt(nn);  n_c = mul(n_c, rn)
//    5. vv  = add(add(mul(du, du), mul(dv, dv)), D2)
//    6. rv  = rsqrt(vv);  v = (mul(-du, rv), mul(-dv, rv), mul(D, rv))
//    7. h_c = add(l_c, v_c);  hh = add(add(mul(hx, hx), mul(hy, hy)), mul(hz, hz))
//    8. rh  = rsqrt(hh);  h_c = mul(h_c, rh)
//    9. ndl = max(dot(n, l), 0);  ndh = max(dot(n, h), 0)
//           dot(a, b) = add(add(mul(ax, bx), mul(ay, by)), mul(az, bz))
//   10. s = ndh; four times s = mul(s, s)
//   11. a = add(AMBIENT, mul(KD, ndl));  sp = mul(KS, s)
//   12. c_c = add(mul(C_c, a), sp);  13. c_c = min(max(c_c, 0), 1)
//   14. out_c = to_index(add(mul(c_c, 255), 0.5))
//
// Inputs per pixel: C = col_i (the filtered colour texel, engine values in [0, 1]), M = nrm_i (the
// filtered normal-map texel, encoded values in [0, 1]), du_i, dv_i (the ray).  Index 0 of col_i,
// nrm_i and rgb_o is R / x, 1 is G / y, 2 is B / z.  Output: three unorm8 codes.
//
// Configuration (cfg_i, shade_pkg::shade_cfg_t; static while the unit is busy; the driver
// precomputes each field with the model, exactly as shade() rounds it with its const()): the unit
// light vector l (three components), AMBIENT, KD, KS, D and D2 = mul(D, D).  Hard-wired
// (shade_pkg): EPS = 2^-40, 1, 0, 255 and 0.5; the constant 2 only appears as mul(M_c, 2).
//
// Fully pipelined, fixed latency SHADE_LAT = shade_pkg::shade_lat(ADD_LAT, MUL_LAT) enabled
// clocks (67 at the paper's depths (ADD_LAT, MUL_LAT) = (2, 1), 90 at (3, 2)), one pixel every
// 4th enabled clock at most at every depth (valid_i must not be 1 within 3 enabled clocks after a
// pixel; asserted: pixel_spacing).  In dm_pipeline a pixel needs two filtered quads, which come
// one per two clocks at most.
// Every register (valid, tag, data, the float units) advances only while en_i is 1, so the
// enclosing pipeline stalls the whole unit with en_i = 0.  A pixel is taken on an enabled edge with
// valid_i = 1; its result shows at valid_o / tag_o / rgb_o after SHADE_LAT enabled edges and holds
// while en_i is 0.  valid (and the core's valid bits, the phase and the hold flag) are reset by
// rst_ni (synchronous, active low, independent of en_i); data and tag registers have no reset.
//
// Alignment: ph_q counts enabled clocks modulo 4.  A pixel that comes with ph_q = 0 enters core
// stage S1 at once, one that comes with ph_q = 1, 2 or 3 waits 3, 2 or 1 clocks in hold registers
// and enters with the next ph_q = 0.  The result is complete in core stage CS = SHADE_LAT - 3; a
// pixel that waited w clocks is at the output in core S(CS + 3 - w) (res_q holds the result from
// CS to CS + 3), so the latency is fixed.  Every two pixels in the core are thus a multiple of 4
// clocks apart, and a float unit serves up to four operations of a pixel whose stages differ
// pairwise by amounts not divisible by 4: pixel p at Sa, Sb, ..., any later pixel at Sa + 4j,
// Sb + 4j, ..., never in the same clock (asserted: core_aligned, and unit_once per shared unit).
//
// Operand registers: no float unit takes an operand through a select.  A shared unit's operands
// are registers of its own (op<unit>_a_q, _b_q), loaded in the clock before each operation by a
// select on the phase of that clock (the unit's own copy of ph_q, see "phase replicas"), so a
// phase register, a select and the unit's DSP or first adder stage are never in one clock (the
// routed top's slowest path was a unit's result through the next one's 4:1 select into its DSP).
// An operation whose operand is another unit's result therefore starts a clock after that result
// (operands selected in Sa-1, the unit in Sa); an operand made earlier is read from a tap of its
// source's delay chain (tp[src][k - b] in stage k for a value made in Sb), at no cost.  A unit fed
// by one source only (a register or another unit's result register) takes it directly.  Holding
// an operand for the second operation of a stream is a load enable of its register.
// Three-component values run as two lanes: lane 0 carries x in stage s and z in s+1 through the
// same registers ("stream"), lane 1 carries y in s; the tail runs R, G, B on one lane.
//
// Core stage schedule.  Latencies: f24_add ADD_LAT, f24_mul MUL_LAT, f24_rsqrt 3
// (pipe_pkg::F24_RSQRT_LAT: table / product + sum / round, over 120 MHz; at 2 clocks it limits
// the unit to below 60 MHz), f24_round_index ADD_LAT + 1 (the add and floor it replaces).
// Every stage is a localparam computed from ADD_LAT and MUL_LAT by shade_pkg::shade_op_stage:
// the 41 shared-unit operations, in a fixed priority order (the critical path first), each take
// the first stage a after their operands' results (a >= b + 1 for a result in Sb; the inputs are
// in S0) whose phase a mod 4 (and a + 1 for a stream) their unit has free.  "@a/a'": the unit
// works on the operands in Sa at (2, 1), Sa' at (3, 2) (a stream: x in Sa, z in Sa + 1):
//   u_uv2hy2 (f24_mul): du^2 @1/1 / h_y^2 @18/23
//   u_dvnc (f24_mul):   dv^2 @1/1 / n_x rn, n_z rn @19/22 / C_y a @46/68
//   u_nc (f24_add):     n_x - 1, n_z - 1 @1/1 (n = 2M - 1, 2M_z waits a clock in m2z_q) /
//                       c_R, c_B = C_x a + sp, C_z a + sp @55/75
//   u_nua (f24_add):    n_y - 1 @1/1 / du^2 + dv^2 @3/4 / a = AMBIENT + KD ndl @42/62 /
//                       c_G = C_y a + sp @56/75
//   u_nv (f24_add):     vv = (du^2 + dv^2) + D2 @6/8 / nn = (nx2 + ny2) + nz2 @9/13 /
//                       hx2 + hy2 @20/26 / hh = (hx2 + hy2) + hz2 @23/31
//   u_rvnh (f24_rsqrt): rv = rsqrt(vv) @9/12 / rn = rsqrt(max(nn, EPS)) @15/18 /
//                       rh = rsqrt(hh) @26/35
//   u_ny2h (f24_mul):   n_y^2 @4/5 / v_y = -dv rv @13/16 / h_x rh, h_z rh @30/42
//   u_va (f24_mul):     v_x = -du rv, v_z = D rv @13/16
//   u_nxh (f24_add):    nx2 + ny2 @6/9 / h_x = l_x + v_x, h_z = l_z + v_z @15/19 /
//                       nlx + nly @25/34
//   u_hd (f24_add):     h_y = l_y + v_y @15/19 / nhx + nhy @34/48 /
//                       dot(n, l) = (nlx + nly) + nlz, dot(n, h) = (nhx + nhy) + nhz @36/53
//   u_hkd (f24_mul):    h_x^2, h_z^2 @18/23 / KD ndl @40/58
//   u_nunh1 (f24_mul):  n_y rn @19/23 / n_x h_x, n_z h_z @32/45
//   u_hunh1 (f24_mul):  n_y l_y @21/28 / h_y rh @30/39 / n_y h_y @32/42
//   u_caa (f24_mul):    C_x a, C_z a @45/66 / sp = KS s^16 @51/72
//   u_sq (f24_mul):     s = ndh^2 @41/59 / s^4 @43/62 / s^8 @46/65 / s^16 @48/68 (each square
//                       fed back through the unit's operand register)
// Fed directly (no select): u_nsqa n_x^2, n_z^2 from u_nc's result (@3/4); u_nla n_x l_x, n_z l_z
// from u_dvnc's (@20/24, l_x / l_z by a select); ndl = max(dot(n, l), 0) and then ndh in one
// register (m_q); max(nn, EPS) in nnm_q.
// The tail: the clamp min(max(c, 0), 1) takes c_R in C0 = shade_clamp_stage (57/78; c_G a stage
// later, c_B two), then one lane for the three channels a stage apart: c 255 (u_k, from C0 + 1),
// floor(c 255 + 0.5) -> unorm8 (u_idx, f24_round_index, from C0 + 1 + MUL_LAT, ADD_LAT + 1
// clocks); R and G held, the result complete in CS = C0 + MUL_LAT + ADD_LAT + 4 (64/87).
// Output: a pixel that waited 3 clocks shows its result from core CS directly, the others from
// res_q (loaded in CS); valid and tag delayed S0 -> S(SHADE_LAT) (pipe_valid_tag).
//
// Delay lines: a source's taps are registers, but for its longest wait between two taps that
// are read (LO to HI, tap_gap): that wait is one pipe_delay of HI - LO enabled clocks, a RAM
// circular buffer (LUT RAM or EBR, as Yosys maps it) when HI - LO >= DELAY_RAM_MIN: by default
// (32) the colour lanes C_x / C_z and C_y from S0 to the products C a (65 and 67 clocks at
// (3, 2)); from 8 on also the ray's du, dv, and the results that wait 11 to 20 clocks for their
// last reader.  A RAM line advances
// only while en_i is 1 (its read register holds its word through a stall), so the taps, the
// pixels and the latency are the registers' (DELAY_RAM_MIN = 0 builds registers only).
//
// Float units: 12 f24_mul (all shared: u_dvnc, u_ny2h and u_sq with four operations, u_hkd,
// u_nunh1, u_hunh1, u_caa and u_k with three, 4 with two), 5 f24_add (all shared: u_nc, u_nua,
// u_nv, u_nxh and u_hd with four: the 20 additions fill the 20 slots, 5 units x 4 phases), 1
// f24_rsqrt (three operations), 1 f24_round_index #(9) (three: the tail's + 0.5 and floor,
// to_index(add(c 255, 0.5)), in one unit); no f24_cmp.  Exact logic (no rounding involved, each
// into one register): 3 doublers, max(nn, EPS), one max(., 0) for ndl then ndh, and 1 clamp.
//
// Exact parts, bit-identical to the model:
// - mul(M_c, 2) is an exponent increment: e = 126 overflows to Inf, zeros and subnormal patterns
//   give a zero of the same sign, Inf stays, NaN gives F24_NAN: exactly f24_mul(M_c, 2.0).
// - The model's max / min are numpy.maximum / numpy.minimum on float64: a NaN operand gives NaN, and
//   equal operands (+0 and -0) give the second one (the constant).  Comparisons use the order of
//   f24_cmp (-0 == +0, subnormal patterns read as zeros).  A NaN passed on here is the operand
//   itself; every consumer is a float unit, which turns any NaN into F24_NAN (and f24_round_index
//   gives 0 for NaN, as the model's to_index does).
// - -du, -dv: the sign bit flipped (the model's float64 negation).
// - The model clips the index to [0, 255]; after the clamp c 255 + 0.5 is in [0.5, 255.5] or NaN
//   (-> 0), so a 9-bit index is exact and its low 8 bits are the code.
module shade_unit
  import f24_pkg::*;
  import shade_pkg::*;
#(
  parameter int unsigned TAG_W   = 8,  // side-band bits (pixel address, fragment id, ...) carried
                                       // unchanged from tag_i to tag_o alongside the pixel
  parameter int unsigned ADD_LAT = pipe_pkg::F24_ADD_LAT,  // every f24_add's LAT (2 .. 4); the
                                       // schedule and SHADE_LAT follow (shade_pkg::shade_lat)
  parameter int unsigned MUL_LAT = pipe_pkg::F24_MUL_LAT,  // every f24_mul's LAT (1 .. 3)
  parameter int unsigned DELAY_RAM_MIN = 32 // a value's wait of this many enabled clocks or more
                                       // between two of its taps is a RAM line (pipe_delay;
                                       // 32: the colour lanes only, in EBR; 8: the waits of
                                       // 11-20 clocks too, in LUT RAM, fewer FF for more LUT4;
                                       // 0: registers only; the same results and latency)
) (
  input  logic             clk_i,
  input  logic             rst_ni,   // synchronous, active low: clears the valid bits
  input  logic             en_i,     // clock enable of the whole pipeline (0 = stall)
  input  shade_cfg_t       cfg_i,    // per-frame constants; static while busy
  input  logic             valid_i,
  input  logic [TAG_W-1:0] tag_i,
  input  f24_t [2:0]       col_i,    // C: the filtered colour texel (R, G, B at 0, 1, 2)
  input  f24_t [2:0]       nrm_i,    // M: the filtered normal-map texel (x, y, z at 0, 1, 2)
  input  f24_t             du_i,     // the ray: texels along u per unit of depth
  input  f24_t             dv_i,     // along v
  output logic             valid_o,
  output logic [TAG_W-1:0] tag_o,
  output logic [2:0][7:0]  rgb_o     // unorm8 codes (R, G, B at 0, 1, 2)
);

  localparam int unsigned RSQRT_LAT = pipe_pkg::F24_RSQRT_LAT;
  localparam int unsigned IDX_LAT   = pipe_pkg::F24_TO_INDEX_LAT;
  localparam int unsigned NS = shade_lat(ADD_LAT, MUL_LAT);  // stages S1 .. SNS
  localparam int unsigned CS = NS - 3;                        // core stages S1 .. SCS

  // ---- the schedule (shade_pkg::shade_op_stage): S_<op> the stage an operation's unit works on
  // its operands in, R_<op> its result's stage (x of a stream; z a stage later) ---------------
  localparam int unsigned S_DU2  = shade_op_stage(OP_DU2,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_NY   = shade_op_stage(OP_NY,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_NY2  = shade_op_stage(OP_NY2,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_DV2  = shade_op_stage(OP_DV2,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_UV   = shade_op_stage(OP_UV,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_VV   = shade_op_stage(OP_VV,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_RV   = shade_op_stage(OP_RV,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_VY   = shade_op_stage(OP_VY,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_VXZ  = shade_op_stage(OP_VXZ,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_HXZ  = shade_op_stage(OP_HXZ,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_HXZ2 = shade_op_stage(OP_HXZ2, ADD_LAT, MUL_LAT);
  localparam int unsigned S_HY   = shade_op_stage(OP_HY,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_HY2  = shade_op_stage(OP_HY2,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_HXY2 = shade_op_stage(OP_HXY2, ADD_LAT, MUL_LAT);
  localparam int unsigned S_HH   = shade_op_stage(OP_HH,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_RH   = shade_op_stage(OP_RH,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_HUY  = shade_op_stage(OP_HUY,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_HUXZ = shade_op_stage(OP_HUXZ, ADD_LAT, MUL_LAT);
  localparam int unsigned S_NXZ  = shade_op_stage(OP_NXZ,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_NXY2 = shade_op_stage(OP_NXY2, ADD_LAT, MUL_LAT);
  localparam int unsigned S_NN   = shade_op_stage(OP_NN,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_RN   = shade_op_stage(OP_RN,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_NUXZ = shade_op_stage(OP_NUXZ, ADD_LAT, MUL_LAT);
  localparam int unsigned S_NHXZ = shade_op_stage(OP_NHXZ, ADD_LAT, MUL_LAT);
  localparam int unsigned S_NUY  = shade_op_stage(OP_NUY,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_NHY  = shade_op_stage(OP_NHY,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_NHXY = shade_op_stage(OP_NHXY, ADD_LAT, MUL_LAT);
  localparam int unsigned S_NLY  = shade_op_stage(OP_NLY,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_NLXY = shade_op_stage(OP_NLXY, ADD_LAT, MUL_LAT);
  localparam int unsigned S_DOTS = shade_op_stage(OP_DOTS, ADD_LAT, MUL_LAT);
  localparam int unsigned S_KDN  = shade_op_stage(OP_KDN,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_A    = shade_op_stage(OP_A,    ADD_LAT, MUL_LAT);
  localparam int unsigned S_CYA  = shade_op_stage(OP_CYA,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_S2   = shade_op_stage(OP_S2,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_S4   = shade_op_stage(OP_S4,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_S8   = shade_op_stage(OP_S8,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_S16  = shade_op_stage(OP_S16,  ADD_LAT, MUL_LAT);
  localparam int unsigned S_SP   = shade_op_stage(OP_SP,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_CG   = shade_op_stage(OP_CG,   ADD_LAT, MUL_LAT);
  localparam int unsigned S_CAXZ = shade_op_stage(OP_CAXZ, ADD_LAT, MUL_LAT);
  localparam int unsigned S_CRB  = shade_op_stage(OP_CRB,  ADD_LAT, MUL_LAT);

  localparam int unsigned R_DU2  = S_DU2 + MUL_LAT,   R_NY   = S_NY + ADD_LAT,
                          R_NY2  = S_NY2 + MUL_LAT,   R_DV2  = S_DV2 + MUL_LAT,
                          R_UV   = S_UV + ADD_LAT,    R_VV   = S_VV + ADD_LAT,
                          R_RV   = S_RV + RSQRT_LAT,  R_VY   = S_VY + MUL_LAT,
                          R_VXZ  = S_VXZ + MUL_LAT,   R_HXZ  = S_HXZ + ADD_LAT,
                          R_HXZ2 = S_HXZ2 + MUL_LAT,  R_HY   = S_HY + ADD_LAT,
                          R_HY2  = S_HY2 + MUL_LAT,   R_HXY2 = S_HXY2 + ADD_LAT,
                          R_HH   = S_HH + ADD_LAT,    R_RH   = S_RH + RSQRT_LAT,
                          R_HUY  = S_HUY + MUL_LAT,   R_HUXZ = S_HUXZ + MUL_LAT,
                          R_NXZ  = S_NXZ + ADD_LAT,   R_NXY2 = S_NXY2 + ADD_LAT,
                          R_NN   = S_NN + ADD_LAT,    R_RN   = S_RN + RSQRT_LAT,
                          R_NUXZ = S_NUXZ + MUL_LAT,  R_NHXZ = S_NHXZ + MUL_LAT,
                          R_NUY  = S_NUY + MUL_LAT,   R_NHY  = S_NHY + MUL_LAT,
                          R_NHXY = S_NHXY + ADD_LAT,  R_NLY  = S_NLY + MUL_LAT,
                          R_NLXY = S_NLXY + ADD_LAT,  R_DOTS = S_DOTS + ADD_LAT,
                          R_KDN  = S_KDN + MUL_LAT,   R_A    = S_A + ADD_LAT,
                          R_CYA  = S_CYA + MUL_LAT,   R_CG   = S_CG + ADD_LAT,
                          R_CAXZ = S_CAXZ + MUL_LAT,  R_CRB  = S_CRB + ADD_LAT,
                          R_S2   = S_S2 + MUL_LAT,    R_S4   = S_S4 + MUL_LAT,
                          R_S8   = S_S8 + MUL_LAT,    R_S16  = S_S16 + MUL_LAT,
                          R_SP   = S_SP + MUL_LAT;
  // the units fed directly (no select) and the exact registers
  localparam int unsigned S_NSQ = R_NXZ;                  // u_nsqa: n_x^2, n_z^2 (from u_nc)
  localparam int unsigned R_NSQ = S_NSQ + MUL_LAT;
  localparam int unsigned S_NL  = R_NUXZ;                 // u_nla: n_x l_x, n_z l_z (from u_dvnc)
  localparam int unsigned R_NL  = S_NL + MUL_LAT;
  localparam int unsigned B_NNM = R_NN + 1;               // max(nn, EPS) in nnm_q
  localparam int unsigned B_M   = R_DOTS + 1;             // ndl in m_q (ndh a stage later)
  localparam int unsigned C0    = shade_clamp_stage(ADD_LAT, MUL_LAT);  // the clamp takes c_R
  localparam int unsigned F_R   = C0 + 1 + MUL_LAT + ADD_LAT + IDX_LAT;  // R's floor (G, B after)

  // Elaboration checks: the inputs are only in S0 (their operations are the first of their
  // units, so in S1 at any depth), the clamp's sources are there when it takes them, the stream
  // ops got their two phases (each unit's operations distinct mod 4: the assertion unit_once).
  if (S_DU2 != 1 || S_DV2 != 1 || S_NY != 1 || S_NXZ != 1 || R_CRB > C0 || R_CG > C0 + 1
      || F_R + 2 != CS || NS != shade_pkg::shade_lat(ADD_LAT, MUL_LAT)) begin : g_check_sched
    $error("shade_unit: the schedule does not fit its assumptions");
  end

  localparam f24_t NEG_ONE = SHADE_ONE ^ 24'h800000;  // sub(x, 1) = add(x, -1)

  // ---- exact helpers ---------------------------------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // the sign bit does not make a NaN
  function automatic logic is_nan(input f24_t x);
    return (x[22:16] == EXP_SPEC) && (x[15:0] != 16'd0);
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // Order-preserving key (f24_cmp's order): zeros of either sign and subnormal patterns give 2^23.
  function automatic logic [23:0] order_key(input f24_t x);
    return (x[22:16] == 7'd0) ? 24'h800000 : x[23] ? {1'b0, ~x[22:0]} : {1'b1, x[22:0]};
  endfunction

  // a > b, false when either is NaN.
  function automatic logic gt(input f24_t a, input f24_t b);
    return !is_nan(a) && !is_nan(b) && (order_key(a) > order_key(b));
  endfunction

  // numpy.maximum / numpy.minimum: NaN if either operand is NaN, the second operand when equal.
  function automatic f24_t max_np(input f24_t a, input f24_t b);
    return (is_nan(a) || gt(a, b)) ? a : b;
  endfunction

  function automatic f24_t min_np(input f24_t a, input f24_t b);
    return (is_nan(a) || gt(b, a)) ? a : b;
  endfunction

  // mul(x, 2) exactly as f24_mul computes it.
  function automatic f24_t dbl(input f24_t x);
    logic [6:0] e;
    e = x[22:16];
    return (e == EXP_SPEC) ? ((x[15:0] != 16'd0) ? F24_NAN : x)
         : (e == 7'd0)     ? {x[23], 23'd0}
         : (e == 7'd126)   ? {x[23], EXP_SPEC, 16'd0}
         :                   {x[23], e + 7'd1, x[15:0]};
  endfunction

  // ---- configuration --------------------------------------------------------------------------
  f24_t [2:0] light;
  assign light = {cfg_i.light_z, cfg_i.light_y, cfg_i.light_x};

  // ---- valid and tag: S1 .. SNS (stage_v[k]: a pixel entered k enabled clocks ago) ---------
  /* verilator lint_off UNUSEDSIGNAL */  // the assertion reads stage 1
  logic [NS:1] stage_v;
  /* verilator lint_on UNUSEDSIGNAL */
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(NS)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o(stage_v));

  // ---- alignment: the core takes pixels on every 4th enabled clock only -----------------------
  // ph_q counts enabled clocks modulo 4.  A pixel that comes with ph_q = 0 enters core stage 1 at
  // once; one that comes with ph_q = 1, 2 or 3 waits in the hold registers (hv_q) until ph_q = 0
  // (3, 2 or 1 clocks) and enters then, so every two pixels in the core are a multiple of 4
  // clocks apart, and cv_q[k] = 1 (a pixel in core stage k) only when ph_q = k mod 4.
  logic [1:0]      ph_q;            // enabled clocks modulo 4
  logic            hv_q;            // a pixel waits in the hold registers
  logic [CS:1]     cv_q;            // core stage valid bits
  f24_t [2:0]      hnrm_q, hcol_q;  // the hold registers (no reset)
  f24_t            hdu_q, hdv_q;
  f24_t [2:0]      in_nrm, in_col;  // the pixel entering core stage 1
  f24_t            in_du, in_dv;
  assign in_nrm = hv_q ? hnrm_q : nrm_i;
  assign in_col = hv_q ? hcol_q : col_i;
  assign in_du  = hv_q ? hdu_q  : du_i;
  assign in_dv  = hv_q ? hdv_q  : dv_i;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      ph_q <= 2'd0;
      hv_q <= 1'b0;
      cv_q <= '0;
    end else if (en_i) begin
      ph_q <= ph_q + 2'd1;
      hv_q <= (ph_q == 2'd0) ? 1'b0 : (hv_q || valid_i);
      cv_q <= {cv_q[CS-1:1], (ph_q == 2'd0) && (hv_q || valid_i)};
    end
  end

  // ---- phase replicas: the shared units' operand selects ----------------------------------------
  // A shared unit's operation of core stage a is the only one it has when ph_q = a mod 4 (the
  // core's pixels are all in stages of phase ph_q: core_aligned), so its operand select needs the
  // phase only, not cv_q[a]: whichever operand it picks in a clock with no pixel at its stages is
  // never read.  Each select has a one-hot copy of ph_q of its own (ps_q[u][r] = (ph_q == r)),
  // which the placer keeps next to it: a select driven by cv_q[1], shared by five units, was
  // 2.5 ns of routing into an adder's stage 1 (77 MHz out of context).  The copies are not
  // merged by synthesis: each register's next value is its own rotation.
  localparam int unsigned NPS = 17;  // operand selects (units and the clamp's)
  localparam int unsigned PS_UV2HY2 = 0,  PS_DVNC = 1,   PS_NUA = 2,    PS_NV = 3,
                          PS_NY2H = 4,    PS_VA = 5,     PS_NXH = 6,    PS_HD = 7,
                          PS_HKD = 8,     PS_RVNH = 9,   PS_NUNH1 = 10, PS_NLA = 11,
                          PS_HUNH1 = 12,  PS_CAA = 13,   PS_NC = 14,    PS_CL = 15,
                          PS_SQ = 16;
  logic [3:0] ps_q [NPS];

  for (genvar u = 0; u < NPS; u++) begin : g_ps
    always_ff @(posedge clk_i) begin
      if (!rst_ni)   ps_q[u] <= 4'b0001;
      else if (en_i) ps_q[u] <= {ps_q[u][2:0], ps_q[u][3]};
    end
  end

  // The clock of core stage a (given a phase replica p).
  function automatic logic at(input logic [3:0] p, input int unsigned a);
    return p[a % 4];
  endfunction

  always_ff @(posedge clk_i) begin
    if (en_i && valid_i && ph_q != 2'd0) begin
      hnrm_q <= nrm_i;
      hcol_q <= col_i;
      hdu_q  <= du_i;
      hdv_q  <= dv_i;
    end
  end

  // ---- float-unit outputs -----------------------------------------------------------------
  f24_t uv2hy2_y;   // du^2, h_y^2
  f24_t dvnc_y;     // dv^2, unit normal x, z (stream), C_y a
  f24_t nc_y;       // n_x, n_z (stream); c_R, c_B = C a + sp (stream)
  f24_t nua_y;      // n_y, du^2 + dv^2, a, c_G
  f24_t nv_y;       // vv, nn, hx2 + hy2, hh
  f24_t nsqa_y;     // n_x^2, n_z^2 (stream)
  f24_t ny2h_y;     // n_y^2, v_y, unit half vector x, z (stream)
  f24_t va_y;       // v_x, v_z (stream)
  f24_t nxh_y;      // nx2 + ny2, h_x, h_z (stream), nlx + nly
  f24_t hd_y;       // h_y, nhx + nhy, dot(n, l), dot(n, h) (a stage later)
  f24_t hkd_y;      // h_x^2, h_z^2 (stream), KD ndl
  f24_t rvnh_y;     // rv, rn, rh
  f24_t nunh1_y;    // unit normal y, n_x h_x, n_z h_z (stream)
  f24_t nla_y;      // n_x l_x, n_z l_z (stream)
  f24_t hunh1_y;    // n_y l_y, unit half vector y, n_y h_y
  f24_t sq_y;       // s = ndh^2, s^4, s^8, s^16
  f24_t caa_y;      // C_x a, C_z a (stream), sp = KS s^16
  f24_t k_y;        // c 255 (R, then G and B a stage apart each)
  logic signed [8:0] idx;  // floor(c 255 + 0.5): R (F_R), G, B (CS); 0 .. 255

  f24_t m2z_q;      // S1: 2M_z, waiting a clock (lane 0 of u_nc)
  f24_t colz_q;     // S1: C_z, waiting a clock (lane 0 of the colour)
  f24_t nnm_q;      // max(nn, EPS) (B_NNM)
  f24_t m_q;        // ndl = max(dot(n, l), 0) (B_M), then ndh
  f24_t cl_q;       // the clamped colour: R (C0 + 1), G, B

  // ---- taps: every value a later operation reads, delayed from the stage it is made in ------
  // tp[src][j] is source src delayed j enabled clocks: a value made in stage b (src's output in
  // Sb) is tp[src][k - b] in stage k.  A select of stage k reads tp[src][k - b]; only the taps
  // read are kept by synthesis (a chain per source, as long as its longest wait), and the
  // longest wait between two read taps of a source is one delay line (g_tap's u_line, below).
  localparam int unsigned TD = CS;  // tap depth (bound)
  localparam int unsigned T_DU = 0, T_DV = 1, T_COL0 = 2, T_COL1 = 3, T_UV2HY2 = 4, T_DVNC = 5,
                          T_NC = 6, T_NUA = 7, T_NV = 8, T_NSQA = 9, T_NY2H = 10, T_VA = 11,
                          T_NXH = 12, T_HD = 13, T_HKD = 14, T_RVNH = 15, T_NUNH1 = 16,
                          T_NLA = 17, T_HUNH1 = 18, T_NNM = 19, T_M = 20, T_SQ = 21, T_CAA = 22;
  localparam int unsigned NT = 23;
  f24_t src [NT];
  /* verilator lint_off UNUSEDSIGNAL */  // the taps no operation reads (removed by synthesis)
  f24_t [TD:0] tp [NT];
  /* verilator lint_on UNUSEDSIGNAL */
  // the colour's lane 0: C_x in S0, C_z (waited a clock) in S1
  assign src[T_DU]     = in_du;
  assign src[T_DV]     = in_dv;
  assign src[T_COL0]   = cv_q[1] ? colz_q : in_col[0];
  assign src[T_COL1]   = in_col[1];
  assign src[T_UV2HY2] = uv2hy2_y;
  assign src[T_DVNC]   = dvnc_y;
  assign src[T_NC]     = nc_y;
  assign src[T_NUA]    = nua_y;
  assign src[T_NV]     = nv_y;
  assign src[T_NSQA]   = nsqa_y;
  assign src[T_NY2H]   = ny2h_y;
  assign src[T_VA]     = va_y;
  assign src[T_NXH]    = nxh_y;
  assign src[T_HD]     = hd_y;
  assign src[T_HKD]    = hkd_y;
  assign src[T_RVNH]   = rvnh_y;
  assign src[T_NUNH1]  = nunh1_y;
  assign src[T_NLA]    = nla_y;
  assign src[T_HUNH1]  = hunh1_y;
  assign src[T_NNM]    = nnm_q;
  assign src[T_M]      = m_q;
  assign src[T_SQ]     = sq_y;
  assign src[T_CAA]    = caa_y;

  // Delay lines: each source's longest wait between two taps that are read, from tap LO (read,
  // or the source itself) to tap HI (read, none read between), is one pipe_delay of HI - LO
  // enabled clocks (a RAM line from DELAY_RAM_MIN clocks on: the colour lanes' 60-odd clocks, the
  // 10 to 20 clocks many results wait for their second reader); the other taps are registers as
  // before.  tap_gap lists every tap a select reads, per source (tp[src][...] below): a tap read
  // but missing here could fall inside a line and read 0.
  localparam int unsigned GW = 16;  // bits of a tap index in the gap search
  typedef logic [5:0][GW-1:0] tap_list_t;

  /* verilator lint_off UNUSEDSIGNAL */  // a tap index has GW bits
  function automatic tap_list_t taps(input int unsigned a, input int unsigned b = 0,
                                     input int unsigned c = 0, input int unsigned d = 0,
                                     input int unsigned e = 0, input int unsigned f = 0);
    return {GW'(f), GW'(e), GW'(d), GW'(c), GW'(b), GW'(a)};
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // {LO, HI} of the largest gap between consecutive read taps (tap 0, the source, counts as read)
  function automatic logic [2*GW-1:0] big_gap(input tap_list_t t);
    logic [GW-1:0] lo, hi, l;
    lo = '0;
    hi = '0;
    for (int i = 0; i < 6; i++) begin
      l = '0;
      for (int j = 0; j < 6; j++) if (t[j] < t[i] && t[j] > l) l = t[j];
      if (t[i] - l > hi - lo) begin
        lo = l;
        hi = t[i];
      end
    end
    return {lo, hi};
  endfunction

  function automatic logic [2*GW-1:0] tap_gap(input int unsigned t);
    case (t)
      T_DU:     return big_gap(taps(S_DU2 - 1, S_VXZ - 1));
      T_DV:     return big_gap(taps(S_DV2 - 1, S_VY - 1));
      T_COL0:   return big_gap(taps(S_CAXZ - 1));
      T_COL1:   return big_gap(taps(S_CYA - 1));
      T_UV2HY2: return big_gap(taps(S_UV - 1 - R_DU2, S_HXY2 - 1 - R_HY2));
      T_DVNC:   return big_gap(taps(S_UV - 1 - R_DV2, S_NHXZ - 1 - R_NUXZ, S_CG - 1 - R_CYA));
      T_NC:     return big_gap(taps(S_NUXZ - 1 - R_NXZ, C0 - R_CRB, C0 + 1 - R_CRB));
      T_NUA:    return big_gap(taps(S_NY2 - 1 - R_NY, S_VV - 1 - R_UV, S_NUY - 1 - R_NY,
                                    S_CYA - 1 - R_A, S_CAXZ - 1 - R_A, C0 + 1 - R_CG));
      T_NV:     return big_gap(taps(S_RV - 1 - R_VV, S_RH - 1 - R_HH, S_HH - 1 - R_HXY2));
      T_NSQA:   return big_gap(taps(S_NXY2 - 1 - R_NSQ, S_NN - 1 - (R_NSQ + 1)));
      T_NY2H:   return big_gap(taps(S_NXY2 - 1 - R_NY2, S_HY - 1 - R_VY,
                                    S_NHXZ - 1 - R_HUXZ));
      T_VA:     return big_gap(taps(S_HXZ - 1 - R_VXZ));
      T_NXH:    return big_gap(taps(S_NN - 1 - R_NXY2, S_HUXZ - 1 - R_HXZ, S_HXZ2 - 1 - R_HXZ,
                                    S_DOTS - 1 - R_NLXY));
      T_HD:     return big_gap(taps(S_HY2 - 1 - R_HY, S_HUY - 1 - R_HY, S_DOTS - R_NHXY));
      T_HKD:    return big_gap(taps(S_HXY2 - 1 - R_HXZ2, S_HH - 1 - (R_HXZ2 + 1),
                                    S_A - 1 - R_KDN));
      T_RVNH:   return big_gap(taps(S_VY - 1 - R_RV, S_VXZ - 1 - R_RV, S_NUXZ - 1 - R_RN,
                                    S_NUY - 1 - R_RN, S_HUXZ - 1 - R_RH, S_HUY - 1 - R_RH));
      T_NUNH1:  return big_gap(taps(S_NLY - 1 - R_NUY, S_NHY - 1 - R_NUY, S_NHXY - 1 - R_NHXZ,
                                    S_DOTS - (R_NHXZ + 1)));
      T_NLA:    return big_gap(taps(S_NLXY - 1 - R_NL, S_DOTS - 1 - (R_NL + 1)));
      T_HUNH1:  return big_gap(taps(S_NLXY - 1 - R_NLY, S_NHY - 1 - R_HUY,
                                    S_NHXY - 1 - R_NHY));
      T_NNM:    return big_gap(taps(S_RN - 1 - B_NNM));
      T_M:      return big_gap(taps(S_KDN - 1 - B_M, S_S2 - 1 - (B_M + 1)));
      T_SQ:     return big_gap(taps(S_S4 - 1 - R_S2, S_S8 - 1 - R_S4, S_S16 - 1 - R_S8,
                                    S_SP - 1 - R_S16));
      T_CAA:    return big_gap(taps(S_CRB - 1 - R_CAXZ, S_CG - 1 - R_SP, S_CRB - 1 - R_SP));
      default:  return '0;
    endcase
  endfunction

  for (genvar t = 0; t < NT; t++) begin : g_tap
    localparam logic [2*GW-1:0] GAP = tap_gap(t);
    localparam int unsigned LO = int'(GAP[2*GW-1:GW]);  // the line's input tap
    localparam int unsigned HI = int'(GAP[GW-1:0]);     // its output tap
    // tv, q_q: this source's taps and registers as plain vectors (one whole-word write of tp[t]:
    // no array of the sources is read or written element by element)
    /* verilator lint_off UNUSEDSIGNAL */  // the registers inside the line (removed)
    f24_t [TD:0] tv;
    f24_t [TD:1] q_q;
    /* verilator lint_on UNUSEDSIGNAL */
    assign tv[0] = src[t];
    if (HI > LO) begin : g_line
      f24_t line_q;
      pipe_delay #(.W(24), .N(HI - LO), .RAM_MIN(DELAY_RAM_MIN)) u_line (
        .clk_i, .rst_ni, .en_i, .d_i(tv[LO]), .q_o(line_q));
      for (genvar j = 1; j <= TD; j++) begin : g_j
        if (j == HI) begin : g_out
          assign tv[j] = line_q;
        end else if (j > LO && j < HI) begin : g_in
          assign tv[j] = '0;  // inside the line: not read
        end else begin : g_reg
          assign tv[j] = q_q[j];
        end
      end
    end else begin : g_regs
      assign tv[TD:1] = q_q;
    end
    always_ff @(posedge clk_i) begin
      if (en_i) q_q <= tv[TD-1:0];
    end
    assign tp[t] = tv;
  end

  logic [7:0]      g_q;             // CS: G (its floor held a clock)
  logic [7:0]      r_q [1:2];       // CS - 1, CS: R (its floor held two clocks)
  logic [2:0][7:0] res_q;           // the result held from core CS to the output (NS)

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      m2z_q  <= dbl(in_nrm[2]);
      colz_q <= in_col[2];
      nnm_q  <= max_np(nv_y, SHADE_EPS);
      m_q    <= max_np(hd_y, SHADE_ZERO);
      // R (u_nc, C0), G (u_nua, C0 + 1), B (u_nc's z, C0 + 2)
      cl_q <= min_np(max_np(at(ps_q[PS_CL], C0) ? tp[T_NC][C0 - R_CRB]
                            : at(ps_q[PS_CL], C0 + 1) ? tp[T_NUA][C0 + 1 - R_CG]
                            : tp[T_NC][C0 + 1 - R_CRB], SHADE_ZERO), SHADE_ONE);
      // the floors come R (F_R), G, B (CS); the result is complete in core CS
      r_q[1] <= idx[7:0];
      r_q[2] <= r_q[1];
      g_q    <= idx[7:0];
      if (cv_q[CS]) res_q <= {idx[7:0], g_q, r_q[2]};
    end
  end

  // ---- operand registers of the shared units ---------------------------------------------------
  // Operation @a (in S_<op>): its operands selected in a - 1, at(ps_q[PS_<unit>], a - 1); a
  // stream's z in a.
  // The last operand of a select chain is the remaining operation's.  A scalar operand of a
  // stream is held for its z (a load enable: the flip-flop's clock enable, no select input).
  f24_t opuh_q;                        // u_uv2hy2 (squares: one operand)
  f24_t opdv_a_q, opdv_b_q;            // u_dvnc
  f24_t opnc_a_q, opnc_b_q;            // u_nc
  f24_t opnu_a_q, opnu_b_q;            // u_nua
  f24_t opnv_a_q, opnv_b_q;            // u_nv
  f24_t oprs_q;                        // u_rvnh
  f24_t opyh_a_q, opyh_b_q;            // u_ny2h
  f24_t opva_a_q, opva_b_q;            // u_va
  f24_t opxh_a_q, opxh_b_q;            // u_nxh
  f24_t ophd_a_q, ophd_b_q;            // u_hd
  f24_t ophk_a_q, ophk_b_q;            // u_hkd
  f24_t opnh_a_q, opnh_b_q;            // u_nunh1
  f24_t opnl_b_q;                      // u_nla (a: u_dvnc's result, direct)
  f24_t ophh_a_q, ophh_b_q;            // u_hunh1
  f24_t opca_a_q, opca_b_q;            // u_caa
  f24_t opsq_q;                        // u_sq (squares: one operand)

  // -x: the sign bit flipped
  function automatic f24_t neg(input f24_t x);
    return {~x[23], x[22:0]};
  endfunction

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      // u_uv2hy2: du^2 / h_y^2
      opuh_q   <= at(ps_q[PS_UV2HY2], S_DU2 - 1) ? tp[T_DU][S_DU2 - 1]
                : tp[T_HD][S_HY2 - 1 - R_HY];
      // u_dvnc: dv^2 / n_x rn, n_z rn / C_y a
      opdv_a_q <= at(ps_q[PS_DVNC], S_DV2 - 1) ? tp[T_DV][S_DV2 - 1]
                : (at(ps_q[PS_DVNC], S_NUXZ - 1) || at(ps_q[PS_DVNC], S_NUXZ))
                  ? tp[T_NC][S_NUXZ - 1 - R_NXZ] : tp[T_COL1][S_CYA - 1];
      opdv_b_q <= at(ps_q[PS_DVNC], S_DV2 - 1) ? tp[T_DV][S_DV2 - 1]
                : at(ps_q[PS_DVNC], S_NUXZ - 1) ? tp[T_RVNH][S_NUXZ - 1 - R_RN]
                : at(ps_q[PS_DVNC], S_NUXZ) ? opdv_b_q
                : tp[T_NUA][S_CYA - 1 - R_A];
      // u_nc: n_x - 1, n_z - 1 (n = 2M - 1; 2M_z waited a clock in m2z_q) / c_R, c_B = C a + sp
      opnc_a_q <= at(ps_q[PS_NC], S_NXZ - 1) ? dbl(in_nrm[0]) : at(ps_q[PS_NC], S_NXZ) ? m2z_q
                : tp[T_CAA][S_CRB - 1 - R_CAXZ];
      opnc_b_q <= (at(ps_q[PS_NC], S_NXZ - 1) || at(ps_q[PS_NC], S_NXZ)) ? NEG_ONE
                : at(ps_q[PS_NC], S_CRB - 1) ? tp[T_CAA][S_CRB - 1 - R_SP] : opnc_b_q;
      // u_nua: n_y - 1 / du^2 + dv^2 / a = AMBIENT + KD ndl / c_G = C_y a + sp
      opnu_a_q <= at(ps_q[PS_NUA], S_NY - 1) ? dbl(in_nrm[1])
                : at(ps_q[PS_NUA], S_UV - 1) ? tp[T_UV2HY2][S_UV - 1 - R_DU2]
                : at(ps_q[PS_NUA], S_A - 1) ? cfg_i.ambient : tp[T_DVNC][S_CG - 1 - R_CYA];
      opnu_b_q <= at(ps_q[PS_NUA], S_NY - 1) ? NEG_ONE
                : at(ps_q[PS_NUA], S_UV - 1) ? tp[T_DVNC][S_UV - 1 - R_DV2]
                : at(ps_q[PS_NUA], S_A - 1) ? tp[T_HKD][S_A - 1 - R_KDN]
                : tp[T_CAA][S_CG - 1 - R_SP];
      // u_nv: vv = (du^2 + dv^2) + D2 / nn = (nx2 + ny2) + nz2 / hx2 + hy2 / hh = (..) + hz2
      opnv_a_q <= at(ps_q[PS_NV], S_VV - 1) ? tp[T_NUA][S_VV - 1 - R_UV]
                : at(ps_q[PS_NV], S_NN - 1) ? tp[T_NXH][S_NN - 1 - R_NXY2]
                : at(ps_q[PS_NV], S_HXY2 - 1) ? tp[T_HKD][S_HXY2 - 1 - R_HXZ2]
                : tp[T_NV][S_HH - 1 - R_HXY2];
      opnv_b_q <= at(ps_q[PS_NV], S_VV - 1) ? cfg_i.d2
                : at(ps_q[PS_NV], S_NN - 1) ? tp[T_NSQA][S_NN - 1 - (R_NSQ + 1)]
                : at(ps_q[PS_NV], S_HXY2 - 1) ? tp[T_UV2HY2][S_HXY2 - 1 - R_HY2]
                : tp[T_HKD][S_HH - 1 - (R_HXZ2 + 1)];
      // u_rvnh: rv / rn / rh
      oprs_q   <= at(ps_q[PS_RVNH], S_RV - 1) ? tp[T_NV][S_RV - 1 - R_VV]
                : at(ps_q[PS_RVNH], S_RN - 1) ? tp[T_NNM][S_RN - 1 - B_NNM]
                : tp[T_NV][S_RH - 1 - R_HH];
      // u_ny2h: n_y^2 / v_y = -dv rv / h_x rh, h_z rh
      opyh_a_q <= at(ps_q[PS_NY2H], S_NY2 - 1) ? tp[T_NUA][S_NY2 - 1 - R_NY]
                : at(ps_q[PS_NY2H], S_VY - 1) ? neg(tp[T_DV][S_VY - 1])
                : tp[T_NXH][S_HUXZ - 1 - R_HXZ];
      opyh_b_q <= at(ps_q[PS_NY2H], S_NY2 - 1) ? tp[T_NUA][S_NY2 - 1 - R_NY]
                : at(ps_q[PS_NY2H], S_VY - 1) ? tp[T_RVNH][S_VY - 1 - R_RV]
                : at(ps_q[PS_NY2H], S_HUXZ - 1) ? tp[T_RVNH][S_HUXZ - 1 - R_RH] : opyh_b_q;
      // u_va: v_x = -du rv, v_z = D rv
      opva_a_q <= at(ps_q[PS_VA], S_VXZ - 1) ? neg(tp[T_DU][S_VXZ - 1]) : cfg_i.d;
      opva_b_q <= at(ps_q[PS_VA], S_VXZ - 1) ? tp[T_RVNH][S_VXZ - 1 - R_RV] : opva_b_q;
      // u_nxh: nx2 + ny2 / h_x = l_x + v_x, h_z = l_z + v_z / nlx + nly
      opxh_a_q <= at(ps_q[PS_NXH], S_NXY2 - 1) ? tp[T_NSQA][S_NXY2 - 1 - R_NSQ]
                : at(ps_q[PS_NXH], S_NLXY - 1) ? tp[T_NLA][S_NLXY - 1 - R_NL]
                : at(ps_q[PS_NXH], S_HXZ - 1) ? light[0] : light[2];
      opxh_b_q <= at(ps_q[PS_NXH], S_NXY2 - 1) ? tp[T_NY2H][S_NXY2 - 1 - R_NY2]
                : at(ps_q[PS_NXH], S_NLXY - 1) ? tp[T_HUNH1][S_NLXY - 1 - R_NLY]
                : tp[T_VA][S_HXZ - 1 - R_VXZ];
      // u_hd: h_y = l_y + v_y / nhx + nhy / dot(n, l) = (nlx + nly) + nlz, then
      // dot(n, h) = (nhx + nhy) + nhz
      ophd_a_q <= at(ps_q[PS_HD], S_HY - 1) ? light[1]
                : at(ps_q[PS_HD], S_NHXY - 1) ? tp[T_NUNH1][S_NHXY - 1 - R_NHXZ]
                : at(ps_q[PS_HD], S_DOTS - 1) ? tp[T_NXH][S_DOTS - 1 - R_NLXY]
                : tp[T_HD][S_DOTS - R_NHXY];
      ophd_b_q <= at(ps_q[PS_HD], S_HY - 1) ? tp[T_NY2H][S_HY - 1 - R_VY]
                : at(ps_q[PS_HD], S_NHXY - 1) ? tp[T_HUNH1][S_NHXY - 1 - R_NHY]
                : at(ps_q[PS_HD], S_DOTS - 1) ? tp[T_NLA][S_DOTS - 1 - (R_NL + 1)]
                : tp[T_NUNH1][S_DOTS - (R_NHXZ + 1)];
      // u_hkd: h_x^2, h_z^2 / KD ndl
      ophk_a_q <= at(ps_q[PS_HKD], S_KDN - 1) ? cfg_i.kd : tp[T_NXH][S_HXZ2 - 1 - R_HXZ];
      ophk_b_q <= at(ps_q[PS_HKD], S_KDN - 1) ? tp[T_M][S_KDN - 1 - B_M]
                : tp[T_NXH][S_HXZ2 - 1 - R_HXZ];
      // u_nunh1: n_y rn / n_x h_x, n_z h_z
      opnh_a_q <= at(ps_q[PS_NUNH1], S_NUY - 1) ? tp[T_NUA][S_NUY - 1 - R_NY]
                : tp[T_DVNC][S_NHXZ - 1 - R_NUXZ];
      opnh_b_q <= at(ps_q[PS_NUNH1], S_NUY - 1) ? tp[T_RVNH][S_NUY - 1 - R_RN]
                : tp[T_NY2H][S_NHXZ - 1 - R_HUXZ];
      // u_nla: n_x l_x, n_z l_z
      opnl_b_q <= at(ps_q[PS_NLA], S_NL - 1) ? light[0] : light[2];
      // u_hunh1: n_y l_y / h_y rh / n_y h_y
      ophh_a_q <= at(ps_q[PS_HUNH1], S_NLY - 1) ? tp[T_NUNH1][S_NLY - 1 - R_NUY]
                : at(ps_q[PS_HUNH1], S_HUY - 1) ? tp[T_HD][S_HUY - 1 - R_HY]
                : tp[T_NUNH1][S_NHY - 1 - R_NUY];
      ophh_b_q <= at(ps_q[PS_HUNH1], S_NLY - 1) ? light[1]
                : at(ps_q[PS_HUNH1], S_HUY - 1) ? tp[T_RVNH][S_HUY - 1 - R_RH]
                : tp[T_HUNH1][S_NHY - 1 - R_HUY];
      // u_caa: C_x a, C_z a / sp = KS s^16
      opca_a_q <= at(ps_q[PS_CAA], S_SP - 1) ? cfg_i.ks : tp[T_COL0][S_CAXZ - 1];
      opca_b_q <= at(ps_q[PS_CAA], S_CAXZ - 1) ? tp[T_NUA][S_CAXZ - 1 - R_A]
                : at(ps_q[PS_CAA], S_SP - 1) ? tp[T_SQ][S_SP - 1 - R_S16] : opca_b_q;
      // u_sq: s = ndh^2 (ndh in m_q a stage after ndl) / s^4 / s^8 / s^16
      opsq_q   <= at(ps_q[PS_SQ], S_S2 - 1) ? tp[T_M][S_S2 - 1 - (B_M + 1)]
                : at(ps_q[PS_SQ], S_S4 - 1) ? tp[T_SQ][S_S4 - 1 - R_S2]
                : at(ps_q[PS_SQ], S_S8 - 1) ? tp[T_SQ][S_S8 - 1 - R_S4]
                : tp[T_SQ][S_S16 - 1 - R_S8];
    end
  end

  // ---- float units ----------------------------------------------------------------------------
  f24_mul #(.LAT(MUL_LAT)) u_uv2hy2 (.clk_i, .en_i, .a_i(opuh_q), .b_i(opuh_q), .y_o(uv2hy2_y));
  f24_mul #(.LAT(MUL_LAT)) u_dvnc (.clk_i, .en_i, .a_i(opdv_a_q), .b_i(opdv_b_q), .y_o(dvnc_y));
  f24_add #(.LAT(ADD_LAT)) u_nc   (.clk_i, .en_i, .a_i(opnc_a_q), .b_i(opnc_b_q), .y_o(nc_y));
  f24_add #(.LAT(ADD_LAT)) u_nua  (.clk_i, .en_i, .a_i(opnu_a_q), .b_i(opnu_b_q), .y_o(nua_y));
  f24_add #(.LAT(ADD_LAT)) u_nv   (.clk_i, .en_i, .a_i(opnv_a_q), .b_i(opnv_b_q), .y_o(nv_y));
  f24_rsqrt #(.LAT(RSQRT_LAT)) u_rvnh (.clk_i, .en_i, .a_i(oprs_q), .y_o(rvnh_y));
  f24_mul #(.LAT(MUL_LAT)) u_nsqa (.clk_i, .en_i, .a_i(nc_y), .b_i(nc_y), .y_o(nsqa_y));
  f24_mul #(.LAT(MUL_LAT)) u_ny2h (.clk_i, .en_i, .a_i(opyh_a_q), .b_i(opyh_b_q), .y_o(ny2h_y));
  f24_mul #(.LAT(MUL_LAT)) u_va   (.clk_i, .en_i, .a_i(opva_a_q), .b_i(opva_b_q), .y_o(va_y));
  f24_add #(.LAT(ADD_LAT)) u_nxh  (.clk_i, .en_i, .a_i(opxh_a_q), .b_i(opxh_b_q), .y_o(nxh_y));
  f24_add #(.LAT(ADD_LAT)) u_hd   (.clk_i, .en_i, .a_i(ophd_a_q), .b_i(ophd_b_q), .y_o(hd_y));
  f24_mul #(.LAT(MUL_LAT)) u_hkd  (.clk_i, .en_i, .a_i(ophk_a_q), .b_i(ophk_b_q), .y_o(hkd_y));
  f24_mul #(.LAT(MUL_LAT)) u_nunh1 (.clk_i, .en_i, .a_i(opnh_a_q), .b_i(opnh_b_q),
                                    .y_o(nunh1_y));
  f24_mul #(.LAT(MUL_LAT)) u_nla  (.clk_i, .en_i, .a_i(dvnc_y), .b_i(opnl_b_q), .y_o(nla_y));
  f24_mul #(.LAT(MUL_LAT)) u_hunh1 (.clk_i, .en_i, .a_i(ophh_a_q), .b_i(ophh_b_q),
                                    .y_o(hunh1_y));
  // s = ndh; four times s = mul(s, s) on one unit, each square fed back through its operand
  // register (sp = mul(KS, s): u_caa)
  f24_mul #(.LAT(MUL_LAT)) u_sq   (.clk_i, .en_i, .a_i(opsq_q), .b_i(opsq_q), .y_o(sq_y));
  f24_mul #(.LAT(MUL_LAT)) u_caa (.clk_i, .en_i, .a_i(opca_a_q), .b_i(opca_b_q), .y_o(caa_y));
  // the tail: one lane for the three channels, R, G and B a stage apart (c 255 from C0 + 1,
  // floor(c 255 + 0.5) from C0 + 1 + MUL_LAT: to_index(add(., 0.5)) in the clocks of the two)
  f24_mul #(.LAT(MUL_LAT)) u_k  (.clk_i, .en_i, .a_i(cl_q), .b_i(SHADE_255), .y_o(k_y));
  f24_round_index #(.W(9), .LAT(ADD_LAT + IDX_LAT)) u_idx (.clk_i, .en_i, .a_i(k_y), .idx_o(idx));
  logic unused_idx;                 // bit 8: the index is in 0 .. 255 (see the header)
  assign unused_idx = idx[8];
  // a pixel that waited 3 clocks is at the output in core CS, the others in CS + 1 .. CS + 3
  assign rgb_o = cv_q[CS] ? {idx[7:0], g_q, r_q[2]} : res_q;

  // The simulation checks are in shade_unit_assert.sv (bound into every instance).

endmodule
