// SPDX-License-Identifier: Apache-2.0
// f24_from_int: signed W-bit integer -> f24.  Exact when |k| has at most 17 significant bits,
// otherwise rounded to nearest, ties to even; 0 gives +0.  Latency LAT enabled clocks (1, the
// default, or 2), one conversion per clock; the result word is the same at both.  Golden model:
// model.f24_conv.from_int.
//
// Structure (one clock; the normalising shift is the long path, so the rounding is kept off it):
//   - k = 0 and k = -2^(W-1) are decoded from k itself: +0, and the constant -2^(W-1) (exact).
//     Every other k has a magnitude of W - 1 bits, one bit less to negate and normalise.
//   - |k| < 2^17 is exact: the leading-zero count and shift of the low 17 bits alone, no
//     rounding; its exponent is 79 - (leading zeros).
//   - |k| >= 2^17 (W > 18 only; W = 20 in the design: bit length 18 or 19) needs at most W - 19
//     bits of left shift: the count sees the bits above bit 16 with bit 17's place forced to one,
//     so the shift is short (one 2:1 mux at W = 20).  It is rounded before that shift: half an
//     ulp (at the guard position for the count) is added to the magnitude in one carry chain
//     beside the exact path's shifter, the sum is shifted, and on a tie (guard 1, sticky 0, from
//     the magnitude shifted alone) its last bit is cleared (the sum is then the odd neighbour of
//     the even result).  A sum that carries out of the bit length is exactly a power of two: the
//     shifted sum's top bit adds one to the exponent, the fraction is 0.
//   - No range check: the exponent is 63 + (bit length - 1), at most 63 + 62 for any |k| below
//     2^63 (plus one when rounding carries), and 2^63 itself is exact, so it stays in [63, 126].
// LAT = 2 (for clock speed): stage 1 the negation and the two leading-zero counts, stage 2 the
// shifts, the rounding and the choice of the result: the same operations as LAT = 1's function,
// split in two functions (written apart because Yosys maps the two functions composed into a
// different netlist from the single one: LAT = 1 keeps the single function's).
// Equal to the previous single round-and-pack (f24_pkg::f24_round_pack) for every W, and to the
// previous form of the rounding (shift, then {exponent, fraction} + 1 chosen by the round-up bit);
// checked by Yosys SAT miters for W = 2 .. 64 (a selection) and by the cocotb test against the
// model.
module f24_from_int
  import f24_pkg::*;
