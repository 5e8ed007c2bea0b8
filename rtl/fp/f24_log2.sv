// f24_log2: y = log2(a), piecewise-linear approximation, latency 2 enabled clocks, one operation
// per clock.  |y - log2 a| <= 0.75 * 2^-16 + ulp(y)/2; log2(1) = +0 and log2(2^k) = k exactly.  The
// design, bound and table layout are documented in model/f24_approx.py (bit-exact model: log2).
//   stage 1: unpack, classify, table read at a[15:9], step * a[8:0]
//   stage 2: S = E * 2^31 + base * 2^9 + product (signed fixed point), |S|, normalise, round, pack
// Specials: +-0 -> -Inf, negative nonzero -> NaN, +Inf -> +Inf, NaN -> NaN.
module f24_log2
  import f24_pkg::*;
  import f24_approx_pkg::*;
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,
  output f24_t y_o
);

  localparam int unsigned PROD_W = LOG2_INC_W + POS_BITS;  // step * position
  localparam int unsigned MAG_W  = 6 + ACC_FRAC;           // |S| < 64 * 2^31
  localparam int unsigned S_W    = MAG_W + 1;              // signed S
  localparam int unsigned LZ_W   = $clog2(MAG_W + 1);

  // ---- stage 1 -------------------------------------------------------------------------------
  f24_class_t             ca;
  logic                   spec_d, spec_q;  // special operand: the result is spec_y
  f24_t                   spec_y_d, spec_y_q;
  logic signed [6:0]      ex_d, ex_q;      // unbiased exponent E = e - 63, -62..63
  logic [LOG2_BASE_W-1:0] base_d, base_q;
  logic [PROD_W-1:0]      prod_d, prod_q;

  always_comb begin
    ca     = f24_classify(a_i);
    base_d = LOG2_BASE[a_i[15:POS_BITS]];
    prod_d = PROD_W'(LOG2_INC[a_i[15:POS_BITS]]) * PROD_W'(a_i[POS_BITS-1:0]);
    ex_d   = $signed(a_i[22:16] - 7'd63);  // wraps only for e = 0, 127 (specials)
    spec_d = 1'b1;
    if (ca.nan) spec_y_d = F24_NAN;
    else if (ca.zero) spec_y_d = f24_inf(1'b1);
    else if (a_i[23]) spec_y_d = F24_NAN;
    else if (ca.inf) spec_y_d = f24_inf(1'b0);
    else begin
      spec_d   = 1'b0;
      spec_y_d = '0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      spec_q   <= spec_d;
      spec_y_q <= spec_y_d;
      ex_q     <= ex_d;
      base_q   <= base_d;
      prod_q   <= prod_d;
    end
  end

  // ---- stage 2 -------------------------------------------------------------------------------
  logic signed [S_W-1:0] s_acc;  // log2 a * 2^31 (approximately)
  logic [MAG_W-1:0]      mag, norm;
  logic [LZ_W-1:0]       lz;
  logic signed [11:0]    e;
  logic [16:0]           sig;
  logic                  guard, sticky;
  f24_t                  y_d, y_q;

  always_comb begin
    s_acc = $signed({ex_q, {ACC_FRAC{1'b0}}})
          + $signed(S_W'({base_q, {POS_BITS{1'b0}}}))
          + $signed(S_W'(prod_q));
    // |S| < 2^37, so the magnitude fits MAG_W bits (the sign bit of -S is 0).
    mag = MAG_W'(s_acc[S_W-1] ? -s_acc : s_acc);
    lz  = '0;
    for (int i = 0; i < MAG_W; i++) begin
      if (mag[i]) lz = LZ_W'(MAG_W - 1 - i);  // the highest set bit wins
    end
    norm   = mag << lz;
    sig    = norm[MAG_W-1 -: 17];
    guard  = norm[MAG_W-18];
    sticky = |norm[MAG_W-19:0];
    // Leading one at bit MAG_W-1-lz, worth 2^(MAG_W-1-lz-31).
    e = 12'sd63 + 12'(MAG_W - 1 - ACC_FRAC) - $signed({{(12 - LZ_W){1'b0}}, lz});
    if (spec_q) y_d = spec_y_q;
    else if (mag == '0) y_d = f24_zero(1'b0);  // log2(1) = +0
    else y_d = f24_round_pack(s_acc[S_W-1], e, sig, guard, sticky);
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  assign y_o = y_q;

endmodule
