// SPDX-License-Identifier: Apache-2.0
// traverse_bdiff: d = b - u for NB integer cell boundaries b and one position u, in fixed point,
// the same f24 word as f24_add(f24_from_int(b), -u) (model.traverse.crossing_time's
// ar.sub(ar.from_int(b), p0)) for every operand the traverse ring gives it:
//   0 <= b < 2^IB (b_i holds it in W-bit two's complement), and u a non-negative f24 below 2^IB
//   (+0, -0 or a normal number; sign bit 1 only for -0).
// The ring's boundaries lie in [0, N] (N <= 2^15: cells stay inside the pyramid) and its
// positions u0 in [0, W) (setup flags every other ray invalid), so IB = 16 covers them; the bound
// checker (traverse_bdiff_assert) flags an operand outside that range.
// Latency 3 enabled clocks, one operation per clock: the clocks of f24_from_int (1) and f24_add
// (2) it replaces.
//
// Why the same word.  u is taken to FB = 19 fraction bits, the last of them a sticky bit:
// U = floor(u * 2^19), with its lowest bit ORed with "u has bits below 2^-19" (jamming).  Then
// D = b * 2^19 - U is exact, and so is its rounding to 17 significant bits (round to nearest,
// ties to even), unless the sticky bit stood for lost bits.  That happens only for u < 2^-2
// (every u >= 2^-2 has its ulp at 2^-18 or above), and then:
//   - b >= 1: the exact b - u and b - U * 2^-19 lie strictly between the same two neighbouring
//     multiples of 2^-18, and both are above 3/4, where every f24 value and every halfway point
//     between two of them (the rounding boundaries, powers of two included) is a multiple of
//     2^-18: both round to the same word.
//   - b = 0: the result is -u, exactly (a separate path: u itself with its sign set).
// Without lost bits D is b - u exactly; D = 0 gives +0 (x + (-x) = +0, and 0 - (+-0) = +0).
// No result is below 2^-19 or above 2^16 in magnitude: no flush, no overflow.
// tests: tb/traverse_bdiff (against the model's from_int and add: directed edge cases, random
// operands, every u with a set of b), and a SAT miter against f24_from_int + f24_add
// (scripts/flow/bdiff_miter.py).
//
// Stage 1: U and its sticky bit (u's 17-bit significand shifted by the inverted exponent; the
//          sticky bit from one addition, exponent + trailing-zero count, compared with a
//          constant), split at bit 19: b * 2^19 has 19 zero low bits, so U's low part and the
//          borrow into the high part of b * 2^19 - U (low part non-zero) depend on u alone and
//          are registered here, beside b.
// Stage 2: the 16-bit high parts b - U_hi - borrow and U_hi - b side by side (two 17-bit carry
//          chains) and beside them the 19-bit low part of b * 2^19 - U (-U mod 2^19), the
//          magnitude M of the difference that is not negative, its leading-zero count (of the
//          high part, or 16 plus the low part's count when the high part is zero; flat
//          nibble-wise counts of both candidates, the sign picks).
// Stage 3: M normalised (leading one at bit 34), rounded to 17 bits at bit 18, packed; exponent
//          63 + (34 - lz) - 19.
module traverse_bdiff
  import f24_pkg::*;