#(
  parameter int unsigned W   = 20,  // integer width in bits, two's complement (2 .. 64)
  parameter int unsigned LAT = 1    // latency in enabled clocks, 1 (the default) or 2
) (
  input  logic                clk_i,  // clock
  input  logic                en_i,   // clock enable: the registers advance only while en_i is 1
  input  logic signed [W-1:0] k_i,    // integer to convert
  output f24_t                y_o     // k_i as f24
);

  if (W < 2 || W > 64) begin : g_check_w
    $error("f24_from_int: W must be in 2..64");
  end

  if (LAT < 1 || LAT > 2) begin : g_check_lat
    $error("f24_from_int: LAT must be 1 or 2");
  end

  // The big path works on mag zero-extended to BW bits (at least 18: only W > 18 uses it); its
  // shift lzr is at most W - 19, so RW bits of it are enough.
  localparam int unsigned BW = (W > 19) ? W - 1 : 18;
  localparam int unsigned RW = (W > 20) ? $clog2(W - 18) : 1;
  localparam logic [BW-1:0] HALF = BW'(1) << (BW - 18);          // half an ulp for lzr = 0
  localparam logic [BW-1:0] STM  = (BW'(1) << (BW - 18)) - BW'(1);  // the bits below the guard

  // |k| >= 2^17 (W > 18 only): the magnitude has bit length BW - lzr >= 18, its last
  // BW - 17 - lzr bits drop.  Rounded to nearest even by adding half an ulp to the magnitude
  // itself (one carry chain, before the shift) and clearing the last bit on a tie (guard 1,
  // sticky 0: the sum is then the odd neighbour of the even result); the sum is shifted by lzr
  // afterwards.  A sum that carries out of the bit length is exactly a power of two: fraction 0,
  // the exponent one higher (bit BW of the shifted sum).
  function automatic f24_t round_big(input logic s, input logic [W-2:0] mag,
                                     input logic [RW-1:0] lzr);
    logic [BW-1:0] ub;     // mag, BW bits
    logic [BW-1:0] ul;     // ub << lzr: the leading one at bit BW - 1
    logic          tie;    // guard 1, sticky 0
    logic [BW:0]   r;      // ub + half an ulp
    logic [BW:0]   rl;     // r << lzr: the leading one at bit BW - 1, or BW after a carry
    ub  = BW'(mag);
    ul  = ub << lzr;
    tie = ul[BW-18] && ((ul & STM) == '0);
    r   = {1'b0, ub} + {1'b0, HALF >> lzr};
    rl  = r << lzr;
    return {s, 7'(7'(63 + W - 2) - 7'(lzr) + 7'(rl[BW])), rl[BW-2:BW-16], rl[BW-17] && !tie};
  endfunction

  // LAT = 1: the conversion as one function of k.
  function automatic f24_t from_int(input logic signed [W-1:0] k);
    logic               s;
    logic               kmin;   // k = -2^(W-1): exactly 2^(W-1) in magnitude
    logic [W-2:0]       mag;    // |k| for every other k (W - 1 bits)
    logic [63:0]        ml;     // mag, zero-extended
    // |k| < 2^17: exact.  Normalise the low 17 bits; no rounding.
    logic [4:0]         lzx;    // leading zeros of mag[16:0] (garbage for 0, which is not used)
    logic [15:0]        nxx;    // mag[16:0] << lzx below its leading one (at bit 16)
    logic [6:0]         ex;     // its biased exponent, 63 + 16 - lzx
    // |k| >= 2^17 (W > 18 only): at most W - 19 leading zeros, rounded to nearest even.
    logic               big;
    logic [63:0]        u;      // mag left-aligned in 64 bits
    logic [RW-1:0]      lzr;    // leading zeros of u, at most W - 19 (a one is forced in below)
    s    = k[W-1];
    kmin = s && (k[W-2:0] == '0);
    mag  = s ? -k[W-2:0] : k[W-2:0];
    ml   = 64'(mag);
    lzx  = f24_clz32({ml[16:0], 15'd0});
    nxx  = 16'(ml[16:0] << lzx);
    ex   = 7'd79 - {2'd0, lzx};
    big  = (ml[63:17] != 47'd0);
    u    = ml << (65 - W);
    lzr  = RW'(f24_clz64(u | (64'd1 << (82 - W))));
    // 0 gives +0.  The exponent never leaves [1, 126]: |k| <= 2^63, and 2^63 itself is exact.
    return (k == '0) ? '0
         : kmin      ? {1'b1, 7'(63 + W - 1), 16'd0}
         : !big      ? {s, ex, nxx}
         :             round_big(s, mag, lzr);
  endfunction

  // Stage 1's result (the register between the stages at LAT = 2).
  typedef struct packed {
    logic         zero;   // k = 0
    logic         kmin;   // k = -2^(W-1): exactly 2^(W-1) in magnitude
    logic         s;      // sign
    logic [W-2:0] mag;    // |k| for every other k (W - 1 bits)
    logic         big;    // |k| >= 2^17
    logic [4:0]   lzx;    // leading zeros of mag[16:0] (garbage for 0, which is not used)
    logic [RW-1:0] lzr;   // leading zeros of mag left-aligned, at most W - 19 (a one forced in)
  } conv_t;

  // Stage 1: the magnitude and both leading-zero counts.
  function automatic conv_t from_int_count(input logic signed [W-1:0] k);
    logic         s;
    logic [W-2:0] mag;
    logic [63:0]  ml;     // mag, zero-extended
    logic [63:0]  u;      // mag left-aligned in 64 bits
    s   = k[W-1];
    mag = s ? -k[W-2:0] : k[W-2:0];
    ml  = 64'(mag);
    u   = ml << (65 - W);
    return '{zero: (k == '0),
             kmin: s && (k[W-2:0] == '0),
             s:    s,
             mag:  mag,
             big:  (ml[63:17] != 47'd0),
             lzx:  f24_clz32({ml[16:0], 15'd0}),
             lzr:  RW'(f24_clz64(u | (64'd1 << (82 - W))))};
  endfunction

  // Stage 2: the shifts, the rounding and the result.
  function automatic f24_t from_int_pack(input conv_t c);
    logic [16:0]        ml;     // mag's low 17 bits (zero-extended for W < 18)
    // |k| < 2^17: exact.  Normalise the low 17 bits; no rounding.
    logic [15:0]        nxx;    // mag[16:0] << lzx below its leading one (at bit 16)
    logic [6:0]         ex;     // its biased exponent, 63 + 16 - lzx
    // |k| >= 2^17 (W > 18 only): at most W - 19 leading zeros, rounded to nearest even.
    ml   = 17'(c.mag);
    nxx  = 16'(ml << c.lzx);
    ex   = 7'd79 - {2'd0, c.lzx};
    // 0 gives +0.  The exponent never leaves [1, 126]: |k| <= 2^63, and 2^63 itself is exact.
    return c.zero  ? '0
         : c.kmin  ? {1'b1, 7'(63 + W - 1), 16'd0}
         : !c.big  ? {c.s, ex, nxx}
         :           round_big(c.s, c.mag, c.lzr);
  endfunction

  // Each stage is a function of its inputs, evaluated where its register is enabled (a simulator
  // evaluates it only in the clocks the unit advances; the hardware is the same).
  conv_t c_q;  // LAT = 2: stage 1
  f24_t  y_q;  // the last stage

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      if (LAT == 1) begin
        y_q <= from_int(k_i);
      end else begin
        c_q <= from_int_count(k_i);
        y_q <= from_int_pack(c_q);
      end
    end
  end

  assign y_o = y_q;

endmodule
