// f24_add: y = a + b, correctly rounded (RNE), latency 2 enabled clocks, one operation per clock.
// Subtract by flipping b's sign outside.
//
// Stage 1: swap so |a| >= |b|, align the smaller significand with a guard, a round and a
//          sticky bit (every bit shifted further out is ORed into the sticky bit; the sticky bit
//          comes from a trailing-zero count compared with the shift, not from a shifter), add or
//          subtract in one carry chain; flag an exactly zero sum (two zeros, or equal magnitudes
//          cancelling) and the special result (NaN / Inf) from the larger operand's class.
// Stage 2: two normalisations side by side, selected by the top three bits of the sum:
//          - "round": the leading one at sum bit 20, 19 or 18 (a carry, no change, one bit of
//            cancellation): a three-way shift, round to nearest even, pack;
//          - "exact": the leading one at bit 17 or below, which only a subtraction of operands
//            at most one binade apart gives, and then every bit of the difference fits 17 bits:
//            leading-zero count and shift, no rounding.
//          The long shift and the rounding carry chain are never in series.
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
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the pipeline registers advance only while en_i is 1
  input  f24_t a_i,
  input  f24_t b_i,
  output f24_t y_o
);

  localparam int unsigned EXT_W = 3;                  // guard, round, sticky
  localparam int unsigned SUM_W = 1 + SIG_W + EXT_W;  // carry + significand + extra = 21

  // Each stage is a function of its inputs, evaluated where its register is enabled (so a
  // simulator evaluates a stage only in the clocks it advances; the hardware is the same).

  // ---------------------------------------------------------------- stage 1: swap, align, add
  typedef struct packed {
    logic             special;  // NaN or Inf result
    f24_t             spec_y;
    logic             zero;     // the sum is exactly zero
    logic             s;        // result sign: the larger operand's; for a zero sum, -0 only
                                // for (-0) + (-0)
    logic [6:0]       e;        // biased exponent of the larger operand
    logic [SUM_W-1:0] sum;      // |a + b| in units of 2^(e-63-19), sticky jammed in
  } align_t;

  // Trailing zeros of a significand {1, f}: 0..16.
  function automatic logic [4:0] sig_tz(input logic [FRAC_W-1:0] f);
    logic [4:0] n;
    n = 5'd16;
    for (int i = FRAC_W - 1; i >= 0; i--) begin
      if (f[i]) n = 5'(i);
    end
    return n;
  endfunction

  function automatic align_t add_align(input f24_t a, input f24_t b);
    f24_t       x, z;                  // x: the operand of larger magnitude, z: the other one
    logic       a_big;
    logic       x_zero, z_zero;        // exponent 0 (x zero implies z zero)
    logic       z_spec;                // exponent 127 (z special implies x special)
    logic       sub;                   // effective subtraction
    logic [6:0] d_ab, d_ba, d;         // exponent differences; d = ex - ez, 0..126
    logic       st_ab, st_ba;          // the sticky bit for either order
    logic [SIG_W-1:0] sig_z;           // 0 for a zero operand
    logic [SUM_W-1:0] x_al, z_sh, z_al;
    logic       sticky;                // a one of z is shifted below the window
    a_big  = (a[22:0] >= b[22:0]);
    x      = a_big ? a : b;
    z      = a_big ? b : a;
    // Both differences from the operands, the one that is not negative picked by a_big, so that
    // the shift does not wait for a subtraction after the swap.
    d_ab   = a[22:16] - b[22:16];
    d_ba   = b[22:16] - a[22:16];
    d      = a_big ? d_ab : d_ba;
    // The sticky bit for b shifted by d_ab and for a shifted by d_ba, picked by a_big like d:
    // significand bit i of z sits at window bit i + 3 - d and falls out when i + 3 < d, so some
    // one falls out when the lowest one (bit tz) does.
    st_ab  = (b[22:16] != 7'd0) && ({2'b0, sig_tz(b[15:0])} + 7'd3 < d_ab);
    st_ba  = (a[22:16] != 7'd0) && ({2'b0, sig_tz(a[15:0])} + 7'd3 < d_ba);
    x_zero = (x[22:16] == 7'd0);
    z_zero = (z[22:16] == 7'd0);
    z_spec = (z[22:16] == EXP_SPEC);
    sub    = x[23] ^ z[23];
    sig_z  = z_zero ? '0 : {1'b1, z[15:0]};
    // Window: bit 20 carry, 19..3 the significand, 2..0 guard, round, sticky.  A shift of 20 or
    // more (d[4:0] >= 20, or d >= 32) empties the window.
    z_sh   = ({1'b0, sig_z, {EXT_W{1'b0}}} >> d[4:0]) & {SUM_W{d[6:5] == 2'd0}};
    sticky = a_big ? st_ab : st_ba;
    x_al   = {1'b0, 1'b1, x[15:0], {EXT_W{1'b0}}};  // a zero x means a zero sum, flagged apart
    z_al   = z_sh | {{(SUM_W-1){1'b0}}, sticky};
    // |x| >= |z|: a NaN or Inf z makes x one too, and a NaN z makes x a NaN.  So the result is
    // special when x is, NaN for a NaN x or for Inf - Inf, else the Inf x.  The sum is zero for
    // two zeros (x zero implies z zero) or for equal magnitudes subtracted; |x| > |z| >= 0
    // otherwise gives a nonzero sum.
    return '{special: (x[22:16] == EXP_SPEC),
             spec_y:  (x[15:0] != 16'd0 || (z_spec && sub)) ? F24_NAN
                                                             : {x[23], EXP_SPEC, 16'd0},
             zero:    x_zero || (sub && a[22:0] == b[22:0]),
             s:       (x_zero || (sub && a[22:0] == b[22:0])) ? (a[23] & b[23]) : x[23],
             e:       x[22:16],
             sum:     x_al + (z_al ^ {SUM_W{sub}}) + SUM_W'(sub)};
  endfunction

  // ---------------------------------------------------------------- stage 2: normalise, round
  function automatic f24_t add_round(input align_t r);
    // "round" side: leading one at bit 20, 19 or 18, exponent e + 1, e, e - 1.
    logic [FRAC_W-1:0]  frac;    // the fraction below the leading one
    logic               guard, sticky, up;
    logic [7:0]         e_r;     // biased exponent before rounding, 0..127
    logic [23:0]        rnd;     // {exponent, fraction} after rounding; exponent 0..128
    f24_t               y_rnd;
    // "exact" side: leading one at bit 17 .. 2, exponent e - 2 - lz.
    // lz32[4] is 0 and nrm[15] is the leading one here: both unused by design.
    /* verilator lint_off UNUSEDSIGNAL */
    logic [4:0]         lz32;    // leading zeros of {sum[17:2], 16 zeros}: below 16 here
    logic [15:0]        nrm;     // sum[17:2] << lz: leading one at bit 15
    /* verilator lint_on UNUSEDSIGNAL */
    logic [3:0]         lz;      // leading zeros of sum[17:2]
    logic signed [8:0]  e_x;
    f24_t               y_exact;
    if (r.sum[20]) begin
      frac = r.sum[19:4];  guard = r.sum[3];  sticky = |r.sum[2:0];  e_r = {1'b0, r.e} + 8'd1;
    end else if (r.sum[19]) begin
      frac = r.sum[18:3];  guard = r.sum[2];  sticky = |r.sum[1:0];  e_r = {1'b0, r.e};
    end else begin
      frac = r.sum[17:2];  guard = r.sum[1];  sticky = r.sum[0];     e_r = {1'b0, r.e} - 8'd1;
    end
    up      = guard & (sticky | frac[0]);
    rnd     = {e_r, frac} + 24'(up);
    // A rounded exponent of 0 is below 2^-62 (flush to zero), 127 or more above F24_MAX.
    y_rnd   = (rnd[23:16] == 8'd0) ? {r.s, 23'd0}
            : (rnd[23] || rnd[22:16] == EXP_SPEC) ? {r.s, EXP_SPEC, 16'd0}
            : {r.s, rnd[22:0]};
    lz32    = f24_clz32({r.sum[17:2], 16'd0});
    lz      = lz32[3:0];
    nrm     = r.sum[17:2] << lz;
    e_x     = $signed({2'b0, r.e}) - 9'sd2 - $signed({5'd0, lz});
    // Bit 0 of the fraction is below the lowest bit the difference can have.
    y_exact = (e_x <= 9'sd0) ? {r.s, 23'd0} : {r.s, e_x[6:0], nrm[14:0], 1'b0};
    return r.special         ? r.spec_y
         : r.zero            ? {r.s, 23'd0}
         : (r.sum[20:18] != 3'd0) ? y_rnd
         :                     y_exact;
  endfunction

  align_t s1_q;
  f24_t   y_q;

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s1_q <= add_align(a_i, b_i);
      y_q  <= add_round(s1_q);
    end
  end

  assign y_o = y_q;

endmodule
