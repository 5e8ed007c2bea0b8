// f24_div: y = a / b, correctly rounded (RNE), latency 2 enabled clocks, one operation per clock.
// Stage 1: operand classes and the special result, sign, exponent and the 19-bit significand
// quotient by a restoring division loop (combinational), with a sticky bit from the final
// remainder.
// Stage 2: normalise the quotient to 17 bits + guard + sticky, round, pack (f24_round_pack).
module f24_div
  import f24_pkg::*;
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the pipeline registers advance only while en_i is 1
  input  f24_t a_i,    // dividend
  input  f24_t b_i,    // divisor
  output f24_t y_o     // a / b
);

  localparam int unsigned Q_W = SIG_W + 2;  // quotient bits: 17 + guard + one for ma < mb

  // ---- stage 1: classify, exponent, significand quotient ---------------------------------------
  logic        a_zero, b_zero;  // exponent 0: +-0 (subnormal patterns read as zero)
  logic        a_spec, b_spec;  // exponent 127: Inf or NaN
  logic        any_nan;
  logic [16:0] ma, mb;          // significands with the hidden one, value in [2^16, 2^17)
  logic [17:0] rem;             // partial remainder, always < 2 * mb
  logic [Q_W-1:0] quo;          // floor(ma * 2^18 / mb), in [2^17, 2^19)

  logic                 spec_d, spec_q;  // result is a special (y_spec)
  f24_t                 y_spec_d, y_spec_q;
  logic                 s_d, s_q;
  logic signed [11:0]   e_d, e_q;        // biased exponent of a quotient in [1, 2)
  logic [Q_W-1:0]       quo_d, quo_q;
  logic                 rem_nz_d, rem_nz_q;

  always_comb begin
    a_zero  = (a_i[22:16] == 7'd0);
    b_zero  = (b_i[22:16] == 7'd0);
    a_spec  = (a_i[22:16] == EXP_SPEC);
    b_spec  = (b_i[22:16] == EXP_SPEC);
    any_nan = (a_spec && a_i[15:0] != 16'd0) || (b_spec && b_i[15:0] != 16'd0);
    ma      = {1'b1, a_i[15:0]};
    mb      = {1'b1, b_i[15:0]};

    // Restoring division: one quotient bit per step, most significant first.  ma < 2 * mb, so
    // the first bit is ma >= mb and every later remainder stays below 2 * mb (18 bits).
    rem = {1'b0, ma};
    quo = '0;
    for (int i = Q_W - 1; i >= 0; i--) begin
      if (rem >= {1'b0, mb}) begin
        quo[i] = 1'b1;
        rem    = rem - {1'b0, mb};
      end
      if (i != 0) rem = {rem[16:0], 1'b0};
    end

    s_d      = a_i[23] ^ b_i[23];
    e_d      = $signed({5'd0, a_i[22:16]}) - $signed({5'd0, b_i[22:16]}) + 12'sd63;
    quo_d    = quo;
    rem_nz_d = (rem != 18'd0);

    // NaN for a NaN operand, 0/0 or Inf/Inf; Inf for Inf/finite or finite/0; zero for 0/finite
    // or finite/Inf.
    spec_d   = a_spec || b_spec || a_zero || b_zero;
    y_spec_d = (any_nan || (a_zero && b_zero) || (a_spec && b_spec)) ? F24_NAN
             : (a_spec || b_zero)                                    ? {s_d, EXP_SPEC, 16'd0}
             :                                                         {s_d, 23'd0};
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      spec_q   <= spec_d;
      y_spec_q <= y_spec_d;
      s_q      <= s_d;
      e_q      <= e_d;
      quo_q    <= quo_d;
      rem_nz_q <= rem_nz_d;
    end
  end

  // ---- stage 2: normalise, round, pack ---------------------------------------------------------
  logic [Q_W-1:0]     norm;   // quo_q with its leading one at the top bit
  logic signed [11:0] e;
  f24_t               y_rnd;  // the rounded quotient of two finite nonzero operands
  f24_t               y_d, y_q;

  always_comb begin
    // ma >= mb: quotient in [1, 2), leading one at the top bit.  ma < mb: quotient in (1/2, 1),
    // shifted up by one (its last bit, and the remainder, go to the sticky bit).
    norm  = quo_q << !quo_q[Q_W-1];
    e     = e_q - $signed({11'd0, !quo_q[Q_W-1]});
    y_rnd = f24_round_pack(s_q, e, norm[Q_W-1:2], norm[1], norm[0] | rem_nz_q);
    y_d   = spec_q ? y_spec_q : y_rnd;
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  assign y_o = y_q;

endmodule
