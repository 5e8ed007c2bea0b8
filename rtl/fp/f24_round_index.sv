// SPDX-License-Identifier: Apache-2.0
// f24_round_index: idx = to_index(add(a, 0.5)) of the f24 engine in one unit: the word of
// f24_add(a, 0.5) followed by f24_to_index #(.W(W)) (model.f24.add, then model.f24_conv.to_index
// with W bits: floor, saturated to [-2^(W-1), 2^(W-1) - 1], NaN -> 0), for every a and
// 2 <= W <= 16.  It replaces that pair where the pipeline rounds a value to an index: the shading
// unit's colour codes (c 255 + 0.5, W = 9) and the MIP level (lod + 0.5).  Not one of the
// FLOAT24 units: a fused pair, like traverse_bdiff.
// tests: tb/f24_round_index (directed edge cases and random words against the model at several
// W, the latency and the hold while en_i = 0; a numpy mirror of the algorithm below over every
// one of the 2^24 words at every W), and a SAT miter against f24_add + f24_to_index
// (scripts/flow/unit_miter.py --unit round_index).
//
// Why floor(a + 0.5) needs no rounding step.  With a = (-1)^s m 2^(e - 79) (m = {1, fraction},
// 17 bits), the sum S = a + 0.5 is exact in fixed point with 18 fraction bits for |a| >= 2^-2
// (e >= 61), and for |a| < 2^-2 it lies in (0.25, 0.75), where every rounding of it has floor 0.
// add() rounds S to 17 significant bits (nearest, ties to even); the floor of that differs from
// floor(S) only if the rounding carries S up to the next integer n.  That needs n - S at most half
// the gap below n, while n - S is a multiple of a's ulp: below n = 1 the gap is 2^-17, and a =
// 0.5 - 2^-18 (e = 61, fraction 0xFFFF) gives S = 1 - 2^-18, a tie that rounds to the even 1.0;
// for every other n (and every negative S) a's ulp is larger than half the gap, so no other a
// is rounded across an integer.  So, with q = floor(|a|), r = its bit 2^-1 and t = the bits of
// |a| below 2^-1 (any set):
//   a >= 0: idx = q + r (floor(|a| + 0.5)), and 1 for a = 0.5 - 2^-18;
//   a < 0:  idx = -(q + (r & t)) (-ceil(|a| - 0.5));
// |a| >= 2^(W-1), Inf: saturated by the sign; NaN: 0; |a| < 2^-2, zeros, subnormal patterns: 0.
// Only the exponents 61 .. 61 + W give an unsaturated index: q has W - 1 bits, shifted out of the
// significand by 79 - e (18 - W .. 18).
//
// Stage 1: q, r, t (t from the fraction's trailing-zero count compared with the bit's position),
//          the increment (q + r, or q + (r & t)) into the magnitude, the saturating and zero cases.
// Stage 2: the sign applied, the magnitude 2^(W-1) of a positive sum saturated.
// Latency LAT enabled clocks (2 or more; the pipeline uses ADD_LAT + F24_TO_INDEX_LAT, the pair's):
// LAT - 2 plain delay registers (f24_delay) after the two stages, the same word at every LAT.
module f24_round_index
  import f24_pkg::*;
#(
  parameter int unsigned W   = 9,  // index width in bits, two's complement (2 .. 16)
  parameter int unsigned LAT = 2   // latency in enabled clocks, at least 2
) (
  input  logic                clk_i,  // clock
  input  logic                en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t                a_i,    // operand
  output logic signed [W-1:0] idx_o   // to_index(add(a_i, 0.5)), W bits, saturated
);

  if (W < 2 || W > 16) begin : g_check_w
    $error("f24_round_index: W must be in 2..16");
  end

  if (LAT < 2) begin : g_check_lat
    $error("f24_round_index: LAT must be at least 2");
  end

  localparam int unsigned E_LO  = 61;          // |a| >= 2^-2
  localparam int unsigned E_SAT = 62 + W;      // |a| >= 2^(W-1): saturated
  localparam logic signed [W-1:0] IDX_MAX = {1'b0, {(W-1){1'b1}}};
  localparam logic signed [W-1:0] IDX_MIN = {1'b1, {(W-1){1'b0}}};

  typedef struct packed {
    logic         s;     // the sign
    logic         zero;  // the index is 0 (NaN, |a| < 2^-2, zeros, subnormal patterns)
    logic         sat;   // |a| >= 2^(W-1) or Inf: saturated by the sign
    logic [W-1:0] mg;    // the index's magnitude (at most 2^(W-1))
  } s1_t;

  function automatic s1_t stage1(input f24_t a);
    logic [6:0]  e;
    logic [16:0] m;
    logic [4:0]  rp;    // the position of the bit 2^-1 in m: 78 - e (e in E_LO .. E_SAT - 1)
    logic [W-1:0] sh;   // m >> rp (the bits above W - 1 are 0 unless saturated): bit 0 is r,
                        // bits W-1:1 are q
    logic [4:0]  tz;    // trailing zeros of m (16 for m = 2^16)
    logic        t;     // a bit of m below position rp is set
    logic        inc;
    e  = a[22:16];
    m  = {1'b1, a[15:0]};
    rp = 5'(7'd78 - e);
    sh = W'(m >> rp);
    tz = 5'd16;
    for (int i = 15; i >= 0; i--) begin
      if (m[i]) tz = 5'(i);
    end
    t   = tz < rp;
    inc = a[23] ? (sh[0] && t) : (sh[0] || (e == 7'(E_LO) && a[15:0] == 16'hFFFF));
    return '{s:    a[23],
             zero: (e == EXP_SPEC && a[15:0] != 16'd0) || e < 7'(E_LO),
             sat:  e >= 7'(E_SAT),
             mg:   {1'b0, sh[W-1:1]} + W'(inc)};
  endfunction

  function automatic logic signed [W-1:0] stage2(input s1_t r);
    return r.zero ? '0
         : r.sat  ? (r.s ? IDX_MIN : IDX_MAX)
         : r.s    ? -$signed(r.mg)
         : r.mg[W-1] ? IDX_MAX : $signed(r.mg);
  endfunction

  s1_t                 s1_q;
  logic signed [W-1:0] y_q;

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s1_q <= stage1(a_i);
      y_q  <= stage2(s1_q);
    end
  end

  f24_delay #(.W(W), .N(LAT - 2)) u_delay (.clk_i, .en_i, .d_i(y_q), .q_o(idx_o));

endmodule