#(
  parameter int unsigned W  = 20,  // width of each b_i (two's complement), at least IB + 1
  parameter int unsigned NB = 1    // boundaries per position (their shift of u is shared)
) (
  input  logic                clk_i,  // clock
  input  logic                en_i,   // clock enable: the registers advance only while en_i is 1
  input  logic signed [W-1:0] b_i [NB],  // boundaries, 0 <= b < 2^IB
  input  f24_t                u_i,    // position, non-negative, below 2^IB
  output f24_t                y_o [NB]   // f24(b - u)
);

  localparam int unsigned IB = 16;       // integer bits of b and u
  localparam int unsigned FB = 19;       // fraction bits of U (the last one sticky)
  localparam int unsigned MW = IB + FB;  // 35: width of b * 2^19, U and the magnitude M

  if (W < IB + 1) begin : g_check_w
    $error("traverse_bdiff: W must be at least IB + 1");
  end

  // ---- stage 1 -------------------------------------------------------------------------------
  // U = {1, f} * 2^(e - 79 + 19): the significand placed at bit 18 (e = 60: u in [2^-3, 2^-2))
  // and shifted right by 78 - e (left by up to 18 for e up to 78, u < 2^16).
  typedef struct packed {
    logic [IB-1:0] bs;   // b (b * 2^19 has 19 zero low bits)
  } s1b_t;
  typedef struct packed {
    logic [IB-1:0] uh;   // U's high part, U >> 19 (the integer part of u)
    logic [FB-1:0] ul;   // U's low part (sticky in bit 0): the low part of U - b * 2^19
    logic          bor;  // ul != 0: the borrow of b * 2^19 - U into its high part
    logic          st;   // U's sticky bit stands for lost bits (then u is not zero)
    logic [22:0]   mag;  // u's exponent and fraction (the result -u of b = 0)
  } s1u_t;

  // Leading zeros of a 20-bit word (20 for 0), flat: a zero flag and a 2-bit count per nibble
  // (one LUT each), then the first non-zero nibble picks {its index, its count} (no chain of
  // halvings, whose zero tests wait on each other's muxes).
  function automatic logic [4:0] clz20(input logic [19:0] v);
    logic [3:0]      nib;
    logic [4:0]      nz;
    logic [4:0][1:0] lc;
    logic [4:0]      n;
    for (int g = 0; g < 5; g++) begin
      nib   = v[19 - 4*g -: 4];
      nz[g] = (nib != 4'd0);
      lc[g] = nib[3] ? 2'd0 : nib[2] ? 2'd1 : nib[1] ? 2'd2 : 2'd3;
    end
    n = 5'd20;
    for (int g = 4; g >= 0; g--) begin
      if (nz[g]) n = {3'(g), lc[g]};
    end
    return n;
  endfunction

  function automatic logic [4:0] clz19(input logic [FB-1:0] v);  // leading zeros; 19 for 0
    return clz20({v, 1'b1});
  endfunction

  function automatic s1u_t fixed_of(input logic [22:0] u);  // (the sign is 0 or u is 0)
    logic [6:0]    e;
    logic [16:0]   m;
    logic [4:0]    tz;     // trailing zeros of m (16 for m = 2^16)
    logic          st;     // a one of m is shifted out below bit 0
    logic [MW-1:0] v;      // m * 2^18 >> (78 - e), without the sticky bit (0 for e = 0)
    e  = u[22:16];
    m  = {1'b1, u[15:0]};
    tz = 5'd16;
    for (int i = 15; i >= 0; i--) begin
      if (m[i]) tz = 5'(i);
    end
    // m * 2^18 >> (78 - e) = m * 2^67 >> (127 - e): a shift by ~e, no subtraction
    v  = MW'({m, 67'd0} >> ~e);
    // a one is lost when 78 - e > 18 + tz: one addition compared with a constant
    st = (e != 7'd0) && (({1'b0, e} + {3'd0, tz}) < 8'd60);
    return '{uh:  v[MW-1:FB],
             ul:  {v[FB-1:1], v[0] | st},
             bor: (v[FB-1:0] != '0) || st,
             st:  st,
             mag: u[22:0]};
  endfunction

  s1b_t s1b_q [NB];
  s1u_t s1u_q;

  // ---- stage 2 -------------------------------------------------------------------------------
  typedef struct packed {
    logic          neg;   // b < u
    logic          zero;  // b = u
    logic          spec;  // b = 0 with lost bits: the result is -u
    logic [MW-1:0] m;     // |D|
    logic [5:0]    lz;    // leading zeros of m (below 35)
    logic [22:0]   mag;   // u's exponent and fraction
  } s2_t;

  // D = b * 2^19 - U = (b - uh - bor) * 2^19 + nl with nl = -ul mod 2^19, and
  // -D = U - b * 2^19 = (uh - b) * 2^19 + ul (no borrow): the IB-bit high parts are subtracted
  // here, beside the 19-bit negation of ul (which depends on u alone).
  function automatic s2_t diff(input s1b_t b, input s1u_t u);
    logic [IB:0]   p;   // b - uh - bor (its top bit: D negative)
    logic [IB-1:0] q;   // uh - b (read when D is negative: then it is the high part of -D)
    logic [IB-1:0] h;   // the high part of M = |D|
    logic [5:0]    lp, lq;  // leading zeros of the high part of M in either case
    logic [5:0]    ll;      // leading zeros of M when its high part is zero
    logic [FB-1:0] nl;      // -ul mod 2^19: the low part of D
    p  = {1'b0, b.bs} - {1'b0, u.uh} - (IB+1)'(u.bor);
    q  = u.uh - b.bs;
    lp = {1'b0, clz20({p[IB-1:0], 4'hF})};  // (read only when not 0)
    lq = {1'b0, clz20({q, 4'hF})};
    nl = FB'(0) - u.ul;
    h  = p[IB] ? q : p[IB-1:0];
    ll = 6'(IB) + (p[IB] ? {1'b0, clz19(u.ul)} : {1'b0, clz19(nl)});
    return '{neg:  p[IB],
             zero: (h == '0) && !u.bor,
             spec: (b.bs == '0) && u.st,
             m:    {h, p[IB] ? u.ul : nl},
             lz:   (h != '0) ? (p[IB] ? lq : lp) : ll,
             mag:  u.mag};
  endfunction

  s2_t s2_q [NB];

  // ---- stage 3 -------------------------------------------------------------------------------
  function automatic f24_t pack(input s2_t s);
    logic [MW-2:0] n;    // m with its leading one at bit MW - 1, below that one
    logic          up;   // round up: above halfway, or halfway with an odd significand
    logic [6:0]    e;    // 63 + (MW - 1 - lz) - FB
    n  = (MW-1)'(s.m << s.lz);
    up = n[17] && ((n[16:0] != '0) || n[18]);
    e  = 7'(63 + MW - 1 - FB) - {1'b0, s.lz};
    return s.spec ? {1'b1, s.mag}
         : s.zero ? '0
         :          {s.neg, 23'({e, n[MW-2:18]} + 23'(up))};
  endfunction

  f24_t y_q [NB];

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s1u_q <= fixed_of(u_i[22:0]);
      for (int i = 0; i < NB; i++) begin
        s1b_q[i] <= '{bs: b_i[i][IB-1:0]};
        s2_q[i]  <= diff(s1b_q[i], s1u_q);
        y_q[i]   <= pack(s2_q[i]);
      end
    end
  end

  for (genvar g = 0; g < NB; g++) begin : g_out
    assign y_o[g] = y_q[g];
  end

endmodule
