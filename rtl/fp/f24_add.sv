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

  // ---------------------------------------------------------------- stage 1: swap, align, add
  f24_t       x, z;                  // x: the operand of larger magnitude, z: the other one
  logic       a_big;
  logic       x_zero, z_zero;        // exponent 0 (x zero implies z zero)
  logic       x_spec, z_spec;        // exponent 127 (z special implies x special)
  logic [6:0] d;                     // exponent difference ex - ez, 0..126
  logic [4:0] d_sat;                 // saturated: 21 shifts every bit into the sticky bit
  logic [SIG_W-1:0] sig_x, sig_z;    // 0 for zero operands
  logic [2*SUM_W-1:0] z_wide;        // {z, 21 zeros} >> d_sat: the window above, lost bits below
  logic [SUM_W-1:0] x_al, z_al;
  logic       sticky;

  logic             special_d, special_q;  // NaN or Inf result
  f24_t             spec_y_d, spec_y_q;
  logic             s_d, s_q;              // sign of the larger operand
  logic             zs_d, zs_q;            // sign of an exactly zero sum: -0 only for (-0) + (-0)
  logic [6:0]       e_d, e_q;              // biased exponent of the larger operand
  logic [SUM_W-1:0] sum_d, sum_q;          // |a + b| in units of 2^(e-63-19), sticky jammed in

  always_comb begin
    a_big  = (a_i[22:0] >= b_i[22:0]);
    x      = a_big ? a_i : b_i;
    z      = a_big ? b_i : a_i;
    x_zero = (x[22:16] == 7'd0);
    z_zero = (z[22:16] == 7'd0);
    x_spec = (x[22:16] == EXP_SPEC);
    z_spec = (z[22:16] == EXP_SPEC);
    d      = x[22:16] - z[22:16];
    d_sat  = (d > 7'd21) ? 5'd21 : d[4:0];
    sig_x  = x_zero ? '0 : {1'b1, x[15:0]};
    sig_z  = z_zero ? '0 : {1'b1, z[15:0]};
    z_wide = {1'b0, sig_z, {EXT_W{1'b0}}, {SUM_W{1'b0}}} >> d_sat;
    sticky = |z_wide[SUM_W-1:0];
    x_al   = {1'b0, sig_x, {EXT_W{1'b0}}};
    z_al   = z_wide[2*SUM_W-1:SUM_W] | {{(SUM_W-1){1'b0}}, sticky};
    sum_d  = (x[23] ^ z[23]) ? (x_al - z_al) : (x_al + z_al);
    s_d    = x[23];
    zs_d   = a_i[23] & b_i[23];
    e_d    = x[22:16];

    // |x| >= |z|: a NaN or Inf z makes x one too, and a NaN z makes x a NaN.  So the result is
    // special when x is, NaN for a NaN x or for Inf - Inf, else the Inf x.
    special_d = x_spec;
    spec_y_d  = (x[15:0] != 16'd0 || (z_spec && x[23] != z[23])) ? F24_NAN
                                                                  : {x[23], EXP_SPEC, 16'd0};
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      special_q <= special_d;
      spec_y_q  <= spec_y_d;
      s_q       <= s_d;
      zs_q      <= zs_d;
      e_q       <= e_d;
      sum_q     <= sum_d;
    end
  end

  // ---------------------------------------------------------------- stage 2: normalise, round
  logic [4:0]         lz;     // leading zeros of sum_q (garbage when it is 0, which is not used)
  logic [SUM_W-1:0]   norm;   // leading one at the top bit
  logic signed [11:0] e_n;
  f24_t               y_rnd;  // the rounded nonzero sum
  f24_t               y_d, y_q;

  always_comb begin
    lz    = f24_clz32({sum_q, {(32 - SUM_W){1'b0}}});
    norm  = sum_q << lz;
    // Leading one at sum bit 19 (no carry, no cancellation) means exponent e_q.
    e_n   = $signed({5'd0, e_q}) + 12'sd1 - $signed({7'd0, lz});
    y_rnd = f24_round_pack(s_q, e_n, norm[SUM_W-1 -: SIG_W], norm[EXT_W], |norm[EXT_W-1:0]);
    y_d   = special_q       ? spec_y_q
          : (sum_q == '0)   ? {zs_q, 23'd0}
          :                   y_rnd;
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  assign y_o = y_q;

endmodule
