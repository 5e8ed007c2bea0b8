// SPDX-License-Identifier: Apache-2.0
// f24_add: y = a + b, correctly rounded (RNE), latency LAT enabled clocks, one operation per clock.
// Subtract by flipping b's sign outside.  The result word is the same at every LAT.
//
// LAT = 2 (the default, the paper's):
// Stage 1: swap so |a| >= |b|, align the smaller significand with a guard, a round and a
//          sticky bit (every bit shifted further out is ORed into the sticky bit; the sticky bit
//          comes from a trailing-zero count compared with the shift, not from a shifter: the
//          count of either operand, each encoded as tz + 3 with no adder, compared with the
//          difference taken in that order, picked by the swap), add or subtract in one carry
//          chain; flag an exactly zero sum (two zeros, or equal magnitudes cancelling) and the
//          special result (NaN / Inf) from the larger operand's class.
// Stage 2: the position q of the leading one of sum[20:2] (one leading-zero count), and two
//          normalisations side by side, selected by the top three bits of the sum:
//          - "round": the leading one at sum bit 20, 19 or 18 (a carry, no change, one bit of
//            cancellation): a three-way select of the fraction, round to nearest even;
//          - "exact": the leading one at bit 17 or below, which only a subtraction of operands
//            at most one binade apart gives, and then every bit of the difference fits 17 bits:
//            a left shift by the leading zeros (15 - q), no rounding.
//          One carry chain serves both: {e - 17, fraction} + {q, rounding increment}, whose
//          exponent field is e + 1, e, e - 1 on the "round" side (q = 18, 17, 16, plus the
//          rounding carry) and e - 2 - (15 - q) on the "exact" side (its fraction field,
//          sum[17:2] plus 0, carries nothing).  Then the range check and the choice between
//          specials, zero, Inf, "round" and "exact".  The long shift and the carry chain are
//          never in series.
// LAT = 3 (for clock speed): the same logic cut at two other places, so that no stage holds
// both a long shifter and a carry chain that depends on it:
//   stage 1 "align": swap, exponent difference, alignment shift and sticky bit (no add);
//   stage 2 "add":   the one carry chain of the add, then the "round" side's three-way select
//                    (fraction, guard, sticky, round-up bit) and the leading-zero count (q);
//   stage 3 "pack":  the carry chain of the exponent and rounding and its range check beside
//                    the "exact" side's shift, then the last choice.
// LAT = 4: stage 1 of LAT = 3 cut once more, after the swap and before the alignment shift:
//   stage 1 "swap":  the magnitude compare, the swap, the exponent difference and the sticky bit;
//   stage 2 "shift": the alignment shift;
//   stages 3 and 4:  "add" and "pack" as at LAT = 3.
//
// Why three extra bits are enough: if the exponent difference is 0 or 1 the aligned operand fits
// the window exactly (no sticky) and any cancellation is exact.  Otherwise the difference keeps at
// least 16 bits, the normalising left shift is at most 2 and the guard bit stays above the sticky
// bit.  Jamming the lost bits into the odd window LSB keeps the window sum strictly between the
// same two even window values as the exact sum, and every rounding boundary (halfway point or
// power of two) lies on an even window value, so the rounded result is the same.
//
// Why the "exact" side needs no rounding: with an exponent difference d >= 2 and a subtraction,
// |x| >= 2^19 and |z| < 2^18 in window units, so the difference is above 2^18 (leading one at bit
// 18 or higher).  A leading one at bit 17 or below therefore means d <= 1, where the window holds
// the operands exactly and the difference has its lowest one at bit 2 or higher: at most 16 bits
// below the leading one, none lost.
module f24_add
  import f24_pkg::*;
