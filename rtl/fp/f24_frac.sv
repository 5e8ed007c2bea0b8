// SPDX-License-Identifier: Apache-2.0
// f24_frac: y = sub(a, from_int(to_index(a, 20), 20)) of the f24 engine in one unit: the word of
// f24_to_index #(.W(20)), f24_from_int #(.W(20)) and f24_add(a, -that) for every a (model.f24.sub,
// model.f24_conv.to_index / from_int at model.arith.INDEX_W = 20 bits).  It replaces that chain
// where the texture address unit takes a coordinate's bilinear weight, fx = x - floor(x)
// (tex_addr; the floor itself still comes from its f24_to_index, for the clamps).  Not one of the
// FLOAT24 units: a fused chain, like traverse_bdiff.
// tests: tb/f24_frac (directed edge cases and random words against the model, the latency and
// the hold while en_i = 0; a numpy mirror of the cases below over every one of the 2^24 words),
// and a SAT miter against the chain (scripts/flow/unit_miter.py --unit frac).
//
// The cases, with a = (-1)^s m 2^(e - 79), m = {1, fraction} (17 bits), k = 79 - e:
//   e = 0 (zeros, subnormal patterns): floor 0, and a - (+0) is a zero of a's sign;
//   e = 127: Inf gives a, NaN gives F24_NAN;
//   a >= 0, |a| < 1 (e <= 62): floor 0, y = a exactly;
//   a >= 0, 1 <= a < 2^16 (63 <= e <= 78): y = the k low bits of m (the fraction of a, exact),
//     normalised: exponent e - (leading zeros), +0 when they are 0;
//   a < 0, 1/2 <= |a| < 2^16 (62 <= e <= 78): y = ceil(|a|) - |a|: 2^k minus those k bits,
//     exact, normalised; +0 when they are 0;
//   a < 0, |a| < 1/2 (1 <= e <= 61): y = 1 - |a| in (1/2, 1], which needs rounding: RNE of
//     2^17 - |a| 2^17 is 2^17 - RNE(|a| 2^17) (2^17 is even), with RNE(|a| 2^17) = r =
//     m >> (62 - e) rounded to nearest even by the bit below and the bits under it:
//     y = 2^-17 (2^17 - r), 1.0 for r = 0;
//   2^16 <= |a| < 2^19 (79 <= e <= 81): a is an integer, from_int(floor(a)) = a, y = +0;
//   |a| >= 2^19 (e >= 82): the floor saturates to 2^19 - 1 (from_int rounds it to 2^19) or to
//     -2^19, so y = sign(a) RNE(|a| - 2^19): for e <= 98 the difference m - 2^(98 - e) (ulps of a)
//     is exact (normalised; +0 when 0); for e = 99 2^19 is half an ulp: m = 2^16 gives
//     (2^17 - 1) 2^(e - 80) exactly, any other m the even one of m - 1 and m (a tie); for e >= 100
//     y = a.
//
// Stage 1: the case, the operands of the one 17-bit addition (the fraction, 2^k minus it, 2^17 - r,
//          m - 2^(98 - e) or m - 1: every shift and mask by the exponent is decoded here) and
//          the words of the cases that need no normalising.
// Stage 2: the addition and the fraction mask: the value to normalise.
// Stage 3: the value normalised (leading-zero count, shift) into its word, or the word of stage 1.
// Latency LAT enabled clocks (3 or more; tex_addr uses ADD_LAT + 2, the clocks of the chain):
// LAT - 3 plain delay registers (f24_delay) after the three stages, the same word at every LAT.
module f24_frac
  import f24_pkg::*;
