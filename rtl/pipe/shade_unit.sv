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
// Fully pipelined, fixed latency SHADE_LAT = 44 enabled clocks (shade_pkg), one pixel every 4th
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
// and enters with the next ph_q = 0.  The result is complete in core S41; a pixel that waited w
// clocks is at the output in core S44 - w (res_q holds the result from S41 to S44), so the
// latency is fixed.  Every two pixels in the core are thus a multiple of 4 clocks apart, and a
// float unit serves up to four operations of a pixel whose stages differ pairwise by amounts not
// divisible by 4: pixel p at Sa, Sb, ..., any later pixel at Sa + 4j, Sb + 4j, ..., never in the
// same clock (asserted: core_aligned, and unit_once per shared unit).  A shared unit's operands
// are registers, or a select between registers by the phase a mod 4 of its operation in core
// stage a (the unit's own copy of ph_q, see "phase replicas").  The units with four operations
// are multipliers (2:1 to 4:1 selects; u_dvnc's are made a clock early into operand registers of
// its own, leaving a 2:1); every adder keeps the 2:1 select (or none) it had with two operations
// per unit (u_vvhh's D2 enters through hz2's register, leaving it one).
// Three-component values run as two lanes: lane 0 carries x in stage s and z in s+1 through the
// same registers ("stream"), lane 1 carries y in s; the tail runs R, G, B on one lane.
//
// Core stage schedule (S0 = the input ports or the hold registers; "a -> b": a unit takes operands
// in Sa, result in Sb; "@a / @b": a unit's operations; "reg" = exact logic into one register):
//   S0   2M_c (exact doubling, see below; 2M_z waits a clock for lane 0) reg          S0 -> S1
//        du, dv delayed S0 -> S9; C_x, C_z as a stream S0 -> S29, C_y S0 -> S30
//   S1   du^2 @1 / h_y^2 @12                                           f24_mul      -> S2 / S13
//        dv^2 @1 / n_x rn @19 / n_z rn @20 / C_y a @30                 f24_mul      -> S2 / .. S31
//        n_x - 1 @1 / n_z - 1 @2 (lane 0, n = 2M - 1)                  f24_add      -> S3 / S4
//        n_y - 1 @1 / du^2 + dv^2 @2                                   f24_add      -> S3 / S4
//        n delayed S3 -> S19 (lanes)
//   S4   vv = (du^2 + dv^2) + D2 @4 / hh = (hx2 + hy2) + hz2 @15       f24_add      -> S6 / S17
//   S6   rv = rsqrt(vv) @6 / rn = rsqrt(nn) @16 / rh = rsqrt(hh) @17   f24_rsqrt    -> S9 / .. S20
//   S8   n_x^2 @8 / n_z^2 @9                                           f24_mul      -> S9 / S10
//        n_y^2 @8 / v_y = -dv rv @9                                    f24_mul      -> S9 / S10
//   S9   v_x = -du rv @9 / v_z = D rv @10 (rv held a clock)            f24_mul      -> S10 / S11
//        nx2 + ny2 @9 / h_y = l_y + v_y @10                            f24_add      -> S11 / S12
//   S10  h_x = l_x + v_x @10 / h_z = l_z + v_z @11                     f24_add      -> S12 / S13
//        h delayed S12 -> S20 (lanes)
//   S12  h_x^2 @12 / h_z^2 @13 / KD ndl @26 / s = ndh^2 @27            f24_mul      -> S13 / .. S28
//        nn = (nx2 + ny2) + nz2 @12 / hx2 + hy2 @13                    f24_add      -> S14 / S15
//   S14  max(nn, EPS), held S15 -> S16                                 reg          S14 -> S15
//   S19  (n_x rn, n_z rn: above) n_y rn @19 / n_y l_y @20 / n_x h_x @21 / n_z h_z @22
//                                                                      f24_mul      -> S20 / .. S23
//   S20  n_x l_x @20 / n_z l_z @21                                     f24_mul      -> S21 / S22
//        h_x rh @20 / h_z rh @21 (unit half vector, lane 0)            f24_mul      -> S21 / S22
//        h_y rh @20 / n_y h_y @21                                      f24_mul      -> S21 / S22
//   S21  nlx + nly @21 / nhx + nhy @22                                 f24_add      -> S23 / S24
//   S23  dot(n, l) = (nlx + nly) + nlz @23 / dot(n, h) @24             f24_add      -> S25 / S26
//        (nlz, then nhz, wait a clock in one register)
//   S25  ndl = max(dot(n, l), 0) -> S26, ndh = max(dot(n, h), 0) -> S27   reg (one)
//   S27  a = AMBIENT + KD ndl @27 / c_G = C_y a + sp @32               f24_add      -> S29 / S34
//   S28  s^4 @28 / s^8 @29 / s^16 @30 / sp = KS s^16 @31               f24_mul      -> S29 / .. S32
//   S29  C_x a @29 / C_z a @30 (a held a clock)                        f24_mul      -> S30 / S31
//        C_x a, C_z a delayed S30 -> S32; C_y a S31 -> S32
//   S32  c_c = C_c a + sp (lane 0: R @32, B @33, sp held a clock)      f24_add      -> S34 / S35
//   S34  min(max(c_c, 0), 1): R (S34), G (S34, held), B (S35, held)    reg          -> S35 .. S37
//   S35  c_c * 255: R @35 / G @36 / B @37                              f24_mul      -> S36 .. S38
//   S36  + 0.5: R @36 / G @37 / B @38                                  f24_add      -> S38 .. S40
//   S38  floor -> unorm8: R @38 / G @39 / B @40                        f24_to_index -> S39 .. S41
//   S39  R held (S40, S41), G held (S41); with B the result is complete in S41
//   Output: a pixel that waited 3 clocks shows its result from core S41 directly, the others
//   from res_q (loaded in S41); valid and tag delayed S0 -> S44 (pipe_valid_tag).
// The f24_rsqrt runs at LAT = pipe_pkg::F24_RSQRT_LAT = 3 (table / product + sum / round:
// over 120 MHz; at 2 clocks it limits the unit to below 60 MHz), with the same results;
// the schedule above is written for that latency (checked at elaboration).
//
// Float units: 13 f24_mul (12 shared: 4 with four operations, u_k with three, 7 with two), 11
// f24_add (all shared: u_kh with three), 1 f24_rsqrt (three operations), 1 f24_to_index #(9)
// (three); no f24_cmp (18, 12, 2 and 2 with two operations per unit; 34, 21, 3 and 2 before
// sharing).  Exact logic (no rounding involved, each into one register): 3 doublers,
// max(nn, EPS), one max(., 0) for ndl then ndh, and 1 clamp.
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

  localparam int unsigned NS = SHADE_LAT;  // stages S1 .. S44
  localparam int unsigned CS = NS - 3;     // core stages S1 .. S41

  // The f24_rsqrt: the schedule (header) is written for 3 clocks (rv S6 -> S9, rn S16 -> S19,
  // rh S17 -> S20); another latency needs the stages below renumbered.
  localparam int unsigned RSQRT_LAT = pipe_pkg::F24_RSQRT_LAT;
  if (RSQRT_LAT != 3 || NS != 44) begin : g_check_lat
    $error("shade_unit: the stage schedule is written for F24_RSQRT_LAT = 3, SHADE_LAT = 44");
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

  // ---- valid and tag: S1 .. S41 (stage_v[k]: a pixel entered k enabled clocks ago) ---------
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
  // never read.  Each shared unit has a one-hot copy of ph_q of its own (ps_q[u][r] = (ph_q == r)),
  // which the placer keeps next to it: a select driven by cv_q[1], shared by five units, was
  // 2.5 ns of routing into an adder's stage 1 (77 MHz out of context).  The copies are not
  // merged by synthesis: each register's next value is its own rotation.
  localparam int unsigned NPS = 20;  // shared units with an operand select
  localparam int unsigned PS_UV2HY2 = 0,  PS_DVNC = 1,   PS_N1UV = 2,   PS_VVHH = 3,
                          PS_NSQ1V1 = 4,  PS_VA = 5,     PS_NXYH1 = 6,  PS_HA = 7,
                          PS_HKD = 8,     PS_NNHXY = 9,  PS_RVNH = 10,  PS_NUNH1 = 11,
                          PS_NLA = 12,    PS_HUA = 13,   PS_HUNH1 = 14, PS_DXY = 15,
                          PS_ACC1 = 16,   PS_SSP = 17,   PS_CAA = 18,   PS_CC0 = 19;
  logic [3:0] ps_q [NPS];

  for (genvar u = 0; u < NPS; u++) begin : g_ps
    always_ff @(posedge clk_i) begin
      if (!rst_ni)   ps_q[u] <= 4'b0001;
      else if (en_i) ps_q[u] <= {ps_q[u][2:0], ps_q[u][3]};
    end
  end

  // The unit's operation of core stage a (given its phase replica p).
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

  logic [7:0]      g_q;             // core S41: G (its floor held a clock)
  logic [7:0]      r_q [40:41];     // core S40, S41: R (its floor held two clocks)
  logic [2:0][7:0] res_q;           // the result held from core S41 to the output (S42 .. S44)
  logic signed [8:0] idx;           // floor(c 255 + 0.5): R (S39), G (S40), B (S41); 0 .. 255

  // ---- float-unit outputs (named by their two results and the stages they appear in) --------
  f24_t uv2hy2_s213;                // du^2 (S2), h_y^2 (S13)
  f24_t dvnc_s22131;                // dv^2 (S2), unit normal x (S20), z (S21), C_y a (S31)
  f24_t na_s34;                     // n_x (S3), n_z (S4)
  f24_t n1uv_s34;                   // n_y (S3), du^2 + dv^2 (S4)
  f24_t vvhh_s617;                  // vv (S6), hh (S17)
  f24_t nsqa_s910;                  // n_x^2 (S9), n_z^2 (S10)
  f24_t nsq1v1_s910;                // n_y^2 (S9), v_y (S10)
  f24_t va_s1011;                   // v_x (S10), v_z (S11)
  f24_t nxyh1_s1112;                // nx2 + ny2 (S11), h_y (S12)
  f24_t ha_s1213;                   // h_x (S12), h_z (S13)
  f24_t hkd_s1328;                  // h_x^2 (S13), h_z^2 (S14), KD ndl (S27), ndh^2 (S28)
  f24_t nnhxy_s1415;                // nn (S14), hx2 + hy2 (S15)
  f24_t rvnh_s91920;                // rv (S9), rn (S19), rh (S20)
  f24_t nunh1_s2023;                // unit normal y (S20), n_y l_y (S21), n_x h_x (S22),
                                    // n_z h_z (S23)
  f24_t nla_s2122;                  // n_x l_x (S21), n_z l_z (S22)
  f24_t hua_s2122;                  // unit half vector x (S21), z (S22)
  f24_t hunh1_s2122;                // unit half vector y (S21), n_y h_y (S22)
  f24_t dxy_s2324;                  // nlx + nly (S23), nhx + nhy (S24)
  f24_t dot_s2526;                  // dot(n, l) (S25), dot(n, h) (S26)
  f24_t acc1_s2934;                 // a (S29), C_y a + sp (S34)
  f24_t ssp_s2932;                  // ndh^4 (S29), ndh^8 (S30), ndh^16 (S31), sp (S32)
  f24_t caa_s3031;                  // C_x a (S30), C_z a (S31)
  f24_t [1:0] cc_s34;               // C_c a + sp, per lane (lane 0: R, then B a clock later)
  f24_t       k_s36, kh_s38;        // c 255, c 255 + 0.5 (R, then G and B a clock apart each)

  // ---- stage registers of the data path (no reset; "stream": lane 0, x then z a clock later) --
  f24_t       m2a_q;                // S1 / S2 stream: 2M_x, 2M_z
  f24_t       m2z_q;                // S1: 2M_z, waiting a clock
  f24_t       m2y_q;                // S1: 2M_y
  f24_t       du_q   [1:9];         // S1 .. S9
  f24_t       dv_q   [1:9];
  f24_t       cola_q [1:29];        // stream C_x, C_z: S1 .. S29
  f24_t       colz_q;               // S1: C_z, waiting a clock
  f24_t       col1_q [1:29];        // C_y: S1 .. S29 (S30: u_dvnc's operand register)
  f24_t       na_q   [4:18];        // stream n_x, n_z (S19: u_dvnc's operand register)
  f24_t       n1_q   [4:19];        // n_y
  f24_t       rv_q;                 // S10: rv
  f24_t       nxy_q;                // S12: nx2 + ny2
  f24_t       nsq2_q [11:12];       // nz2
  f24_t       h1_q   [13:20];       // h_y
  f24_t       ha_q   [13:20];       // stream h_x, h_z
  f24_t       hsq2_q;               // S15: hz2; S4: D2
  f24_t       nnm_q;                // S15: max(nn, EPS)
  f24_t       nnm2_q;               // S16
  f24_t       rq_q;                 // rn (S20), then rh (S21)
  f24_t       nu1_q;                // S21: unit normal y
  f24_t       nua_q;                // stream unit normal x, z: S21 / S22
  f24_t       z_q;                  // nlz (S23), then nhz (S24)
  f24_t       m_q;                  // ndl = max(dot(n, l), 0) (S26), then ndh (S27)
  f24_t       a_q;                  // S30: a
  f24_t       dvnc_a_q, dvnc_b_q;   // u_dvnc's operands, selected a clock early
  f24_t       ca_q   [31:32];       // stream C_x a, C_z a
  f24_t       ca1_q;                // S32: C_y a
  f24_t       sp_q;                 // S33: sp
  f24_t       gh_q;                 // S35: c_G, held a clock
  f24_t       bh_q;                 // S36: c_B, held a clock
  f24_t       cl_q;                 // stream of the clamped colour: R (S35), G (S36), B (S37)

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      // the lane-0 streams of the inputs: x when the pixel enters S1, z (held a clock) in S2
      m2z_q <= dbl(in_nrm[2]);
      m2a_q <= cv_q[1] ? m2z_q : dbl(in_nrm[0]);
      m2y_q <= dbl(in_nrm[1]);
      colz_q    <= in_col[2];
      cola_q[1] <= cv_q[1] ? colz_q : in_col[0];
      col1_q[1] <= in_col[1];
      for (int s = 2; s <= 29; s++) cola_q[s] <= cola_q[s-1];
      for (int s = 2; s <= 29; s++) col1_q[s] <= col1_q[s-1];
      du_q[1] <= in_du;
      dv_q[1] <= in_dv;
      for (int s = 2; s <= 9; s++) begin
        du_q[s] <= du_q[s-1];
        dv_q[s] <= dv_q[s-1];
      end
      na_q[4] <= na_s34;
      n1_q[4] <= n1uv_s34;
      for (int s = 5; s <= 18; s++) na_q[s] <= na_q[s-1];
      for (int s = 5; s <= 19; s++) n1_q[s] <= n1_q[s-1];
      rv_q <= rvnh_s91920;
      nxy_q <= nxyh1_s1112;
      nsq2_q[11] <= nsqa_s910;
      nsq2_q[12] <= nsq2_q[11];
      h1_q[13] <= nxyh1_s1112;
      ha_q[13] <= ha_s1213;
      for (int s = 14; s <= 20; s++) begin
        h1_q[s] <= h1_q[s-1];
        ha_q[s] <= ha_q[s-1];
      end
      // hz2 for hh @15; D2 in the clock before vv @4, so that u_vvhh's b operand has no select
      hsq2_q <= at(ps_q[PS_VVHH], 3) ? cfg_i.d2 : hkd_s1328;
      nnm_q  <= max_np(nnhxy_s1415, SHADE_EPS);
      nnm2_q <= nnm_q;
      rq_q   <= rvnh_s91920;
      nu1_q  <= nunh1_s2023;
      nua_q  <= dvnc_s22131;
      // nlz is lane 0's output when the pixel is in S22, nhz the clock after (no pixel in S22 then)
      z_q <= cv_q[22] ? nla_s2122 : nunh1_s2023;
      m_q <= max_np(dot_s2526, SHADE_ZERO);
      a_q <= acc1_s2934;
      ca_q[31]  <= caa_s3031;
      ca_q[32]  <= ca_q[31];
      ca1_q <= dvnc_s22131;
      sp_q <= ssp_s2932;
      // the tail's stream: R (lane 0, S34), G (lane 1, S34, held a clock), B (lane 0, S35, held)
      gh_q <= cc_s34[1];
      bh_q <= cc_s34[0];
      cl_q <= min_np(max_np(cv_q[34] ? cc_s34[0] : cv_q[35] ? gh_q : bh_q, SHADE_ZERO),
                     SHADE_ONE);
      // the floors come R (S39), G (S40), B (S41); the result is complete in core S41
      r_q[40] <= idx[7:0];
      r_q[41] <= r_q[40];
      g_q     <= idx[7:0];
      if (cv_q[41]) res_q <= {idx[7:0], g_q, r_q[41]};
    end
  end

  // ---- float units ----------------------------------------------------------------------------
  // Operand selects: at(ps_q[PS_<unit>], a) = 1 means the unit's operation of core stage a (the
  // phase is a mod 4; see "Phase replicas" above); the last operand of a select chain is the
  // remaining operation's (stages of other phases mod 4; see the header).  -du, -dv: the sign
  // bit flipped.
  f24_t neg_du9, neg_dv9;
  assign neg_du9 = {~du_q[9][23], du_q[9][22:0]};
  assign neg_dv9 = {~dv_q[9][23], dv_q[9][22:0]};

  // 5: du^2 @1 / 7: h_y^2 @12
  f24_t uh_sel;
  assign uh_sel = at(ps_q[PS_UV2HY2], 1) ? du_q[1] : nxyh1_s1112;
  f24_mul u_uv2hy2 (.clk_i, .en_i, .a_i(uh_sel), .b_i(uh_sel), .y_o(uv2hy2_s213));
  // 5: dv^2 @1 / 4: n_x rn @19 / n_z rn @20 / 12: C_y a @30 (stages 1, 3, 0, 2 mod 4)
  // Its operands are selected a clock early into registers of its own (a 4:1 select in front of
  // the DSP was the routed top's slowest path, 17.2 ns): C_y (S29 -> S30), n_x, n_z (S18 ->
  // S19, S20), dv (S0 -> S1), rn (rq_q's input) and a (a_q's input) are picked by the phase of
  // the clock before, as the S30, S19, S1 registers, rq_q and a_q load them unconditionally, so
  // the operand is the same word.  Only n_x rn @19 takes rsqrt's output straight (2:1 select).
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      dvnc_a_q <= at(ps_q[PS_DVNC], 29) ? col1_q[29]
                : (at(ps_q[PS_DVNC], 18) || at(ps_q[PS_DVNC], 19)) ? na_q[18] : in_dv;
      dvnc_b_q <= at(ps_q[PS_DVNC], 29) ? acc1_s2934
                : at(ps_q[PS_DVNC], 19) ? rvnh_s91920 : in_dv;
    end
  end
  f24_mul u_dvnc (.clk_i, .en_i, .a_i(dvnc_a_q),
                  .b_i(at(ps_q[PS_DVNC], 19) ? rvnh_s91920 : dvnc_b_q), .y_o(dvnc_s22131));

  // 1: n_x - 1 @1 / n_z - 1 @2; n_y - 1 @1 / 5: du^2 + dv^2 @2
  f24_add u_na   (.clk_i, .en_i, .a_i(m2a_q), .b_i(NEG_ONE), .y_o(na_s34));
  f24_add u_n1uv (.clk_i, .en_i, .a_i(at(ps_q[PS_N1UV], 1) ? m2y_q : uv2hy2_s213),
                  .b_i(at(ps_q[PS_N1UV], 1) ? NEG_ONE : dvnc_s22131), .y_o(n1uv_s34));

  // 5: vv @4 / 7: hh @15
  f24_add u_vvhh (.clk_i, .en_i, .a_i(at(ps_q[PS_VVHH], 4) ? n1uv_s34 : nnhxy_s1415),
                  .b_i(hsq2_q), .y_o(vvhh_s617));

  // 2: n_x^2 @8 / n_z^2 @9; n_y^2 @8 / 6: v_y @9
  f24_mul u_nsqa   (.clk_i, .en_i, .a_i(na_q[8]), .b_i(na_q[8]), .y_o(nsqa_s910));
  f24_mul u_nsq1v1 (.clk_i, .en_i, .a_i(at(ps_q[PS_NSQ1V1], 8) ? n1_q[8] : neg_dv9),
                    .b_i(at(ps_q[PS_NSQ1V1], 8) ? n1_q[8] : rvnh_s91920), .y_o(nsq1v1_s910));
  // 6: v_x @9 / v_z @10
  f24_mul u_va (.clk_i, .en_i, .a_i(at(ps_q[PS_VA], 9) ? neg_du9 : cfg_i.d),
                .b_i(at(ps_q[PS_VA], 9) ? rvnh_s91920 : rv_q), .y_o(va_s1011));

  // 2: nx2 + ny2 @9 / 7: h_y = l_y + v_y @10
  f24_add u_nxyh1 (.clk_i, .en_i, .a_i(at(ps_q[PS_NXYH1], 9) ? nsqa_s910 : light[1]),
                   .b_i(nsq1v1_s910), .y_o(nxyh1_s1112));
  // 7: h_x @10 / h_z @11
  f24_add u_ha (.clk_i, .en_i, .a_i(at(ps_q[PS_HA], 10) ? light[0] : light[2]), .b_i(va_s1011),
                .y_o(ha_s1213));
  // 7: h_x^2 @12 / h_z^2 @13 / 11: KD ndl @26 / 10: ndh^2 @27 (stages 0 .. 3 mod 4)
  f24_mul u_hkd (.clk_i, .en_i,
                 .a_i(at(ps_q[PS_HKD], 26) ? cfg_i.kd : at(ps_q[PS_HKD], 27) ? m_q : ha_s1213),
                 .b_i((at(ps_q[PS_HKD], 26) || at(ps_q[PS_HKD], 27)) ? m_q : ha_s1213),
                 .y_o(hkd_s1328));
  // 2: nn @12 / 7: hx2 + hy2 @13
  f24_add u_nnhxy (.clk_i, .en_i, .a_i(at(ps_q[PS_NNHXY], 12) ? nxy_q : hkd_s1328),
                   .b_i(at(ps_q[PS_NNHXY], 12) ? nsq2_q[12] : uv2hy2_s213), .y_o(nnhxy_s1415));
  // 6: rv @6 / 4: rn @16 / 8: rh @17 (stages 2, 0, 1 mod 4; vv and hh are both u_vvhh's output)
  f24_rsqrt #(.LAT(RSQRT_LAT)) u_rvnh (.clk_i, .en_i,
                                       .a_i(at(ps_q[PS_RVNH], 16) ? nnm2_q : vvhh_s617),
                                       .y_o(rvnh_s91920));

  // n_y rn @19 / 9: n_y l_y @20 / n_x h_x @21 / n_z h_z @22
  f24_mul u_nunh1 (.clk_i, .en_i,
                   .a_i(at(ps_q[PS_NUNH1], 19) ? n1_q[19]
                      : at(ps_q[PS_NUNH1], 20) ? nunh1_s2023 : nua_q),
                   .b_i(at(ps_q[PS_NUNH1], 19) ? rvnh_s91920
                      : at(ps_q[PS_NUNH1], 20) ? light[1] : hua_s2122),
                   .y_o(nunh1_s2023));
  // 9: n_x l_x @20 / n_z l_z @21
  f24_mul u_nla (.clk_i, .en_i, .a_i(dvnc_s22131),
                 .b_i(at(ps_q[PS_NLA], 20) ? light[0] : light[2]), .y_o(nla_s2122));
  // 8: h_x rh @20 / h_z rh @21; h_y rh @20 / 9: n_y h_y @21
  f24_mul u_hua (.clk_i, .en_i, .a_i(ha_q[20]), .b_i(at(ps_q[PS_HUA], 20) ? rvnh_s91920 : rq_q),
                 .y_o(hua_s2122));
  f24_mul u_hunh1 (.clk_i, .en_i, .a_i(at(ps_q[PS_HUNH1], 20) ? h1_q[20] : nu1_q),
                   .b_i(at(ps_q[PS_HUNH1], 20) ? rvnh_s91920 : hunh1_s2122), .y_o(hunh1_s2122));
  // 9: nlx + nly @21 / nhx + nhy @22
  f24_add u_dxy (.clk_i, .en_i, .a_i(at(ps_q[PS_DXY], 21) ? nla_s2122 : nunh1_s2023),
                 .b_i(at(ps_q[PS_DXY], 21) ? nunh1_s2023 : hunh1_s2122), .y_o(dxy_s2324));
  // 9: dot(n, l) @23 / dot(n, h) @24
  f24_add u_dot (.clk_i, .en_i, .a_i(dxy_s2324), .b_i(z_q), .y_o(dot_s2526));

  // 11: a @27 / 12: C_y a + sp @32 (lane 1 of the tail)
  f24_add u_acc1 (.clk_i, .en_i, .a_i(at(ps_q[PS_ACC1], 27) ? cfg_i.ambient : ca1_q),
                  .b_i(at(ps_q[PS_ACC1], 27) ? hkd_s1328 : ssp_s2932), .y_o(acc1_s2934));
  assign cc_s34[1] = acc1_s2934;
  // 10: ^4 @28 / ^8 @29 / ^16 @30 / 11: sp = KS s @31 (stages 0 .. 3 mod 4)
  f24_t s2_sel;
  assign s2_sel = at(ps_q[PS_SSP], 28) ? hkd_s1328 : ssp_s2932;
  f24_mul u_ssp (.clk_i, .en_i, .a_i(at(ps_q[PS_SSP], 31) ? cfg_i.ks : s2_sel), .b_i(s2_sel),
                 .y_o(ssp_s2932));
  // 12: C_x a @29 / C_z a @30
  f24_mul u_caa (.clk_i, .en_i, .a_i(cola_q[29]), .b_i(at(ps_q[PS_CAA], 29) ? acc1_s2934 : a_q),
                 .y_o(caa_s3031));

  // the tail: 12: + sp @32 (R, then B @33; G's add is u_acc1); 13: clamp (cl_q: R, G, B a
  // clock apart); 14: unorm8
  f24_add u_cc0 (.clk_i, .en_i, .a_i(ca_q[32]), .b_i(at(ps_q[PS_CC0], 32) ? ssp_s2932 : sp_q),
                 .y_o(cc_s34[0]));
  // one lane for the three channels, R, G and B a clock apart (operations @35 / @36 / @37, then
  // @36 .. @38 and @38 .. @40)
  f24_mul u_k  (.clk_i, .en_i, .a_i(cl_q), .b_i(SHADE_255), .y_o(k_s36));
  f24_add u_kh (.clk_i, .en_i, .a_i(k_s36), .b_i(SHADE_HALF), .y_o(kh_s38));
  // sat_o is not needed: the operand is in [0.5, 255.5] or NaN
  f24_to_index #(.W(9)) u_idx (.clk_i, .en_i, .a_i(kh_s38), .idx_o(idx), .sat_o());
  logic unused_idx;                 // bit 8: the index is in 0 .. 255 (see the header)
  assign unused_idx = idx[8];
  // a pixel that waited 3 clocks is at the output in core S41, the others in S42 .. S44
  assign rgb_o = cv_q[41] ? {idx[7:0], g_q, r_q[41]} : res_q;

  // The simulation checks are in shade_unit_assert.sv (bound into every instance).

endmodule