#(
  // Latency in enabled clocks, 2 .. 4: 2 = the paper's (two stages); 3 and 4 = three and four
  // stages for a faster clock.  The same result at every LAT.
  parameter int unsigned LAT = 2
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the pipeline registers advance only while en_i is 1
  input  f24_t a_i,
  input  f24_t b_i,
  output f24_t y_o
);

  if (LAT < 2 || LAT > 4) begin : g_check_lat
    $error("f24_add: LAT must be in 2..4");
  end

  localparam int unsigned EXT_W = 3;                  // guard, round, sticky
  localparam int unsigned SUM_W = 1 + SIG_W + EXT_W;  // carry + significand + extra = 21

  // ---------------------------------------------------------------- swap and align
  // The operands swapped, before the alignment shift (the register of stage 1 at LAT = 4).
  typedef struct packed {
    logic             special;  // NaN or Inf result
    logic             nan;      // the special result is the NaN (else the Inf of sign s)
    logic             zero;     // the sum is exactly zero
    logic             s;        // result sign (see align_t)
    logic [7:0]       e17;      // biased exponent of the larger operand minus 17 (signed)
    logic             sub;      // effective subtraction
    logic [FRAC_W-1:0] xf;      // fraction of the larger operand
    logic [SIG_W-1:0] sig_z;    // significand of the smaller operand, 0 for a zero operand
    logic [6:0]       d;        // exponent difference, 0..126
    logic             sticky;   // a one of the smaller operand is shifted below the window
  } swap_t;

  // The operands swapped and aligned, before the add (the register of stage 1 at LAT >= 3).
  typedef struct packed {
    logic             special;  // NaN or Inf result
    logic             nan;      // the special result is the NaN (else the Inf of sign s)
    logic             zero;     // the sum is exactly zero
    logic             s;        // result sign (see align_t)
    logic [7:0]       e17;      // biased exponent of the larger operand minus 17 (signed)
    logic             sub;      // effective subtraction
    logic [FRAC_W-1:0] xf;      // fraction of the larger operand
    logic [SUM_W-1:0] z_al;     // the smaller operand aligned to the window, sticky in bit 0
  } prep_t;

  // The sum (the register of stage 1 at LAT = 2).
  typedef struct packed {
    logic             special;  // NaN or Inf result
    logic             nan;      // the special result is the NaN (else the Inf of sign s)
    logic             zero;     // the sum is exactly zero
    logic             s;        // result sign: the larger operand's; for a zero sum, -0 only
                                // for (-0) + (-0)
    logic [7:0]       e17;      // biased exponent of the larger operand minus 17 (signed)
    logic [SUM_W-1:0] sum;      // |a + b| in units of 2^(e-63-19), sticky jammed in
  } align_t;

  // Both normalisations up to their last step (the register of stage 2 at LAT >= 3).
  typedef struct packed {
    logic             special;  // NaN or Inf result
    logic             nan;      // the special result is the NaN (else the Inf of sign s)
    logic             zero;     // the sum is exactly zero
    logic             s;        // result sign
    logic             rnd_side; // the leading one at sum bit 20, 19 or 18: the "round" side
    logic [7:0]       e17;      // biased exponent of the larger operand minus 17 (signed)
    logic [FRAC_W-1:0] frac;    // "round" side: the fraction below the leading one
    logic             up;       // "round" side: round up (RNE); 0 on the "exact" side
    logic [4:0]       q;        // the leading one of sum[20:2] at bit q (sum bit q + 2)
    logic [15:0]      sx;       // "exact" side: sum[17:2]
  } sel_t;

  // Trailing zeros of a significand {1, f} plus 3 (the window's extra bits): 3..19, encoded
  // directly (no adder after the count).
  function automatic logic [4:0] sig_tz3(input logic [FRAC_W-1:0] f);
    logic [4:0] n;
    n = 5'(FRAC_W + EXT_W);
    for (int i = FRAC_W - 1; i >= 0; i--) begin
      if (f[i]) n = 5'(i + EXT_W);
    end
    return n;
  endfunction

  function automatic swap_t add_swap(input f24_t a, input f24_t b);
    f24_t       x, z;                  // x: the operand of larger magnitude, z: the other one
    logic       a_big;
    logic       x_zero, z_zero;        // exponent 0 (x zero implies z zero)
    logic       z_spec;                // exponent 127 (z special implies x special)
    logic       sub;                   // effective subtraction
    logic [6:0] d_ab, d_ba;            // exponent differences
    logic       st_ab, st_ba;          // the sticky bit for either order
    a_big  = (a[22:0] >= b[22:0]);
    x      = a_big ? a : b;
    z      = a_big ? b : a;
    // Both differences from the operands, the one that is not negative picked by a_big, so that
    // the shift does not wait for a subtraction after the swap.
    d_ab   = a[22:16] - b[22:16];
    d_ba   = b[22:16] - a[22:16];
    // The sticky bit for b shifted by d_ab and for a shifted by d_ba, picked by a_big like d:
    // significand bit i of z sits at window bit i + 3 - d and falls out when i + 3 < d, so some
    // one falls out when the lowest one (bit tz) does.
    st_ab  = (b[22:16] != 7'd0) && ({2'b0, sig_tz3(b[15:0])} < d_ab);
    st_ba  = (a[22:16] != 7'd0) && ({2'b0, sig_tz3(a[15:0])} < d_ba);
    x_zero = (x[22:16] == 7'd0);
    z_zero = (z[22:16] == 7'd0);
    z_spec = (z[22:16] == EXP_SPEC);
    sub    = x[23] ^ z[23];
    // |x| >= |z|: a NaN or Inf z makes x one too, and a NaN z makes x a NaN.  So the result is
    // special when x is, NaN for a NaN x or for Inf - Inf, else the Inf x.  The sum is zero for
    // two zeros (x zero implies z zero) or for equal magnitudes subtracted; |x| > |z| >= 0
    // otherwise gives a nonzero sum.  A zero x means a zero sum, flagged apart.
    return '{special: (x[22:16] == EXP_SPEC),
             nan:     (x[15:0] != 16'd0 || (z_spec && sub)),
             zero:    x_zero || (sub && a[22:0] == b[22:0]),
             s:       (x_zero || (sub && a[22:0] == b[22:0])) ? (a[23] & b[23]) : x[23],
             e17:     {1'b0, x[22:16]} - 8'd17,
             sub:     sub,
             xf:      x[15:0],
             sig_z:   z_zero ? '0 : {1'b1, z[15:0]},
             d:       a_big ? d_ab : d_ba,
             sticky:  a_big ? st_ab : st_ba};
  endfunction

  function automatic prep_t add_shift(input swap_t w);
    logic [SUM_W-1:0] z_sh;
    // Window: bit 20 carry, 19..3 the significand, 2..0 guard, round, sticky.  A shift of 20 or
    // more (d[4:0] >= 20, or d >= 32) empties the window.
    z_sh = ({1'b0, w.sig_z, {EXT_W{1'b0}}} >> w.d[4:0]) & {SUM_W{w.d[6:5] == 2'd0}};
    return '{special: w.special, nan: w.nan, zero: w.zero, s: w.s, e17: w.e17, sub: w.sub,
             xf:      w.xf,
             z_al:    z_sh | {{(SUM_W-1){1'b0}}, w.sticky}};
  endfunction

  function automatic prep_t add_prep(input f24_t a, input f24_t b);
    return add_shift(add_swap(a, b));
  endfunction

  // ---------------------------------------------------------------- add
  function automatic align_t add_sum(input prep_t p);
    logic [SUM_W-1:0] x_al;
    x_al = {1'b0, 1'b1, p.xf, {EXT_W{1'b0}}};
    return '{special: p.special, nan: p.nan, zero: p.zero, s: p.s, e17: p.e17,
             sum:     x_al + (p.z_al ^ {SUM_W{p.sub}}) + SUM_W'(p.sub)};
  endfunction

  // ---------------------------------------------------------------- normalise: select
  function automatic sel_t add_select(input align_t r);
    // "round" side: leading one at bit 20, 19 or 18.
    logic [FRAC_W-1:0]  frac;    // the fraction below the leading one
    logic               guard, sticky;
    logic [4:0]         lz32;    // leading zeros of {13 zeros, sum[20:2]}
    // The leading one of sum[20:2] (a nonzero sum has one there unless it is flagged zero) at
    // bit q = 31 - lz32 = ~lz32: 18, 17, 16 on the "round" side, 15 .. 0 on the "exact" side.
    lz32 = f24_clz32({13'd0, r.sum[20:2]});
    if (r.sum[20]) begin
      frac = r.sum[19:4];  guard = r.sum[3];  sticky = |r.sum[2:0];
    end else if (r.sum[19]) begin
      frac = r.sum[18:3];  guard = r.sum[2];  sticky = |r.sum[1:0];
    end else begin
      frac = r.sum[17:2];  guard = r.sum[1];  sticky = r.sum[0];
    end
    // On the "exact" side the sum has no ones below bit 2, so guard = 0 and up = 0.
    return '{special:  r.special, nan: r.nan, zero: r.zero, s: r.s,
             rnd_side: (r.sum[20:18] != 3'd0),
             e17:      r.e17,
             frac:     frac,
             up:       guard & (sticky | frac[0]),
             q:        ~lz32,
             sx:       r.sum[17:2]};
  endfunction

  // ---------------------------------------------------------------- normalise: round, pack
  function automatic f24_t add_finish(input sel_t t);
    logic [23:0]        rnd;     // {exponent, fraction} after the exponent change and rounding
    logic [7:0]         er;      // rnd's exponent: "round" side 0..128, "exact" side -16..124
    // nrm[15] is the leading one: unused by design.
    /* verilator lint_off UNUSEDSIGNAL */
    logic [15:0]        nrm;     // sum[17:2] << lz: leading one at bit 15
    /* verilator lint_on UNUSEDSIGNAL */
    logic               flush, ovf;
    // One carry chain: {e - 17, fraction} + {q, rounding increment}.  On the "exact" side the
    // fraction field holds sum[17:2] plus 0 (no carry into the exponent), so er = e - 2 - lz
    // with lz = 15 - q.
    rnd   = {t.e17, t.frac} + {3'd0, t.q, 15'd0, t.up};
    er    = rnd[23:16];
    nrm   = t.sx << ~t.q[3:0];
    // A result exponent of 0 or below is under 2^-62 (flush to zero), 127 or more above
    // F24_MAX (the "round" side only: the "exact" side's er is below e, and negative at bit 7).
    flush = (er == 8'd0) || (!t.rnd_side && er[7]);
    ovf   = t.rnd_side && (er[7] || er[6:0] == EXP_SPEC);
    // Bit 0 of the "exact" side's fraction is below the lowest bit the difference can have.
    return t.special          ? (t.nan ? F24_NAN : {t.s, EXP_SPEC, 16'd0})
         : (t.zero || flush)  ? {t.s, 23'd0}
         : ovf                ? {t.s, EXP_SPEC, 16'd0}
         :                      {t.s, er[6:0], t.rnd_side ? rnd[15:0] : {nrm[14:0], 1'b0}};
  endfunction

  // ---------------------------------------------------------------- the stages
  // Each stage is a function of its inputs, evaluated where its register is enabled (so a
  // simulator evaluates a stage only in the clocks it advances; the hardware is the same).
  swap_t  w_q;   // LAT = 4: stage 1
  align_t s1_q;  // LAT = 2: stage 1
  prep_t  p_q;   // LAT = 3: stage 1; LAT = 4: stage 2
  sel_t   t_q;   // LAT = 3: stage 2; LAT = 4: stage 3
  f24_t   y_q;   // the last stage

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      if (LAT == 2) begin
        s1_q <= add_sum(add_prep(a_i, b_i));
        y_q  <= add_finish(add_select(s1_q));
      end else if (LAT == 3) begin
        p_q  <= add_prep(a_i, b_i);
        t_q  <= add_select(add_sum(p_q));
        y_q  <= add_finish(t_q);
      end else begin
        w_q  <= add_swap(a_i, b_i);
        p_q  <= add_shift(w_q);
        t_q  <= add_select(add_sum(p_q));
        y_q  <= add_finish(t_q);
      end
    end
  end

  assign y_o = y_q;

endmodule
