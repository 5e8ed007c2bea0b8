// SPDX-License-Identifier: Apache-2.0
// f24_log2: y = log2(a), piecewise-linear approximation, latency LAT enabled clocks, one operation
// per clock.  |y - log2 a| <= 0.75 * 2^-16 + ulp(y)/2; log2(1) = +0 and log2(2^k) = k exactly.  The
// design, bound and table layout are documented in model/f24_approx.py (bit-exact model: log2).
// The result is the same, bit for bit, at every LAT.
// LAT = 2 (the default):
//   stage 1: unpack, classify, table read at a[15:9], step * a[8:0]
//   stage 2: S = E * 2^31 + base * 2^9 + product (signed fixed point), |S|, normalise, round, pack
// LAT = 3 (for clock speed): |S| is built without a negation after the sum and its leading-zero
// count is predicted from E and the fraction, so the stages are table, product + sum, shift +
// round.  With F = base * 2^9 + step * r (0 <= F < 2^31), |S| = E * 2^31 + F for E >= 0 and
// (-E - 1) * 2^31 + (2^31 - F) for E < 0 (f = 0: -E * 2^31), i.e. {I, G} with the integer part
// I < 64 and G = (base' * 2^9 +- step * r) mod 2^31, base' = base or (2^22 - base) mod 2^22.
//   stage 1: unpack, classify, I; the step table read at a[15:9] (logic: a combinational read,
//            negated for E < 0); the base' table read at {E < 0, a[15:9]} (a synchronous ROM:
//            block RAM, its address register is the stage register); the shift count: exact
//            from I when I != 0, else from the leading zeros of f (E = 0) or 2^16 - f (E = -1),
//            which is the count of |S| or one less
//   stage 2: G = base' * 2^9 + (+-step) * r (signed product in the multiplier)
//   stage 3: {I, G} << count, a 1-bit correction (the leading one at the top or one below),
//            round (RNE), pack
// Specials: +-0 -> -Inf, negative nonzero -> NaN, +Inf -> +Inf, NaN -> NaN.
module f24_log2
  import f24_pkg::*;
  import f24_approx_pkg::*;
