// f24_add: y = a + b, correctly rounded (RNE), latency 2 enabled clocks, one operation per clock.
// Subtract by flipping b's sign outside.
//
// Stage 1: swap so |a| >= |b|, align the smaller significand with a guard, a round and a
//          sticky bit (every bit shifted further out is ORed into the sticky bit), add or
//          subtract; the special result (NaN / Inf) from the larger operand's class.
// Stage 2: leading-zero count (f24_clz32), normalise, round (f24_round_pack), pack; select
//          specials and zeros.
//
// Why three extra bits are enough: if the exponent difference is 0 or 1 the aligned operand fits
// the window exactly (no sticky) and any cancellation is exact.  Otherwise the difference keeps at
// least 16 bits, the normalising left shift is at most 2 and the guard bit stays above the sticky
// bit.  Jamming the lost bits into the odd window LSB keeps the window sum strictly between the
// same two even window values as the exact sum, and every rounding boundary (halfway point or
// power of two) lies on an even window value, so the rounded result is the same.
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
    logic             s;        // sign of the larger operand
    logic             zs;       // sign of an exactly zero sum: -0 only for (-0) + (-0)
    logic [6:0]       e;        // biased exponent of the larger operand
    logic [SUM_W-1:0] sum;      // |a + b| in units of 2^(e-63-19), sticky jammed in
  } align_t;

  function automatic align_t add_align(input f24_t a, input f24_t b);
    f24_t       x, z;                  // x: the operand of larger magnitude, z: the other one
    logic       a_big;
    logic       x_zero, z_zero;        // exponent 0 (x zero implies z zero)
    logic       z_spec;                // exponent 127 (z special implies x special)
    logic [6:0] d;                     // exponent difference ex - ez, 0..126
    logic [4:0] d_sat;                 // saturated: 21 shifts every bit into the sticky bit
    logic [SIG_W-1:0] sig_x, sig_z;    // 0 for zero operands
    logic [2*SUM_W-1:0] z_wide;        // {z, 21 zeros} >> d_sat: the window above, lost bits below
    logic [SUM_W-1:0] x_al, z_al;
    logic       sticky;
    a_big  = (a[22:0] >= b[22:0]);
    x      = a_big ? a : b;
    z      = a_big ? b : a;
    x_zero = (x[22:16] == 7'd0);
    z_zero = (z[22:16] == 7'd0);
    z_spec = (z[22:16] == EXP_SPEC);
    d      = x[22:16] - z[22:16];
    d_sat  = (d > 7'd21) ? 5'd21 : d[4:0];
    sig_x  = x_zero ? '0 : {1'b1, x[15:0]};
    sig_z  = z_zero ? '0 : {1'b1, z[15:0]};
    z_wide = {1'b0, sig_z, {EXT_W{1'b0}}, {SUM_W{1'b0}}} >> d_sat;
    sticky = |z_wide[SUM_W-1:0];
    x_al   = {1'b0, sig_x, {EXT_W{1'b0}}};
    z_al   = z_wide[2*SUM_W-1:SUM_W] | {{(SUM_W-1){1'b0}}, sticky};
    // |x| >= |z|: a NaN or Inf z makes x one too, and a NaN z makes x a NaN.  So the result is
    // special when x is, NaN for a NaN x or for Inf - Inf, else the Inf x.
    return '{special: (x[22:16] == EXP_SPEC),
             spec_y:  (x[15:0] != 16'd0 || (z_spec && x[23] != z[23])) ? F24_NAN
                                                                      : {x[23], EXP_SPEC, 16'd0},
             s:       x[23],
             zs:      a[23] & b[23],
             e:       x[22:16],
             sum:     (x[23] ^ z[23]) ? (x_al - z_al) : (x_al + z_al)};
  endfunction

  // ---------------------------------------------------------------- stage 2: normalise, round
  function automatic f24_t add_round(input align_t r);
    logic [4:0]         lz;     // leading zeros of r.sum (garbage when it is 0, which is not used)
    logic [SUM_W-1:0]   norm;   // leading one at the top bit
    logic signed [11:0] e_n;
    lz   = f24_clz32({r.sum, {(32 - SUM_W){1'b0}}});
    norm = r.sum << lz;
    // Leading one at sum bit 19 (no carry, no cancellation) means exponent r.e.
    e_n  = $signed({5'd0, r.e}) + 12'sd1 - $signed({7'd0, lz});
    return r.special       ? r.spec_y
         : (r.sum == '0)   ? {r.zs, 23'd0}
         :                   f24_round_pack(r.s, e_n, norm[SUM_W-1 -: SIG_W], norm[EXT_W],
                                            |norm[EXT_W-1:0]);
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
