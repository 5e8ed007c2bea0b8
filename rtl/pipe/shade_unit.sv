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
// Fully pipelined, fixed latency SHADE_LAT = 40 enabled clocks (shade_pkg), one pixel every other
// enabled clock at most (valid_i must not be 1 on two consecutive enabled clocks; asserted).  In
// dm_pipeline a pixel needs two filtered quads, which come one per clock at most.
// Every register (valid, tag, data, the float units) advances only while en_i is 1, so the
// enclosing pipeline stalls the whole unit with en_i = 0.  A pixel is taken on an enabled edge with
// valid_i = 1; its result shows at valid_o / tag_o / rgb_o after SHADE_LAT enabled edges and holds
// while en_i is 0.  valid is reset by rst_ni (synchronous, active low, independent of en_i); data
// and tag registers have no reset.
//
// Stage schedule (S0 = the input ports; "a -> b": a unit takes operands in Sa, result in Sb;
// "reg" = exact logic into one register):
//   S0   M_c * 2 (exact doubling, see below)                          reg          S0 -> S1
//        du*du, dv*dv                                                f24_mul      S0 -> S1
//        du, dv delayed S0 -> S8; C delayed S0 -> S22
//   S1   n_c = 2M_c - 1                                              f24_add x3   S1 -> S3
//        du2 + dv2                                                   f24_add      S1 -> S3
//   S3   n_c * n_c                                                   f24_mul x3   S3 -> S4
//        (du2 + dv2) + D2 = vv                                       f24_add      S3 -> S5
//        n delayed S3 -> S12
//   S4   nx2 + ny2 (nz2 delayed S4 -> S6)                            f24_add      S4 -> S6
//   S5   rv = rsqrt(vv)                                              f24_rsqrt    S5 -> S8
//   S6   nn = (nx2 + ny2) + nz2                                      f24_add      S6 -> S8
//   S8   v = (-du rv, -dv rv, D rv)                                  f24_mul x3   S8 -> S9
//        max(nn, EPS)                                                reg          S8 -> S9
//   S9   h_c = l_c + v_c                                             f24_add x3   S9 -> S11
//        rn = rsqrt(nn)                                              f24_rsqrt    S9 -> S12
//   S11  h_c * h_c                                                   f24_mul x3   S11 -> S12
//        h delayed S11 -> S19
//   S12  n_c * rn (unit normal)                                      f24_mul x3   S12 -> S13
//        hx2 + hy2 (hz2 delayed S12 -> S14)                          f24_add      S12 -> S14
//   S13  n_c * l_c                                                   f24_mul x3   S13 -> S14
//        unit normal delayed S13 -> S20
//   S14  hh = (hx2 + hy2) + hz2                                      f24_add      S14 -> S16
//        nlx + nly (nlz delayed S14 -> S16)                          f24_add      S14 -> S16
//   S16  rh = rsqrt(hh)                                              f24_rsqrt    S16 -> S19
//        dot(n, l) = (nlx + nly) + nlz                               f24_add      S16 -> S18
//   S18  ndl = max(dot(n, l), 0)                                     reg          S18 -> S19
//   S19  h_c * rh (unit half vector)                                 f24_mul x3   S19 -> S20
//        KD * ndl                                                    f24_mul      S19 -> S20
//   S20  n_c * h_c                                                   f24_mul x3   S20 -> S21
//        a = AMBIENT + KD ndl                                        f24_add      S20 -> S22
//   S21  nhx + nhy (nhz delayed S21 -> S23)                          f24_add      S21 -> S23
//   S22  C_c * a                                                     f24_mul x3   S22 -> S23
//        C_c a delayed S23 -> S31
//   S23  dot(n, h) = (nhx + nhy) + nhz                               f24_add      S23 -> S25
//   S25  ndh = max(dot(n, h), 0)                                     reg          S25 -> S26
//   S26  s = ndh^2, ^4, ^8, ^16 (four squarings)                     f24_mul x4   S26 -> S30
//   S30  sp = KS * s                                                 f24_mul      S30 -> S31
//   The tail (steps 12-14 after C_c a) runs on two lanes: lane 0 takes R in S31 and B (its
//   C_c a and sp a clock older) in S32, lane 1 takes G; the pixel after is two clocks away at
//   least (valid_i never on two consecutive enabled clocks; asserted), so lane 0 is free then.
//   S31  the lanes' operand registers: {C_R a, sp}, {C_G a, sp}; S32: {C_B a, sp}  reg
//   S32  c_c = C_c a + sp                                            f24_add x2   S32 -> S34
//   S34  min(max(c_c, 0), 1)                                         reg          S34 -> S35
//   S35  c_c * 255                                                   f24_mul x2   S35 -> S36
//   S36  + 0.5                                                       f24_add x2   S36 -> S38
//   S38  floor -> unorm8                                             f24_to_index S38 -> S39
//        (B a clock behind on lane 0: its floor S39 -> S40)
//   S39  R and G held                                                reg          S39 -> S40
//   S40  outputs (R, G from the hold registers, B from lane 0's floor); valid and tag delayed
//        S0 -> S40
// The three f24_rsqrt run at LAT = pipe_pkg::F24_RSQRT_LAT = 3 (table / product + sum / round:
// over 120 MHz; at their 2 clocks they limit the unit to below 60 MHz), with the same results;
// the schedule above is written for that latency (checked at elaboration).
//
// Float units: 34 f24_mul, 21 f24_add, 3 f24_rsqrt, 2 f24_to_index #(9); no f24_cmp (35, 23, 3
// and 3 before the tail shared lane 0 between R and B).  Exact logic (no rounding involved, each
// into one register): 3 doublers, max(nn, EPS), 2 x max(., 0) and 2 clamps.
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

  localparam int unsigned NS = SHADE_LAT;  // S1 .. S38 are registers

  // The three f24_rsqrt: the schedule (header) is written for 3 clocks each (rv S5 -> S8, rn
  // S9 -> S12, rh S16 -> S19); another latency needs the stages below renumbered.
  localparam int unsigned RSQRT_LAT = pipe_pkg::F24_RSQRT_LAT;
  if (RSQRT_LAT != 3 || NS != 40) begin : g_check_lat
    $error("shade_unit: the stage schedule is written for F24_RSQRT_LAT = 3, SHADE_LAT = 40");
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

  // ---- valid and tag: S1 .. S40 (stage_v[k]: a pixel in stage k; the tail reads them) ------------
  /* verilator lint_off UNUSEDSIGNAL */  // the schedule reads stages 1, 31 and 39 of the 40
  logic [NS:1] stage_v;
  /* verilator lint_on UNUSEDSIGNAL */
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(NS)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o(stage_v));

  logic [1:0][7:0] rg_q;            // S40: R and G held a clock for B
  logic signed [8:0] idx [2];       // floor(c 255 + 0.5) per lane, in 0 .. 255 (S39; B in S40)

  // ---- float-unit outputs (named by the stage where they appear) ------------------------------
  f24_t [2:0] n_s3;                 // 2M - 1
  f24_t [2:0] nsq_s4;               // n_c^2
  f24_t       nxy_s6, nn_s8;
  f24_t       du2_s1, dv2_s1, duv_s3, vv_s5, rv_s8;
  f24_t [2:0] v_s9;                 // unit view vector
  f24_t       rn_s12;
  f24_t [2:0] h_s11;                // l + v
  f24_t [2:0] hsq_s12;
  f24_t [2:0] nu_s13;               // unit normal
  f24_t       hxy_s14, hh_s16, rh_s19;
  f24_t [2:0] nl_s14;               // n_c l_c
  f24_t       nlxy_s16, dnl_s18;
  f24_t [2:0] hu_s20;               // unit half vector
  f24_t [2:0] nh_s21;               // n_c h_c
  f24_t       kdl_s20, a_s22, nhxy_s23, dnh_s25;
  f24_t [2:0] ca_s23;               // C_c a
  f24_t       s_s27, s_s28, s_s29, s_s30, sp_s31;
  f24_t [1:0] cc_s34;               // C_c a + sp, per lane (lane 0: R, then B a clock later)
  f24_t [1:0] k_s36, kh_s38;        // c 255, c 255 + 0.5

  // ---- stage registers of the data path (no reset) --------------------------------------------
  f24_t [2:0] m2_q;                 // S1: 2M
  f24_t       du_q   [1:8];         // S1 .. S8
  f24_t       dv_q   [1:8];
  f24_t [2:0] col_q  [1:22];        // S1 .. S22
  f24_t       nsqz_q [5:6];         // nz^2, S5 .. S6
  f24_t [2:0] n_q    [4:12];        // 2M - 1, S4 .. S12
  f24_t       nnm_q;                // S9: max(nn, EPS)
  f24_t       hsqz_q [13:14];       // hz^2
  f24_t [2:0] h_q    [12:19];       // l + v
  f24_t       nlz_q  [15:16];       // nz lz
  f24_t [2:0] nu_q   [14:20];       // unit normal
  f24_t       ndl_q;                // S19: max(dot(n, l), 0)
  f24_t       nhz_q  [22:23];       // nz hz
  f24_t       ndh_q;                // S26: max(dot(n, h), 0)
  f24_t [2:0] ca_q   [24:31];       // C_c a
  f24_t       cab_q;                // S32: C_B a (lane 0's second operand set)
  f24_t       sp_q;                 // S32: sp
  f24_t [1:0] ta_q, tb_q;           // S32: the lanes' adder operands
  f24_t [1:0] cl_q;                 // S35: clamped colour, per lane

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int c = 0; c < 3; c++) m2_q[c] <= dbl(nrm_i[c]);
      du_q[1] <= du_i;
      dv_q[1] <= dv_i;
      for (int s = 2; s <= 8; s++) begin
        du_q[s] <= du_q[s-1];
        dv_q[s] <= dv_q[s-1];
      end
      col_q[1] <= col_i;
      for (int s = 2; s <= 22; s++) col_q[s] <= col_q[s-1];
      nsqz_q[5] <= nsq_s4[2];
      nsqz_q[6] <= nsqz_q[5];
      n_q[4] <= n_s3;
      for (int s = 5; s <= 12; s++) n_q[s] <= n_q[s-1];
      nnm_q <= max_np(nn_s8, SHADE_EPS);
      hsqz_q[13] <= hsq_s12[2];
      hsqz_q[14] <= hsqz_q[13];
      h_q[12] <= h_s11;
      for (int s = 13; s <= 19; s++) h_q[s] <= h_q[s-1];
      nlz_q[15] <= nl_s14[2];
      nlz_q[16] <= nlz_q[15];
      nu_q[14] <= nu_s13;
      for (int s = 15; s <= 20; s++) nu_q[s] <= nu_q[s-1];
      ndl_q <= max_np(dnl_s18, SHADE_ZERO);
      nhz_q[22] <= nh_s21[2];
      nhz_q[23] <= nhz_q[22];
      ndh_q <= max_np(dnh_s25, SHADE_ZERO);
      ca_q[24] <= ca_s23;
      for (int s = 25; s <= 31; s++) ca_q[s] <= ca_q[s-1];
      // the tail: R (lane 0) and G (lane 1) in S31, B on lane 0 in S32 (a pixel is in S31 iff
      // stage_v[31]; the clock after, lane 0 takes B, which waited a clock in cab_q / sp_q)
      cab_q <= ca_q[31][2];
      sp_q  <= sp_s31;
      ta_q[0] <= stage_v[31] ? ca_q[31][0] : cab_q;
      tb_q[0] <= stage_v[31] ? sp_s31      : sp_q;
      ta_q[1] <= ca_q[31][1];
      tb_q[1] <= sp_s31;
      for (int l = 0; l < 2; l++) cl_q[l] <= min_np(max_np(cc_s34[l], SHADE_ZERO), SHADE_ONE);
      if (stage_v[39]) begin
        rg_q[0] <= idx[0][7:0];
        rg_q[1] <= idx[1][7:0];
      end
    end
  end

  // ---- float units ----------------------------------------------------------------------------
  // 5-6: the view vector
  f24_mul u_du2 (.clk_i, .en_i, .a_i(du_i), .b_i(du_i), .y_o(du2_s1));
  f24_mul u_dv2 (.clk_i, .en_i, .a_i(dv_i), .b_i(dv_i), .y_o(dv2_s1));
  f24_add u_duv (.clk_i, .en_i, .a_i(du2_s1), .b_i(dv2_s1), .y_o(duv_s3));
  f24_add u_vv  (.clk_i, .en_i, .a_i(duv_s3), .b_i(cfg_i.d2), .y_o(vv_s5));
  f24_rsqrt #(.LAT(RSQRT_LAT)) u_rv (.clk_i, .en_i, .a_i(vv_s5), .y_o(rv_s8));
  f24_mul u_vx  (.clk_i, .en_i, .a_i({~du_q[8][23], du_q[8][22:0]}), .b_i(rv_s8), .y_o(v_s9[0]));
  f24_mul u_vy  (.clk_i, .en_i, .a_i({~dv_q[8][23], dv_q[8][22:0]}), .b_i(rv_s8), .y_o(v_s9[1]));
  f24_mul u_vz  (.clk_i, .en_i, .a_i(cfg_i.d), .b_i(rv_s8), .y_o(v_s9[2]));

  // 2-4: |n|^2, its reciprocal square root
  f24_add u_nxy (.clk_i, .en_i, .a_i(nsq_s4[0]), .b_i(nsq_s4[1]), .y_o(nxy_s6));
  f24_add u_nn  (.clk_i, .en_i, .a_i(nxy_s6), .b_i(nsqz_q[6]), .y_o(nn_s8));
  f24_rsqrt #(.LAT(RSQRT_LAT)) u_rn (.clk_i, .en_i, .a_i(nnm_q), .y_o(rn_s12));

  // 7-8: |h|^2, its reciprocal square root
  f24_add u_hxy (.clk_i, .en_i, .a_i(hsq_s12[0]), .b_i(hsq_s12[1]), .y_o(hxy_s14));
  f24_add u_hh  (.clk_i, .en_i, .a_i(hxy_s14), .b_i(hsqz_q[14]), .y_o(hh_s16));
  f24_rsqrt #(.LAT(RSQRT_LAT)) u_rh (.clk_i, .en_i, .a_i(hh_s16), .y_o(rh_s19));

  // 9, 11: n.l, the diffuse term a = AMBIENT + KD ndl
  f24_add u_nlxy (.clk_i, .en_i, .a_i(nl_s14[0]), .b_i(nl_s14[1]), .y_o(nlxy_s16));
  f24_add u_dnl  (.clk_i, .en_i, .a_i(nlxy_s16), .b_i(nlz_q[16]), .y_o(dnl_s18));
  f24_mul u_kdl  (.clk_i, .en_i, .a_i(cfg_i.kd), .b_i(ndl_q), .y_o(kdl_s20));
  f24_add u_a    (.clk_i, .en_i, .a_i(cfg_i.ambient), .b_i(kdl_s20), .y_o(a_s22));

  // 9-11: n.h, s = ndh^16, sp = KS s
  f24_add u_nhxy (.clk_i, .en_i, .a_i(nh_s21[0]), .b_i(nh_s21[1]), .y_o(nhxy_s23));
  f24_add u_dnh  (.clk_i, .en_i, .a_i(nhxy_s23), .b_i(nhz_q[23]), .y_o(dnh_s25));
  f24_mul u_s1   (.clk_i, .en_i, .a_i(ndh_q), .b_i(ndh_q), .y_o(s_s27));
  f24_mul u_s2   (.clk_i, .en_i, .a_i(s_s27), .b_i(s_s27), .y_o(s_s28));
  f24_mul u_s3   (.clk_i, .en_i, .a_i(s_s28), .b_i(s_s28), .y_o(s_s29));
  f24_mul u_s4   (.clk_i, .en_i, .a_i(s_s29), .b_i(s_s29), .y_o(s_s30));
  f24_mul u_sp   (.clk_i, .en_i, .a_i(cfg_i.ks), .b_i(s_s30), .y_o(sp_s31));

  // per component
  for (genvar c = 0; c < 3; c++) begin : g_c
    // 1: decode; 2: squares; 4: normalise
    f24_add u_n   (.clk_i, .en_i, .a_i(m2_q[c]), .b_i(NEG_ONE), .y_o(n_s3[c]));
    f24_mul u_nsq (.clk_i, .en_i, .a_i(n_s3[c]), .b_i(n_s3[c]), .y_o(nsq_s4[c]));
    f24_mul u_nu  (.clk_i, .en_i, .a_i(n_q[12][c]), .b_i(rn_s12), .y_o(nu_s13[c]));
    // 7-8: half vector, its squares, normalise
    f24_add u_h   (.clk_i, .en_i, .a_i(light[c]), .b_i(v_s9[c]), .y_o(h_s11[c]));
    f24_mul u_hsq (.clk_i, .en_i, .a_i(h_s11[c]), .b_i(h_s11[c]), .y_o(hsq_s12[c]));
    f24_mul u_hu  (.clk_i, .en_i, .a_i(h_q[19][c]), .b_i(rh_s19), .y_o(hu_s20[c]));
    // 9: the dot products' products
    f24_mul u_nl  (.clk_i, .en_i, .a_i(nu_s13[c]), .b_i(light[c]), .y_o(nl_s14[c]));
    f24_mul u_nh  (.clk_i, .en_i, .a_i(nu_q[20][c]), .b_i(hu_s20[c]), .y_o(nh_s21[c]));
    // 12: colour
    f24_mul u_ca  (.clk_i, .en_i, .a_i(col_q[22][c]), .b_i(a_s22), .y_o(ca_s23[c]));
  end

  // the tail, per lane: 12: + sp; 13: clamp; 14: unorm8
  for (genvar l = 0; l < 2; l++) begin : g_lane
    f24_add u_cc  (.clk_i, .en_i, .a_i(ta_q[l]), .b_i(tb_q[l]), .y_o(cc_s34[l]));
    f24_mul u_k   (.clk_i, .en_i, .a_i(cl_q[l]), .b_i(SHADE_255), .y_o(k_s36[l]));
    f24_add u_kh  (.clk_i, .en_i, .a_i(k_s36[l]), .b_i(SHADE_HALF), .y_o(kh_s38[l]));
    // sat_o is not needed: the operand is in [0.5, 255.5] or NaN
    f24_to_index #(.W(9)) u_idx (.clk_i, .en_i, .a_i(kh_s38[l]), .idx_o(idx[l]), .sat_o());
  end
  logic unused_idx;                 // bit 8: the index is in 0 .. 255 (see the header)
  assign unused_idx = idx[0][8] ^ idx[1][8];
  assign rgb_o = {idx[0][7:0], rg_q[1], rg_q[0]};

`ifndef SYNTHESIS
  // Lane 0 serves R and then B: no pixel on the enabled clock after one.
  pixel_spacing: assert property (@(posedge clk_i) disable iff (!rst_ni)
    en_i && valid_i |-> !stage_v[1]);
`endif

endmodule
