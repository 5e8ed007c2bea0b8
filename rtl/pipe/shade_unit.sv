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
// Fully pipelined, fixed latency SHADE_LAT = 59 enabled clocks (shade_pkg), one pixel every 4th
// enabled clock at most (valid_i must not be 1 within 3 enabled clocks after a pixel; asserted:
// pixel_spacing).  In dm_pipeline a pixel needs two filtered quads, which come one per two
// clocks at most.
// Every register (valid, tag, data, the float units) advances only while en_i is 1, so the
// enclosing pipeline stalls the whole unit with en_i = 0.  A pixel is taken on an enabled edge with
// valid_i = 1; its result shows at valid_o / tag_o / rgb_o after SHADE_LAT enabled edges and holds
// while en_i is 0.  valid (and the core's valid bits, the phase and the hold flag) are reset by
// rst_ni (synchronous, active low, independent of en_i); data and tag registers have no reset.
//
// Alignment: ph_q counts enabled clocks modulo 4.  A pixel that comes with ph_q = 0 enters core
// stage S1 at once, one that comes with ph_q = 1, 2 or 3 waits 3, 2 or 1 clocks in hold registers
// and enters with the next ph_q = 0.  The result is complete in core S56; a pixel that waited w
// clocks is at the output in core S59 - w (res_q holds the result from S56 to S59), so the
// latency is fixed.  Every two pixels in the core are thus a multiple of 4 clocks apart, and a
// float unit serves up to four operations of a pixel whose stages differ pairwise by amounts not
// divisible by 4: pixel p at Sa, Sb, ..., any later pixel at Sa + 4j, Sb + 4j, ..., never in the
// same clock (asserted: core_aligned, and unit_once per shared unit).
//
// Operand registers: no float unit takes an operand through a select.  A shared unit's operands
// are registers of its own (op<unit>_a_q, _b_q), loaded in the clock before each operation by a
// select on the phase of that clock (the unit's own copy of ph_q, see "phase replicas"), so a
// phase register, a select and the unit's DSP or first adder stage are never in one clock (the
// routed top's slowest path was a unit's result through the next one's 4:1 select into its DSP).
// An operation whose operand is another unit's result therefore starts a clock after that result
// (its "R" stage below: operands selected in Sa-1, the unit in Sa); an operand that is a delay
// register or a constant is selected from the register before it, at no cost.  A unit fed by one
// source only (a register or another unit's result register) takes it directly.  Holding an
// operand for the second operation of a stream is a load enable of its register.
// Three-component values run as two lanes: lane 0 carries x in stage s and z in s+1 through the
// same registers ("stream"), lane 1 carries y in s; the tail runs R, G, B on one lane.
//
// Core stage schedule (S0 = the input ports or the hold registers; "@a": the unit works on the
// operands in Sa (for a shared unit: selected into its operand registers in Sa-1), "-> b": its
// result in Sb; "reg" = exact logic into one register):
//   S0   2M_c (exact doubling, see below; 2M_z waits a clock in m2z_q for lane 0), selected
//        into u_nc's and u_nua's operand registers
//        du, dv delayed S0 -> S12; C_x, C_z as a stream S0 -> S44, C_y S0 -> S45
//   S1   u_uv2hy2: du^2 @1 / h_y^2 @18                                 f24_mul      -> S2 / S19
//        u_dvnc: dv^2 @1 / n_x rn @19 / n_z rn @20 / C_y a @46         f24_mul      -> S2 .. S47
//        u_nc: n_x - 1 @1 / n_z - 1 @2 (lane 0, n = 2M - 1) / c_R = C_x a + sp @47 /
//        c_B = C_z a + sp @48 (lane 0, sp held)                        f24_add      -> S3 .. S50
//        u_nua: n_y - 1 @1 / du^2 + dv^2 @3 / a = AMBIENT + KD ndl @42 /
//        c_G = C_y a + sp @48                                          f24_add      -> S3 .. S50
//   S3   u_nsqa: n_x^2 @3 / n_z^2 @4 (direct from u_nc)                f24_mul      -> S4 / S5
//   S4   u_ny2h: n_y^2 @4 / v_y = -dv rv @13 / h_x rh @30 / h_z rh @31 (rh held)
//                                                                      f24_mul      -> S5 .. S32
//   S6   u_nv: vv = (du^2 + dv^2) + D2 @6 / nn = (nx2 + ny2) + nz2 @9 / hx2 + hy2 @20 /
//        hh = (hx2 + hy2) + hz2 @23                                    f24_add      -> S8 .. S25
//        u_nxh: nx2 + ny2 @6 / h_x = l_x + v_x @15 / h_z = l_z + v_z @16 / nlx + nly @25
//        (n_y l_y delayed S22 -> S24)                                  f24_add      -> S8 .. S27
//   S9   u_rvnh: rv = rsqrt(vv) @9 / rn = rsqrt(nn) @15 / rh = rsqrt(hh) @26
//                                                                      f24_rsqrt    -> S12 .. S29
//   S11  max(nn, EPS), held S12 -> S14                                 reg          S11 -> S12
//   S13  u_va: v_x = -du rv @13 / v_z = D rv @14 (rv held)             f24_mul      -> S14 / S15
//   S15  u_hd: h_y = l_y + v_y @15 / nhx + nhy @34 / dot(n, l) = (nlx + nly) + nlz @36 /
//        dot(n, h) = (nhx + nhy) + nhz @37 (nlx + nly delayed S27 -> S35, nlz S22 -> S35,
//        nhz S34 -> S36)                                               f24_add      -> S17 .. S39
//        h delayed S17 -> S29 (lane 0), h_y S17 -> S29
//   S18  u_hkd: h_x^2 @18 / h_z^2 @19 / KD ndl @40 (h_z^2 delayed S20 -> S22)
//                                                                      f24_mul      -> S19 .. S41
//   S19  u_nunh1: n_y rn @19 / n_x h_x @32 / n_z h_z @33               f24_mul      -> S20 .. S34
//   S20  u_nla: n_x l_x @20 / n_z l_z @21 (direct from the unit normal)  f24_mul    -> S21 / S22
//        unit normal delayed S20 -> S31 (lanes)
//   S21  u_hunh1: n_y l_y @21 / h_y rh @30 / n_y h_y @32               f24_mul      -> S22 .. S33
//   S38  ndl = max(dot(n, l), 0) -> S39, ndh = max(dot(n, h), 0) -> S40   reg (one)
//   S40  u_s2 .. u_sp: s = ndh^2 @40, s^4 @41, s^8 @42, s^16 @43, sp = KS s^16 @44: five
//        f24_mul, each fed directly by the one before (no select)     f24_mul      -> S41 .. S45
//   S45  u_caa: C_x a @45 / C_z a @46 (a held)                         f24_mul      -> S46 / S47
//   S49  min(max(c_c, 0), 1): R (S49), G (S50), B (S50, held)          reg          -> S50 .. S52
//   S50  u_k: c_c * 255: R @50 / G @51 / B @52 (direct)                f24_mul      -> S51 .. S53
//   S51  u_kh: + 0.5: R @51 / G @52 / B @53 (direct)                   f24_add      -> S53 .. S55
//   S53  u_idx: floor -> unorm8: R @53 / G @54 / B @55                 f24_to_index -> S54 .. S56
//   S54  R held (S55, S56), G held (S56); with B the result is complete in S56
//   Output: a pixel that waited 3 clocks shows its result from core S56 directly, the others
//   from res_q (loaded in S56); valid and tag delayed S0 -> S59 (pipe_valid_tag).
// The f24_rsqrt runs at LAT = pipe_pkg::F24_RSQRT_LAT = 3 (table / product + sum / round:
// over 120 MHz; at 2 clocks it limits the unit to below 60 MHz), with the same results;
// the schedule above is written for that latency (checked at elaboration).
//
// Float units: 16 f24_mul (11 shared: u_dvnc and u_ny2h with four operations, u_hkd, u_nunh1,
// u_hunh1 and u_k with three, 5 with two; the five of the s^16 chain unshared), 6 f24_add (all
// shared: u_nc, u_nua, u_nv, u_nxh and u_hd with four, u_kh with three: the 23 additions fill
// 23 of the 24 slots, 6 units x 4 phases; h_x / h_z wait a clock for their operand registers
// and nlx + nly two clocks, both in slack), 1 f24_rsqrt (three operations), 1 f24_to_index #(9)
// (three); no f24_cmp (34, 21, 3 and 2 before sharing).  Exact logic (no rounding involved,
// each into one register): 3 doublers, max(nn, EPS), one max(., 0) for ndl then ndh, and 1
// clamp.
//
// Exact parts, bit-identical to the model:
// - mul(M_c, 2) is an exponent increment: e = 126 overflows to Inf, zeros and subnormal patterns
//   give a zero of the same sign, Inf stays, NaN gives F24_NAN: exactly f24_mul(M_c, 2.0).
// - The model's max / min are numpy.maximum / numpy.minimum on float64: a NaN operand gives NaN, and
//   equal operands (+0 and -0) give the second one (the constant).  Comparisons use the order of
//   f24_cmp (-0 == +0, subnormal patterns read as zeros).  A NaN passed on here is the operand
//   itself; every consumer is a float unit, which turns any NaN into F24_NAN (and f24_to_index gives
//   0 for NaN, as the model's to_index does).
// - -du, -dv: the sign bit flipped (the model's float64 negation).
// - The model clips the index to [0, 255]; after the clamp the operand of the floor is in
//   [0.5, 255.5] or NaN (-> 0), so a 9-bit f24_to_index is exact and its low 8 bits are the code.
module shade_unit
  import f24_pkg::*;
  import shade_pkg::*;