#(
  parameter int unsigned LAT = 3  // latency in enabled clocks, at least 3
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,    // operand
  output f24_t y_o     // a - from_int(to_index(a, 20), 20), as the engine rounds it
);

  if (LAT < 3) begin : g_check_lat
    $error("f24_frac: LAT must be at least 3");
  end

  typedef struct packed {
    logic        nrm;   // the result is the sum normalised (else the word w)
    logic        s;     // its sign
    logic [6:0]  e;     // the exponent of the sum's bit 16 (before normalising)
    logic [16:0] x, y;  // the addition: x + y + c
    logic        c;
    logic [16:0] mask;  // the bits of the sum kept (the k low bits for e in 62 .. 78)
    f24_t        w;     // the result of the other cases
  } s1_t;

  typedef struct packed {
    logic        nrm;  // the result is v normalised (else the word w)
    logic        s;    // its sign
    logic [6:0]  e;    // the exponent of v's bit 16 (before normalising)
    logic [16:0] v;    // the value to normalise (0: +0)
    f24_t        w;    // the result of the other cases
  } s2_t;

  function automatic s1_t stage1(input f24_t a);
    logic        s;
    logic [6:0]  e;
    logic [16:0] m;
    logic [4:0]  k;     // 79 - e: the fraction bits of m (e in 62 .. 78)
    logic [16:0] mask;  // the k low bits
    logic [16:0] f;     // the fraction of |a| in ulps of a
    logic [4:0]  sh;    // 62 - e: m's shift into RNE(|a| 2^17) (e in 45 .. 61)
    logic [16:0] q;     // m >> sh
    logic        g;     // the bit below q
    logic        st;    // a bit under g
    logic        rnd;   // RNE(|a| 2^17) = r = q + rnd
    s1_t         o;
    s    = a[23];
    e    = a[22:16];
    m    = {1'b1, a[15:0]};
    k    = 5'(7'd79 - e);
    mask = ~(17'h1FFFF << k);
    f    = m & mask;
    sh   = 5'(7'd62 - e);
    q    = (e < 7'd45) ? 17'd0 : m >> sh;
    g    = (e < 7'd45) ? 1'b0 : m[5'(sh - 5'd1)];
    st   = (e < 7'd44) ? 1'b1 : (m & ~(17'h1FFFF << 5'(sh - 5'd1))) != 17'd0;
    rnd  = g && (st || q[0]);
    o = '{nrm: 1'b0, s: 1'b0, e: e, x: '0, y: '0, c: 1'b0, mask: '1, w: a};
    // the operands of the one 17-bit addition, for every case that needs one
    if (e <= 7'd61) begin          // a < 0: 2^17 - r = ~q + 1 - rnd
      o.x = ~q;
      o.c = !rnd;
    end else if (e <= 7'd78) begin // a >= 0: f; a < 0: 2^k - f = (~f + 1) within k bits
      o.x    = s ? ~f : f;
      o.c    = s;
      o.mask = mask;
    end else if (e <= 7'd98) begin // |a| >= 2^19: m - 2^(98 - e)
      o.x = m;
      o.y = ~(17'd1 << 5'(7'd98 - e));
      o.c = 1'b1;
    end else begin                 // e = 99, m odd: m - 1
      o.x = m;
      o.y = 17'h1FFFF;
    end
    if (e == EXP_SPEC) begin
      o.w = (a[15:0] != 16'd0) ? F24_NAN : a;                       // Inf: a
    end else if (e == 7'd0) begin
      o.w = {s, 23'd0};                                             // a zero of a's sign
    end else if (!s && e <= 7'd62) begin
      o.w = a;                                                      // 0 < a < 1
    end else if (e <= 7'd61) begin                                  // 1 - |a|, rounded:
      if (q == 17'd0 && !rnd) o.w = {1'b0, 7'd63, 16'd0};           // 1.0, or 2^-17 d
      else begin
        o.nrm = 1'b1;
        o.e   = 7'd62;
      end
    end else if (e <= 7'd78) begin
      o.nrm = 1'b1;                                                 // the exact fractions
    end else if (e <= 7'd81) begin
      o.w = '0;                                                     // integers: +0
    end else if (e <= 7'd98) begin
      o.nrm = 1'b1;                                                 // |a| - 2^19, exact
      o.s   = s;
    end else if (e == 7'd99) begin
      if (a[15:0] == 16'd0) o.w = {s, 7'd98, 16'hFFFF};             // 2^16 - 1/2 ulps
      else if (a[0]) begin                                          // the tie, to even: m - 1
        o.nrm = 1'b1;
        o.s   = s;
      end
    end
    return o;
  endfunction

  function automatic s2_t stage2(input s1_t r);
    return '{nrm: r.nrm, s: r.s, e: r.e, v: (r.x + r.y + 17'(r.c)) & r.mask, w: r.w};
  endfunction

  function automatic f24_t stage3(input s2_t r);
    logic [4:0]  lz;
    logic [15:0] n;     // v's bits below its leading one, shifted up
    lz = 5'd16;
    for (int i = 0; i <= 16; i++) begin
      if (r.v[i]) lz = 5'(16 - i);
    end
    n = 16'(r.v << lz);
    return !r.nrm ? r.w
         : (r.v == 17'd0) ? '0
         : {r.s, 7'(r.e - 7'(lz)), n};
  endfunction

  s1_t  s1_q;
  s2_t  s2_q;
  f24_t y_q;

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s1_q <= stage1(a_i);
      s2_q <= stage2(s1_q);
      y_q  <= stage3(s2_q);
    end
  end

  f24_delay #(.W(24), .N(LAT - 3)) u_delay (.clk_i, .en_i, .d_i(y_q), .q_o(y_o));

endmodule