#(
  // Latency in enabled clocks, 2 or 3: 2 = table and product in stage 1, sum, normalisation and
  // rounding in stage 2; 3 = table, product + sum, normalisation + rounding in three stages for
  // a faster clock (same results).
  parameter int unsigned LAT = 2
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,
  output f24_t y_o
);

  localparam int unsigned PROD_W = LOG2_INC_W + POS_BITS;  // step * position
  localparam int unsigned MAG_W  = 6 + ACC_FRAC;           // |S| < 64 * 2^31
  localparam int unsigned S_W    = MAG_W + 1;              // signed S
  localparam int unsigned LZ_W   = $clog2(MAG_W + 1);

  if (LAT < 2 || LAT > 3) begin : g_check_lat
    $error("f24_log2: LAT must be 2 or 3");
  end

  // LAT = 3: the base table for both signs of E, index {E < 0, i}: base (E >= 0) and
  // (2^22 - base) mod 2^22 (E < 0), so that 2^31 - F = (2^22 - base) * 2^9 - step * r.
  typedef logic [LOG2_BASE_W-1:0] base_tab_t [2**(SEG_BITS+1)];
  function automatic base_tab_t signed_base();
    base_tab_t t;
    for (int i = 0; i < 2**SEG_BITS; i++) begin
      t[i]               = LOG2_BASE[i];
      t[i + 2**SEG_BITS] = -LOG2_BASE[i];
    end
    return t;
  endfunction
  localparam base_tab_t BASE_PM = signed_base();

  // ---- stage 1: classification (every LAT) ------------------------------------------------------
  f24_class_t             ca;
  logic                   spec_d, spec_q;  // special operand: the result is spec_y
  f24_t                   spec_y_d, spec_y_q;
  logic signed [6:0]      ex_d;            // unbiased exponent E = e - 63, -62..63

  always_comb begin
    ca     = f24_classify(a_i);
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
    end
  end

  f24_t y_q;

  if (LAT == 2) begin : g_lat2
    // ---- stage 1: table read, product --------------------------------------------------------
    logic signed [6:0]      ex_q;
    logic [LOG2_BASE_W-1:0] base_d, base_q;
    logic [PROD_W-1:0]      prod_d, prod_q;

    always_comb begin
      base_d = LOG2_BASE[a_i[15:POS_BITS]];
      prod_d = PROD_W'(LOG2_INC[a_i[15:POS_BITS]]) * PROD_W'(a_i[POS_BITS-1:0]);
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        ex_q   <= ex_d;
        base_q <= base_d;
        prod_q <= prod_d;
      end
    end

    // ---- stage 2: sum, |S|, normalise, round, pack --------------------------------------------
    logic signed [S_W-1:0] s_acc;  // log2 a * 2^31 (approximately)
    logic [MAG_W-1:0]      mag, norm;
    logic [LZ_W-1:0]       lz;
    logic signed [11:0]    e;
    logic [16:0]           sig;
    logic                  guard, sticky;
    f24_t                  y_d;

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
  end else begin : g_lat3
    // ---- stage 1: table reads, integer part, shift count --------------------------------------
    logic                      neg;             // E < 0: the result is negative
    logic [FRAC_W-1:0]         frac, fneg;      // f and (2^16 - f) mod 2^16
    logic [5:0]                int_d, int_q;    // I, the integer part of |S|
    logic [31:0]               lead;            // a word with |S|'s leading one, or one above
    logic [LZ_W-1:0]           lz_d, lz_q;      // shift count: |S|'s leading zeros or one less
    logic [LOG2_BASE_W-1:0]    base_q;          // base' (block RAM output)
    logic signed [LOG2_INC_W:0] inc_d, inc_q;   // +-step
    logic [POS_BITS-1:0]       pos_q;           // r = a[8:0]
    logic                      neg_q;
    logic                      one_d, one_q;    // a = 1.0: S = 0, the result is +0

    always_comb begin
      neg   = ex_d[6];
      frac  = a_i[FRAC_W-1:0];
      fneg  = -frac;
      inc_d = neg ? -$signed({1'b0, LOG2_INC[frac[15:POS_BITS]]})
                  : $signed({1'b0, LOG2_INC[frac[15:POS_BITS]]});
      // I = E (E >= 0), -E - 1 = ~E (E < 0, f != 0: G < 2^31), -E (E < 0, f = 0: G = 0).
      if (!neg) int_d = 6'(ex_d);
      else if (frac == '0) int_d = 6'(-ex_d);
      else int_d = 6'(~ex_d);
      one_d = (ex_d == 7'sd0) && (frac == '0);
      // |S| = {I, G} is MAG_W = 37 bits; lead holds its bits 36..5.  I != 0: the leading one is
      // I's.  E = 0: G = F, f * 2^15 <= F < f * 2^16, so f at bits 31..16 has the leading one
      // of |S| or the one above it.  E = -1: G = 2^31 - F, 0.72 g * 2^15 < G < g * 2^15 with
      // g = 2^16 - f, so g at bits 30..15 likewise.
      if (int_d != '0) lead = {int_d, 26'd0};
      else if (ex_d == 7'sd0) lead = {5'd0, frac, 11'd0};
      else lead = {6'd0, fneg, 10'd0};
      lz_d = LZ_W'(f24_clz32(lead));
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        base_q <= BASE_PM[{neg, frac[15:POS_BITS]}];
        inc_q  <= inc_d;
        pos_q  <= frac[POS_BITS-1:0];
        neg_q  <= neg;
        int_q  <= int_d;
        lz_q   <= lz_d;
        one_q  <= one_d;
      end
    end

    // ---- stage 2: product, sum ---------------------------------------------------------------
    logic signed [PROD_W:0]  prod;          // +-step * r
    logic [ACC_FRAC-1:0]     g_d, g_q;      // G, the fraction of |S|
    logic [5:0]              int2_q;
    logic [LZ_W-1:0]         lz2_q;
    logic                    neg2_q, spec2_q;
    f24_t                    spec_y2_q;

    always_comb begin
      prod = inc_q * $signed({1'b0, pos_q});
      g_d  = ACC_FRAC'({base_q, {POS_BITS{1'b0}}} + ACC_FRAC'(prod));
    end

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        g_q       <= g_d;
        int2_q    <= int_q;
        lz2_q     <= lz_q;
        neg2_q    <= neg_q;
        spec2_q   <= spec_q || one_q;
        spec_y2_q <= spec_q ? spec_y_q : f24_zero(1'b0);  // log2(1) = +0 (-1.0 is NaN)
      end
    end

    // ---- stage 3: normalise, round, pack -----------------------------------------------------
    logic [MAG_W-1:0]   norm;   // |S| << lz: the leading one at bit MAG_W-1 or MAG_W-2
    logic signed [11:0] e;
    logic [16:0]        sig;
    logic               guard, sticky;
    f24_t               y_d;

    always_comb begin
      norm = {int2_q, g_q} << lz2_q;
      // Leading one at bit MAG_W-1-lz, worth 2^(MAG_W-1-lz-31).
      e = 12'sd63 + 12'(MAG_W - 1 - ACC_FRAC) - $signed({{(12 - LZ_W){1'b0}}, lz2_q});
      if (norm[MAG_W-1]) begin
        sig    = norm[MAG_W-1 -: 17];
        guard  = norm[MAG_W-18];
        sticky = |norm[MAG_W-19:0];
      end else begin  // the count was one short
        e      = e - 12'sd1;
        sig    = norm[MAG_W-2 -: 17];
        guard  = norm[MAG_W-19];
        sticky = |norm[MAG_W-20:0];
      end
      y_d = spec2_q ? spec_y2_q : f24_round_pack(neg2_q, e, sig, guard, sticky);
    end

    always_ff @(posedge clk_i) begin
      if (en_i) y_q <= y_d;
    end
  end

  assign y_o = y_q;

endmodule