#(
  parameter int unsigned TAG_W = 8  // side-band bits (pixel address, fragment id, ...) carried
                                    // unchanged from tag_i to tag_o alongside the pixel
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

  localparam int unsigned NS = SHADE_LAT;  // stages S1 .. S59
  localparam int unsigned CS = NS - 3;     // core stages S1 .. S56

  // The f24_rsqrt: the schedule (header) is written for 3 clocks (rv S9 -> S12, rn S15 -> S18,
  // rh S26 -> S29); another latency needs the stages below renumbered.
  localparam int unsigned RSQRT_LAT = pipe_pkg::F24_RSQRT_LAT;
  if (RSQRT_LAT != 3 || NS != 59) begin : g_check_lat
    $error("shade_unit: the stage schedule is written for F24_RSQRT_LAT = 3, SHADE_LAT = 59");
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

  // ---- valid and tag: S1 .. S59 (stage_v[k]: a pixel entered k enabled clocks ago) ---------
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
  localparam int unsigned NPS = 16;  // operand selects (units and the clamp's)
  localparam int unsigned PS_UV2HY2 = 0,  PS_DVNC = 1,   PS_NUA = 2,    PS_NV = 3,
                          PS_NY2H = 4,    PS_VA = 5,     PS_NXH = 6,    PS_HD = 7,
                          PS_HKD = 8,     PS_RVNH = 9,   PS_NUNH1 = 10, PS_NLA = 11,
                          PS_HUNH1 = 12,  PS_CAA = 13,   PS_NC = 14,    PS_CL = 15;
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

  logic [7:0]      g_q;             // core S56: G (its floor held a clock)
  logic [7:0]      r_q [55:56];     // core S55, S56: R (its floor held two clocks)
  logic [2:0][7:0] res_q;           // the result held from core S56 to the output (S57 .. S59)
  logic signed [8:0] idx;           // floor(c 255 + 0.5): R (S54), G (S55), B (S56); 0 .. 255

  // ---- float-unit outputs (named by their results and the stages they appear in) -------------
  f24_t uv2hy2_s219;                // du^2 (S2), h_y^2 (S19)
  f24_t dvnc_s22147;                // dv^2 (S2), unit normal x (S20), z (S21), C_y a (S47)
  f24_t nc_s34_4950;                // n_x (S3), n_z (S4), C_c a + sp, lane 0: R (S49), B (S50)
  f24_t nua_s35_4450;               // n_y (S3), du^2 + dv^2 (S5), a (S44), C_y a + sp (S50)
  f24_t nv_s81122_25;               // vv (S8), nn (S11), hx2 + hy2 (S22), hh (S25)
  f24_t nsqa_s45;                   // n_x^2 (S4), n_z^2 (S5)
  f24_t ny2h_s514_3132;             // n_y^2 (S5), v_y (S14), unit half vector x (S31), z (S32)
  f24_t va_s1415;                   // v_x (S14), v_z (S15)
  f24_t nxh_s81718_27;              // nx2 + ny2 (S8), h_x (S17), h_z (S18), nlx + nly (S27)
  f24_t hkd_s1920_41;               // h_x^2 (S19), h_z^2 (S20), KD ndl (S41)
  f24_t rvnh_s121829;               // rv (S12), rn (S18), rh (S29)
  f24_t nunh1_s2034;                // unit normal y (S20), n_x h_x (S33), n_z h_z (S34)
  f24_t nla_s2122;                  // n_x l_x (S21), n_z l_z (S22)
  f24_t hunh1_s2233;                // n_y l_y (S22), unit half vector y (S31), n_y h_y (S33)
  f24_t hd_s17_3639;                // h_y (S17), nhx + nhy (S36), dot(n, l) (S38), dot(n, h) (S39)
  f24_t s2_s41, s4_s42, s8_s43, s16_s44, sp_s45;  // ndh^2, ^4, ^8, ^16; sp = KS s^16
  f24_t caa_s4647;                  // C_x a (S46), C_z a (S47)
  f24_t k_s51, kh_s53;              // c 255, c 255 + 0.5 (R, then G and B a clock apart each)

  // ---- stage registers of the data path (no reset; "stream": lane 0, x in stage k and z in k+1
  // of the register named [k]) ----------------------------------------------------------------
  f24_t       m2z_q;                // S1: 2M_z, waiting a clock
  f24_t       du_q   [1:12];        // S1 .. S12
  f24_t       dv_q   [1:12];
  f24_t       cola_q [1:44];        // stream C_x, C_z: S1 .. S44
  f24_t       colz_q;               // S1: C_z, waiting a clock
  f24_t       col1_q [1:45];        // C_y: S1 .. S45
  f24_t       na_q   [4:18];        // stream n_x, n_z
  f24_t       n1_q   [4:18];        // n_y
  f24_t       nsq_q  [5:7];         // stream n_x^2, n_z^2
  f24_t       nnm_q  [12:14];       // max(nn, EPS)
  f24_t       hk_q   [20:21];       // stream h_x^2, h_z^2
  f24_t       ha_q   [18:29];       // stream h_x, h_z
  f24_t       hy_q   [18:29];       // h_y
  f24_t       nu_q   [21:31];       // stream unit normal x, z
  f24_t       nuy_q  [21:31];       // unit normal y
  f24_t       nla_q  [22:34];       // stream n_x l_x, n_z l_z
  f24_t       nly_q  [23:24];       // n_y l_y
  f24_t       dxy_q  [28:35];       // nlx + nly
  f24_t       nhz_q  [35:36];       // n_z h_z
  f24_t       m_q;                  // ndl = max(dot(n, l), 0) (S39), then ndh (S40)
  f24_t       a_q;                  // S45: a
  f24_t       sp_q   [46:47];       // sp
  f24_t       bh_q;                 // S51: c_B, held a clock
  f24_t       cl_q;                 // stream of the clamped colour: R (S50), G (S51), B (S52)

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      // the lane-0 streams of the inputs: x when the pixel enters S1, z (held a clock) in S2
      m2z_q <= dbl(in_nrm[2]);
      colz_q    <= in_col[2];
      cola_q[1] <= cv_q[1] ? colz_q : in_col[0];
      col1_q[1] <= in_col[1];
      for (int s = 2; s <= 44; s++) cola_q[s] <= cola_q[s-1];
      for (int s = 2; s <= 45; s++) col1_q[s] <= col1_q[s-1];
      du_q[1] <= in_du;
      dv_q[1] <= in_dv;
      for (int s = 2; s <= 12; s++) begin
        du_q[s] <= du_q[s-1];
        dv_q[s] <= dv_q[s-1];
      end
      na_q[4] <= nc_s34_4950;
      n1_q[4] <= nua_s35_4450;
      for (int s = 5; s <= 18; s++) begin
        na_q[s] <= na_q[s-1];
        n1_q[s] <= n1_q[s-1];
      end
      nsq_q[5] <= nsqa_s45;
      for (int s = 6; s <= 7; s++) nsq_q[s] <= nsq_q[s-1];
      nnm_q[12] <= max_np(nv_s81122_25, SHADE_EPS);
      for (int s = 13; s <= 14; s++) nnm_q[s] <= nnm_q[s-1];
      hk_q[20] <= hkd_s1920_41;
      hk_q[21] <= hk_q[20];
      ha_q[18] <= nxh_s81718_27;
      hy_q[18] <= hd_s17_3639;
      for (int s = 19; s <= 29; s++) ha_q[s] <= ha_q[s-1];
      for (int s = 19; s <= 29; s++) hy_q[s] <= hy_q[s-1];
      nu_q[21]  <= dvnc_s22147;
      nuy_q[21] <= nunh1_s2034;
      for (int s = 22; s <= 31; s++) begin
        nu_q[s]  <= nu_q[s-1];
        nuy_q[s] <= nuy_q[s-1];
      end
      nla_q[22] <= nla_s2122;
      for (int s = 23; s <= 34; s++) nla_q[s] <= nla_q[s-1];
      nly_q[23] <= hunh1_s2233;
      nly_q[24] <= nly_q[23];
      dxy_q[28] <= nxh_s81718_27;
      for (int s = 29; s <= 35; s++) dxy_q[s] <= dxy_q[s-1];
      nhz_q[35] <= nunh1_s2034;
      nhz_q[36] <= nhz_q[35];
      m_q <= max_np(hd_s17_3639, SHADE_ZERO);
      a_q <= nua_s35_4450;
      sp_q[46] <= sp_s45;
      sp_q[47] <= sp_q[46];
      // the tail's stream: R (lane 0, S49), G (lane 1, S50), B (lane 0, S50, held a clock)
      bh_q <= nc_s34_4950;
      cl_q <= min_np(max_np(at(ps_q[PS_CL], 49) ? nc_s34_4950
                            : at(ps_q[PS_CL], 50) ? nua_s35_4450 : bh_q, SHADE_ZERO), SHADE_ONE);
      // the floors come R (S54), G (S55), B (S56); the result is complete in core S56
      r_q[55] <= idx[7:0];
      r_q[56] <= r_q[55];
      g_q     <= idx[7:0];
      if (cv_q[56]) res_q <= {idx[7:0], g_q, r_q[56]};
    end
  end

  // ---- operand registers of the shared units ---------------------------------------------------
  // at(ps_q[PS_<unit>], a) = 1: the clock before the unit's operation @a+1 (its operands are
  // selected in stage a; the last operand of a select chain is the remaining operation's).
  // -du, -dv: the sign bit flipped.
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

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      // u_uv2hy2: du^2 @1 / h_y^2 @18
      opuh_q   <= at(ps_q[PS_UV2HY2], 0) ? in_du : hd_s17_3639;
      // u_dvnc: dv^2 @1 / n_x rn @19 / n_z rn @20 (rn held) / C_y a @46
      opdv_a_q <= at(ps_q[PS_DVNC], 0) ? in_dv
                : (at(ps_q[PS_DVNC], 18) || at(ps_q[PS_DVNC], 19)) ? na_q[18] : col1_q[45];
      opdv_b_q <= at(ps_q[PS_DVNC], 0) ? in_dv
                : at(ps_q[PS_DVNC], 18) ? rvnh_s121829
                : at(ps_q[PS_DVNC], 19) ? opdv_b_q : a_q;
      // u_nc: n_x - 1 @1 / n_z - 1 @2 (n = 2M - 1; 2M_z waited a clock in m2z_q) / c_R = C_x a + sp
      // @47 / c_B = C_z a + sp @48 (sp held)
      opnc_a_q <= at(ps_q[PS_NC], 0) ? dbl(in_nrm[0]) : at(ps_q[PS_NC], 1) ? m2z_q : caa_s4647;
      opnc_b_q <= (at(ps_q[PS_NC], 0) || at(ps_q[PS_NC], 1)) ? NEG_ONE
                : at(ps_q[PS_NC], 46) ? sp_q[46] : opnc_b_q;
      // u_nua: n_y - 1 @1 / du^2 + dv^2 @3 / a = AMBIENT + KD ndl @42 / c_G = C_y a + sp @48
      opnu_a_q <= at(ps_q[PS_NUA], 0) ? dbl(in_nrm[1]) : at(ps_q[PS_NUA], 2) ? uv2hy2_s219
                : at(ps_q[PS_NUA], 41) ? cfg_i.ambient : dvnc_s22147;
      opnu_b_q <= at(ps_q[PS_NUA], 0) ? NEG_ONE : at(ps_q[PS_NUA], 2) ? dvnc_s22147
                : at(ps_q[PS_NUA], 41) ? hkd_s1920_41 : sp_q[47];
      // u_nv: vv = (du^2 + dv^2) + D2 @6 / nn = (nx2 + ny2) + nz2 @9 / hx2 + hy2 @20 /
      // hh = (hx2 + hy2) + hz2 @23
      opnv_a_q <= at(ps_q[PS_NV], 5) ? nua_s35_4450 : at(ps_q[PS_NV], 8) ? nxh_s81718_27
                : at(ps_q[PS_NV], 19) ? hkd_s1920_41 : nv_s81122_25;
      opnv_b_q <= at(ps_q[PS_NV], 5) ? cfg_i.d2 : at(ps_q[PS_NV], 8) ? nsq_q[7]
                : at(ps_q[PS_NV], 19) ? uv2hy2_s219 : hk_q[21];
      // u_rvnh: rv @9 / rn @15 / rh @26
      oprs_q   <= at(ps_q[PS_RVNH], 14) ? nnm_q[14] : nv_s81122_25;
      // u_ny2h: n_y^2 @4 / v_y = -dv rv @13 / h_x rh @30 / h_z rh @31 (rh held)
      opyh_a_q <= at(ps_q[PS_NY2H], 3) ? nua_s35_4450
                : at(ps_q[PS_NY2H], 12) ? {~dv_q[12][23], dv_q[12][22:0]} : ha_q[29];
      opyh_b_q <= at(ps_q[PS_NY2H], 3) ? nua_s35_4450
                : (at(ps_q[PS_NY2H], 12) || at(ps_q[PS_NY2H], 29)) ? rvnh_s121829 : opyh_b_q;
      // u_va: v_x = -du rv @13 / v_z = D rv @14 (rv held)
      opva_a_q <= at(ps_q[PS_VA], 12) ? {~du_q[12][23], du_q[12][22:0]} : cfg_i.d;
      opva_b_q <= at(ps_q[PS_VA], 12) ? rvnh_s121829 : opva_b_q;
      // u_nxh: nx2 + ny2 @6 / h_x = l_x + v_x @15 / h_z = l_z + v_z @16 / nlx + nly @25
      opxh_a_q <= at(ps_q[PS_NXH], 5) ? nsq_q[5] : at(ps_q[PS_NXH], 24) ? nla_q[24]
                : at(ps_q[PS_NXH], 14) ? light[0] : light[2];
      opxh_b_q <= at(ps_q[PS_NXH], 5) ? ny2h_s514_3132 : at(ps_q[PS_NXH], 24) ? nly_q[24]
                : va_s1415;
      // u_hd: h_y = l_y + v_y @15 / nhx + nhy @34 / dot(n, l) = (nlx + nly) + nlz @36 /
      // dot(n, h) = (nhx + nhy) + nhz @37
      ophd_a_q <= at(ps_q[PS_HD], 14) ? light[1] : at(ps_q[PS_HD], 33) ? nunh1_s2034
                : at(ps_q[PS_HD], 35) ? dxy_q[35] : hd_s17_3639;
      ophd_b_q <= at(ps_q[PS_HD], 14) ? ny2h_s514_3132 : at(ps_q[PS_HD], 33) ? hunh1_s2233
                : at(ps_q[PS_HD], 35) ? nla_q[34] : nhz_q[36];
      // u_hkd: h_x^2 @18 / h_z^2 @19 / KD ndl @40
      ophk_a_q <= at(ps_q[PS_HKD], 39) ? cfg_i.kd : nxh_s81718_27;
      ophk_b_q <= at(ps_q[PS_HKD], 39) ? m_q : nxh_s81718_27;
      // u_nunh1: n_y rn @19 / n_x h_x @32 / n_z h_z @33
      opnh_a_q <= at(ps_q[PS_NUNH1], 18) ? n1_q[18] : nu_q[31];
      opnh_b_q <= at(ps_q[PS_NUNH1], 18) ? rvnh_s121829 : ny2h_s514_3132;
      // u_nla: n_x l_x @20 / n_z l_z @21
      opnl_b_q <= at(ps_q[PS_NLA], 19) ? light[0] : light[2];
      // u_hunh1: n_y l_y @21 / h_y rh @30 / n_y h_y @32
      ophh_a_q <= at(ps_q[PS_HUNH1], 20) ? nunh1_s2034
                : at(ps_q[PS_HUNH1], 29) ? hy_q[29] : nuy_q[31];
      ophh_b_q <= at(ps_q[PS_HUNH1], 20) ? light[1]
                : at(ps_q[PS_HUNH1], 29) ? rvnh_s121829 : hunh1_s2233;
      // u_caa: C_x a @45 / C_z a @46 (a held)
      opca_a_q <= cola_q[44];
      opca_b_q <= at(ps_q[PS_CAA], 44) ? nua_s35_4450 : opca_b_q;
    end
  end

  // ---- float units ----------------------------------------------------------------------------
  f24_mul u_uv2hy2 (.clk_i, .en_i, .a_i(opuh_q), .b_i(opuh_q), .y_o(uv2hy2_s219));
  f24_mul u_dvnc   (.clk_i, .en_i, .a_i(opdv_a_q), .b_i(opdv_b_q), .y_o(dvnc_s22147));
  f24_add u_nc     (.clk_i, .en_i, .a_i(opnc_a_q), .b_i(opnc_b_q), .y_o(nc_s34_4950));
  f24_add u_nua    (.clk_i, .en_i, .a_i(opnu_a_q), .b_i(opnu_b_q), .y_o(nua_s35_4450));
  f24_add u_nv     (.clk_i, .en_i, .a_i(opnv_a_q), .b_i(opnv_b_q), .y_o(nv_s81122_25));
  f24_rsqrt #(.LAT(RSQRT_LAT)) u_rvnh (.clk_i, .en_i, .a_i(oprs_q), .y_o(rvnh_s121829));
  f24_mul u_nsqa   (.clk_i, .en_i, .a_i(nc_s34_4950), .b_i(nc_s34_4950), .y_o(nsqa_s45));
  f24_mul u_ny2h   (.clk_i, .en_i, .a_i(opyh_a_q), .b_i(opyh_b_q), .y_o(ny2h_s514_3132));
  f24_mul u_va     (.clk_i, .en_i, .a_i(opva_a_q), .b_i(opva_b_q), .y_o(va_s1415));
  f24_add u_nxh    (.clk_i, .en_i, .a_i(opxh_a_q), .b_i(opxh_b_q), .y_o(nxh_s81718_27));
  f24_add u_hd     (.clk_i, .en_i, .a_i(ophd_a_q), .b_i(ophd_b_q), .y_o(hd_s17_3639));
  f24_mul u_hkd    (.clk_i, .en_i, .a_i(ophk_a_q), .b_i(ophk_b_q), .y_o(hkd_s1920_41));
  f24_mul u_nunh1  (.clk_i, .en_i, .a_i(opnh_a_q), .b_i(opnh_b_q), .y_o(nunh1_s2034));
  f24_mul u_nla    (.clk_i, .en_i, .a_i(dvnc_s22147), .b_i(opnl_b_q), .y_o(nla_s2122));
  f24_mul u_hunh1  (.clk_i, .en_i, .a_i(ophh_a_q), .b_i(ophh_b_q), .y_o(hunh1_s2233));
  // s = ndh; four times s = mul(s, s); sp = mul(KS, s): one unit per operation, each fed by the
  // previous one's result register (ndh: m_q in S40)
  f24_mul u_s2     (.clk_i, .en_i, .a_i(m_q), .b_i(m_q), .y_o(s2_s41));
  f24_mul u_s4     (.clk_i, .en_i, .a_i(s2_s41), .b_i(s2_s41), .y_o(s4_s42));
  f24_mul u_s8     (.clk_i, .en_i, .a_i(s4_s42), .b_i(s4_s42), .y_o(s8_s43));
  f24_mul u_s16    (.clk_i, .en_i, .a_i(s8_s43), .b_i(s8_s43), .y_o(s16_s44));
  f24_mul u_sp     (.clk_i, .en_i, .a_i(cfg_i.ks), .b_i(s16_s44), .y_o(sp_s45));
  f24_mul u_caa    (.clk_i, .en_i, .a_i(opca_a_q), .b_i(opca_b_q), .y_o(caa_s4647));
  // the tail: one lane for the three channels, R, G and B a clock apart (c 255 @50 .. @52,
  // + 0.5 @51 .. @53, floor @53 .. @55)
  f24_mul u_k  (.clk_i, .en_i, .a_i(cl_q), .b_i(SHADE_255), .y_o(k_s51));
  f24_add u_kh (.clk_i, .en_i, .a_i(k_s51), .b_i(SHADE_HALF), .y_o(kh_s53));
  // sat_o is not needed: the operand is in [0.5, 255.5] or NaN
  f24_to_index #(.W(9)) u_idx (.clk_i, .en_i, .a_i(kh_s53), .idx_o(idx), .sat_o());
  logic unused_idx;                 // bit 8: the index is in 0 .. 255 (see the header)
  assign unused_idx = idx[8];
  // a pixel that waited 3 clocks is at the output in core S56, the others in S57 .. S59
  assign rgb_o = cv_q[56] ? {idx[7:0], g_q, r_q[56]} : res_q;

  // The simulation checks are in shade_unit_assert.sv (bound into every instance).

endmodule
