// f24_sqrt: y = sqrt(a), correctly rounded (RNE), latency 2 enabled clocks, one operation per clock.
// sqrt(+-0) = +-0, sqrt(+Inf) = +Inf, sqrt of a negative nonzero number or of a NaN is F24_NAN.
// Stage 1: operand class, halved exponent and the 18-bit root (17 bits + guard) of the
// even-exponent-adjusted significand by a restoring digit loop (combinational), with a sticky
// bit from the final remainder.
// Stage 2: round and pack (f24_round_pack).  The root of a normal number is always in range.
module f24_sqrt
  import f24_pkg::*;
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the pipeline registers advance only while en_i is 1
  input  f24_t a_i,
  output f24_t y_o     // sqrt(a)
);

  localparam int unsigned R_W = SIG_W + 1;  // root bits: 17 + guard
  localparam int unsigned X_W = 2 * R_W;    // radicand bits

  // ---- stage 1: classify, exponent, integer square root -----------------------------------------
  f24_class_t ca;
  logic [X_W-1:0] x;          // radicand: significand (x2 for an odd exponent) * 2^18, < 2^36
  logic [R_W-1:0] root;       // floor(sqrt(x)), in [2^17, 2^18)
  logic [R_W+2:0] rem;        // partial remainder, <= 2 * root before the next digit pair
  logic [R_W+2:0] trial;      // 4 * root + 1

  logic               spec_d, spec_q;  // result is a special (y_spec)
  f24_t               y_spec_d, y_spec_q;
  logic signed [11:0] e_d, e_q;        // biased exponent of the root, which is in [1, 2)
  logic [R_W-1:0]     root_d, root_q;
  logic               rem_nz_d, rem_nz_q;

  always_comb begin
    ca = f24_classify(a_i);
    // Unbiased exponent ea - 63 is even exactly when ea is odd.  For an even ea the significand
    // is doubled and the exponent reduced by one, so the halved exponent is exact.
    if (a_i[16]) x = {1'b0, 1'b1, a_i[15:0], 18'd0};   // m       in [1, 2)
    else         x = {1'b1, a_i[15:0], 1'b0, 18'd0};   // 2 * m   in [2, 4)
    // floor((ea - 63) / 2) + 63 = floor((ea + 63) / 2); ea + 63 <= 189 fits in 8 bits.
    e_d = $signed({4'd0, 8'({1'b0, a_i[22:16]} + 8'd63) >> 1});

    // Restoring square root: one root bit per pair of radicand bits, most significant first.
    rem  = '0;
    root = '0;
    for (int i = R_W - 1; i >= 0; i--) begin
      rem   = {rem[R_W:0], x[2*i+1], x[2*i]};
      trial = {1'b0, root, 2'b01};
      if (rem >= trial) begin
        rem  = rem - trial;
        root = {root[R_W-2:0], 1'b1};
      end else begin
        root = {root[R_W-2:0], 1'b0};
      end
    end
    root_d   = root;
    rem_nz_d = (rem != '0);

    spec_d = 1'b1;
    if (ca.nan || (a_i[23] && !ca.zero)) y_spec_d = F24_NAN;  // NaN, negative nonzero, -Inf
    else if (ca.zero) y_spec_d = f24_zero(a_i[23]);
    else if (ca.inf) y_spec_d = F24_POS_INF;
    else begin
      spec_d   = 1'b0;
      y_spec_d = F24_NAN;  // unused
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      spec_q   <= spec_d;
      y_spec_q <= y_spec_d;
      e_q      <= e_d;
      root_q   <= root_d;
      rem_nz_q <= rem_nz_d;
    end
  end

  // ---- stage 2: round, pack --------------------------------------------------------------------
  f24_t y_d, y_q;

  always_comb begin
    y_d = spec_q ? y_spec_q
                 : f24_round_pack(1'b0, e_q, root_q[R_W-1:1], root_q[0], rem_nz_q);
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  assign y_o = y_q;

endmodule
