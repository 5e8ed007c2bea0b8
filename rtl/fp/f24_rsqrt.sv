// SPDX-License-Identifier: Apache-2.0
// f24_rsqrt: y = 1/sqrt(a), piecewise-linear approximation, latency LAT enabled clocks, one
// operation per clock.  Within one f24 step of the correctly rounded result, |error| < 1 ulp
// (faithful); the design, bound and table layout are documented in model/f24_approx.py (bit-exact
// model: rsqrt).  The result is the same, bit for bit, at every LAT.
// LAT = 2 (the default):
//   stage 1: unpack, classify, table read at {E odd, a[15:9]}, step * a[8:0]
//   stage 2: base * 2^9 - product - bias, normalise (1 bit), round (RNE), pack
// LAT = 3 (for clock speed: the table word, the product and the rounding each get a stage):
//   stage 1: unpack, classify; the step table read at {E odd, a[15:9]} (logic: a combinational
//            read, negated so that the product enters the sum with its sign); the base table
//            read (a synchronous ROM: block RAM, its address register is the stage register)
//   stage 2: (base - bias / 2^9) * 2^9 + (-step) * a[8:0] (signed product in the multiplier)
//   stage 3: normalise (1 bit), round (RNE), pack
// Specials: +0 -> +Inf, -0 -> -Inf, negative nonzero -> NaN, +Inf -> +0, NaN -> NaN.
module f24_rsqrt
  import f24_pkg::*;
  import f24_approx_pkg::*;
#(
  // Latency in enabled clocks, 2 or 3: 2 = table and product in stage 1, sum and rounding in
  // stage 2; 3 = table, product + sum, rounding in three stages for a faster clock (same results).
  parameter int unsigned LAT = 2
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,
  output f24_t y_o
);

  localparam int unsigned IDX_W  = SEG_BITS + 1;                     // {E odd, segment}
  localparam int unsigned PROD_W = RSQRT_DEC_W + POS_BITS;           // step * position
  localparam int unsigned ACC_W  = ACC_FRAC + 1;                     // T * 2^31, T < 2

  if (LAT < 2 || LAT > 3) begin : g_check_lat
    $error("f24_rsqrt: LAT must be 2 or 3");
  end

  // LAT = 3: RSQRT_BIAS is a multiple of 2^POS_BITS, so base * 2^9 - bias =
  // (base - bias / 2^9) * 2^9: the bias is folded into a copy of the base table (BASE_B) and
  // stage 2 is one addition.
  typedef logic [RSQRT_BASE_W-1:0] base_tab_t [2**IDX_W];
  function automatic base_tab_t biased_base();
    base_tab_t t;
    for (int i = 0; i < 2**IDX_W; i++) begin
      t[i] = RSQRT_BASE[i] - RSQRT_BASE_W'(RSQRT_BIAS >> POS_BITS);
    end
    return t;
  endfunction
  localparam base_tab_t BASE_B = biased_base();

  if (RSQRT_BIAS % (2**POS_BITS) != 0) begin : g_check_bias
    $error("f24_rsqrt: RSQRT_BIAS must be a multiple of 2^POS_BITS");
  end

  // ---- stage 1: classification (every LAT) ------------------------------------------------------
  f24_class_t              ca;
  logic [IDX_W-1:0]        idx;
  logic                    spec_d, spec_q;    // special operand: the result is spec_y
  f24_t                    spec_y_d, spec_y_q;
  logic [6:0]              exp_d, exp_q;      // biased exponent of 2^(-floor(E/2)-1)

  always_comb begin
    ca = f24_classify(a_i);
    // E = e - 63 is odd when e is even: that selects table 1 (2/sqrt(2m)).
    idx    = {~a_i[16], a_i[15:POS_BITS]};
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
    end
  end

  // ---- normalise (1 bit), round, pack: the last stage at every LAT ------------------------------
  // acc = T * 2^31 in (2^30, 2^32).
  function automatic f24_t rsqrt_round(input logic spec, input f24_t spec_y, input logic [6:0] ex,
                                       input logic [ACC_W-1:0] acc);
    logic signed [11:0] e;
    logic [16:0]        sig;
    logic               guard, sticky;
    e = $signed({5'd0, ex});
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
    return spec ? spec_y : f24_round_pack(1'b0, e, sig, guard, sticky);
  endfunction

  f24_t y_q;

  if (LAT == 2) begin : g_lat2
    // ---- stage 1: table read, product --------------------------------------------------------
    logic [RSQRT_BASE_W-1:0] base_d, base_q;
    logic [PROD_W-1:0]       prod_d, prod_q;

    always_comb begin
      base_d = RSQRT_BASE[idx];
      prod_d = PROD_W'(RSQRT_DEC[idx]) * PROD_W'(a_i[POS_BITS-1:0]);
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        base_q <= base_d;
        prod_q <= prod_d;
      end
    end

    // ---- stage 2: sum, normalise, round, pack -----------------------------------------------
    logic [ACC_W-1:0] acc;  // the 33-bit difference is taken mod 2^32

    always_comb begin
      acc = ACC_W'({base_q, {POS_BITS{1'b0}}} - (ACC_W + 1)'(prod_q) - RSQRT_BIAS);
    end

    always_ff @(posedge clk_i) begin
      if (en_i) y_q <= rsqrt_round(spec_q, spec_y_q, exp_q, acc);
    end
  end else begin : g_lat3
    // ---- stage 1: table reads ----------------------------------------------------------------
    logic [RSQRT_BASE_W-1:0]       base_q;         // biased base (block RAM output)
    logic signed [RSQRT_DEC_W:0]   ndec_d, ndec_q; // -step
    logic [POS_BITS-1:0]           pos_q;          // a[8:0]

    always_comb begin
      ndec_d = -$signed({1'b0, RSQRT_DEC[idx]});
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        base_q <= BASE_B[idx];
        ndec_q <= ndec_d;
        pos_q  <= a_i[POS_BITS-1:0];
      end
    end

    // ---- stage 2: product, sum ---------------------------------------------------------------
    logic signed [PROD_W:0] prod;          // -step * position, in (-2^24, 0]
    logic [ACC_W-1:0]       acc_d, acc_q;  // T * 2^31, the sum taken mod 2^32
    logic                   spec2_q;
    f24_t                   spec_y2_q;
    logic [6:0]             exp2_q;

    always_comb begin
      prod  = ndec_q * $signed({1'b0, pos_q});
      acc_d = ACC_W'({base_q, {POS_BITS{1'b0}}} + (ACC_W + 1)'(prod));
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        acc_q     <= acc_d;
        spec2_q   <= spec_q;
        spec_y2_q <= spec_y_q;
        exp2_q    <= exp_q;
      end
    end

    // ---- stage 3: normalise, round, pack ------------------------------------------------------
    always_ff @(posedge clk_i) begin
      if (en_i) y_q <= rsqrt_round(spec2_q, spec_y2_q, exp2_q, acc_q);
    end
  end

  assign y_o = y_q;

endmodule
