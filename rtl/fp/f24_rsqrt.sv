// f24_rsqrt: y = 1/sqrt(a), piecewise-linear approximation, latency 2 enabled clocks, one operation
// per clock.  Within one f24 step of the correctly rounded result, |error| < 1 ulp (faithful); the
// design, bound and table layout are documented in model/f24_approx.py (bit-exact model: rsqrt).
//   stage 1: unpack, classify, table read at {E odd, a[15:9]}, step * a[8:0]
//   stage 2: base * 2^9 - product - bias, normalise (1 bit), round (RNE), pack
// Specials: +0 -> +Inf, -0 -> -Inf, negative nonzero -> NaN, +Inf -> +0, NaN -> NaN.
module f24_rsqrt
  import f24_pkg::*;
  import f24_approx_pkg::*;
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,
  output f24_t y_o
);

  localparam int unsigned IDX_W  = SEG_BITS + 1;                     // {E odd, segment}
  localparam int unsigned PROD_W = RSQRT_DEC_W + POS_BITS;           // step * position
  localparam int unsigned ACC_W  = ACC_FRAC + 1;                     // T * 2^31, T < 2

  // ---- stage 1 -------------------------------------------------------------------------------
  f24_class_t              ca;
  logic [IDX_W-1:0]        idx;
  logic                    spec_d, spec_q;    // special operand: the result is spec_y
  f24_t                    spec_y_d, spec_y_q;
  logic [6:0]              exp_d, exp_q;      // biased exponent of 2^(-floor(E/2)-1)
  logic [RSQRT_BASE_W-1:0] base_d, base_q;
  logic [PROD_W-1:0]       prod_d, prod_q;

  always_comb begin
    ca = f24_classify(a_i);
    // E = e - 63 is odd when e is even: that selects table 1 (2/sqrt(2m)).
    idx    = {~a_i[16], a_i[15:POS_BITS]};
    base_d = RSQRT_BASE[idx];
    prod_d = PROD_W'(RSQRT_DEC[idx]) * PROD_W'(a_i[POS_BITS-1:0]);
    // (188 - e) >> 1 = 62 - floor((e - 63) / 2), in 31..93 for normal e.
    exp_d  = 7'((8'd188 - {1'b0, a_i[22:16]}) >> 1);
    spec_d = 1'b1;
    if (ca.nan) spec_y_d = F24_NAN;
    else if (ca.zero) spec_y_d = f24_inf(a_i[23]);
    else if (a_i[23]) spec_y_d = F24_NAN;
    else if (ca.inf) spec_y_d = f24_zero(1'b0);
    else begin
      spec_d   = 1'b0;
      spec_y_d = '0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      spec_q   <= spec_d;
      spec_y_q <= spec_y_d;
      exp_q    <= exp_d;
      base_q   <= base_d;
      prod_q   <= prod_d;
    end
  end

  // ---- stage 2 -------------------------------------------------------------------------------
  logic [ACC_W-1:0]   acc;  // T * 2^31 in (2^30, 2^32); the 33-bit difference is taken mod 2^32
  logic signed [11:0] e;
  logic [16:0]        sig;
  logic               guard, sticky;
  f24_t               y_d, y_q;

  always_comb begin
    acc = ACC_W'({base_q, {POS_BITS{1'b0}}} - (ACC_W + 1)'(prod_q) - RSQRT_BIAS);
    e   = $signed({5'd0, exp_q});
    if (acc[ACC_W-1]) begin  // T in [1, 2)
      sig    = acc[ACC_W-1 -: 17];
      guard  = acc[ACC_W-18];
      sticky = |acc[ACC_W-19:0];
    end else begin           // T in (1/2, 1): only near m = 2 of table 1
      e      = e - 12'sd1;
      sig    = acc[ACC_W-2 -: 17];
      guard  = acc[ACC_W-19];
      sticky = |acc[ACC_W-20:0];
    end
    if (spec_q) y_d = spec_y_q;
    else y_d = f24_round_pack(1'b0, e, sig, guard, sticky);
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  assign y_o = y_q;

endmodule
