// f24_pkg: the 24-bit float format shared by every unit (1 sign, 7 exponent bias 63, 16 fraction).
// See README "Number format" and ../shared/FLOAT24.md. Zero exponent reads as a signed zero
// (flush-to-zero), exponent 127 is Inf (fraction 0) or NaN; every NaN produced is F24_NAN.
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
    f24_class_t c;
    c.zero = (x[22:16] == 7'd0);
    c.inf  = (x[22:16] == EXP_SPEC) && (x[15:0] == 16'd0);
    c.nan  = (x[22:16] == EXP_SPEC) && (x[15:0] != 16'd0);
    return c;
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // A signed zero / signed Inf of the given sign.
  function automatic f24_t f24_zero(input logic s);
    return {s, 23'd0};
  endfunction

  function automatic f24_t f24_inf(input logic s);
    return {s, EXP_SPEC, 16'd0};
  endfunction

  // Round a normalised 17-bit significand (hidden one at bit 16) with its guard and sticky bits,
  // ties to even, and pack it with a biased exponent that may be out of range (overflow to Inf,
  // flush to zero after rounding).  exp_b is signed and wide enough for every unit's range.
  function automatic f24_t f24_round_pack(input logic s, input logic signed [11:0] exp_b,
                                          input logic [16:0] sig, input logic guard,
                                          input logic sticky);
    logic        up;
    logic [17:0] sig_r;
    logic signed [11:0] e;
    up    = guard & (sticky | sig[0]);
    sig_r = {1'b0, sig} + {17'd0, up};
    e     = exp_b;
    if (sig_r[17]) begin
      e = e + 12'sd1;       // 1.111..1 rounded up to 10.000..0
      sig_r = sig_r >> 1;
    end
    if (e > 12'sd126) return f24_inf(s);
    if (e < 12'sd1) return f24_zero(s);
    return {s, e[6:0], sig_r[15:0]};
  endfunction

endpackage
