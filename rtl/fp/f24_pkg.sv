// SPDX-License-Identifier: Apache-2.0
// f24_pkg: the 24-bit float format shared by every unit (1 sign, 7 exponent bias 63, 16 fraction).
// See docs/number-format.md. Zero exponent reads as a signed zero
// (flush-to-zero), exponent 127 is Inf (fraction 0) or NaN; every NaN produced is F24_NAN.
// Also the helpers the units share: operand class, leading-zero count, round-and-pack.
package f24_pkg;

  // A package's constants serve every unit; no single unit uses all of them.
  /* verilator lint_off UNUSEDPARAM */

  localparam int unsigned F24_W    = 24;  // word width
  localparam int unsigned EXP_W    = 7;   // exponent field width
  localparam int unsigned FRAC_W   = 16;  // fraction field width
  localparam int unsigned SIG_W    = 17;  // significand width with the hidden one
  localparam int unsigned BIAS     = 63;  // exponent bias
  localparam logic [6:0]  EXP_SPEC = 7'h7f;  // Inf / NaN exponent

  typedef logic [F24_W-1:0] f24_t;

  localparam f24_t F24_NAN      = 24'h7f8000;  // the one NaN every unit produces
  localparam f24_t F24_POS_INF  = 24'h7f0000;
  localparam f24_t F24_ONE      = 24'h3f0000;
  localparam f24_t F24_MAX      = 24'h7effff;  // largest finite value

  // Latency of the divider the design instantiates (f24_div #(.LAT(F24_DIV_LAT)) in view_calc
  // and traverse_setup): the restoring division loop over F24_DIV_LAT - 1 stages for the clock
  // (README "What limits the clock"; the unit's default, LAT = 2, is the paper's).
  localparam int unsigned F24_DIV_LAT = 8;
  /* verilator lint_on UNUSEDPARAM */

  // Operand class, decoded once per operand.
  typedef struct packed {
    logic zero;  // exponent 0: +-0 (subnormal patterns read as zero)
    logic inf;
    logic nan;
  } f24_class_t;

  // The sign bit does not affect the class.
  /* verilator lint_off UNUSEDSIGNAL */
  function automatic f24_class_t f24_classify(input f24_t x);
    logic spec, frac_zero;
    spec      = (x[22:16] == EXP_SPEC);
    frac_zero = (x[15:0] == 16'd0);
    return '{zero: (x[22:16] == 7'd0), inf: spec && frac_zero, nan: spec && !frac_zero};
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // A signed zero / signed Inf of the given sign.
  function automatic f24_t f24_zero(input logic s);
    return {s, 23'd0};
  endfunction

  function automatic f24_t f24_inf(input logic s);
    return {s, EXP_SPEC, 16'd0};
  endfunction

  // Leading zeros of a 32-bit word, as a log-depth priority encoder: each step tests whether the
  // upper half of the remaining window is all zeros and keeps the half that holds the leading one.
  // A zero word gives 31: callers test for zero separately.  Bit 0 of v (w2[0]) never changes
  // the count (31 either way), hence the waiver.
  /* verilator lint_off UNUSEDSIGNAL */
  function automatic logic [4:0] f24_clz32(input logic [31:0] v);
    logic [4:0]  n;
    logic [15:0] w16;
    logic [7:0]  w8;
    logic [3:0]  w4;
    logic [1:0]  w2;
    n[4] = (v[31:16] == 16'd0);
    w16  = n[4] ? v[15:0] : v[31:16];
    n[3] = (w16[15:8] == 8'd0);
    w8   = n[3] ? w16[7:0] : w16[15:8];
    n[2] = (w8[7:4] == 4'd0);
    w4   = n[2] ? w8[3:0] : w8[7:4];
    n[1] = (w4[3:2] == 2'd0);
    w2   = n[1] ? w4[1:0] : w4[3:2];
    n[0] = !w2[1];
    return n;
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // Leading zeros of a 64-bit word (63 for zero): one more halving step in front of f24_clz32.
  function automatic logic [5:0] f24_clz64(input logic [63:0] v);
    logic hi_zero;
    hi_zero = (v[63:32] == 32'd0);
    return {hi_zero, f24_clz32(hi_zero ? v[31:0] : v[63:32])};
  endfunction

  // Round a normalised 17-bit significand (hidden one at bit 16) with its guard and sticky bits,
  // ties to even, and pack it with a biased exponent that may be out of range (overflow to Inf,
  // flush to zero after rounding).  exp_b is signed and wide enough for every unit's range.
  // The increment is added to {exponent, fraction}: a fraction 1.111..1 that rounds up carries
  // into the exponent, which is exactly 10.000..0 renormalised.  Written as one expression (no
  // branches) so that simulators evaluate it as plain data flow.
  /* verilator lint_off UNUSEDSIGNAL */  // sig[16], the hidden one, is implied by the packing
  function automatic f24_t f24_round_pack(input logic s, input logic signed [11:0] exp_b,
                                          input logic [16:0] sig, input logic guard,
                                          input logic sticky);
    logic        up;  // round up: above halfway, or halfway with an odd significand
    logic [27:0] r;   // {biased exponent, fraction} after rounding
    logic [11:0] er;  // rounded biased exponent; a negative one reads as a large unsigned number
    up = guard & (sticky | sig[0]);
    r  = {exp_b, sig[15:0]} + {27'd0, up};
    er = r[27:16];
    return (er != 12'd0 && er <= 12'd126) ? {s, r[22:0]}
         : (r[27] || er == 12'd0)         ? {s, 23'd0}             // below 2^-62: flush to zero
         :                                  {s, EXP_SPEC, 16'd0};  // above F24_MAX: Inf
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

endpackage
