// SPDX-License-Identifier: Apache-2.0
// f24_sqrt: y = sqrt(a), correctly rounded (RNE), latency 2 enabled clocks, one operation per clock.
// sqrt(+-0) = +-0, sqrt(+Inf) = +Inf, sqrt of a negative nonzero number or of a NaN is F24_NAN.
// Stage 1: operand class, halved exponent and the 18-bit root (17 bits + guard) of the
// even-exponent-adjusted significand by a restoring digit loop (combinational), with a sticky
// bit from the final remainder.
// Stage 2: round and pack (f24_round_pack).  The root of a normal number is always in range.
module f24_sqrt
  import f24_pkg::*;
#(
  parameter int unsigned LAT = 2   // latency in enabled clocks, 2 (the default) or 3
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the pipeline registers advance only while en_i is 1
  input  f24_t a_i,
  output f24_t y_o     // sqrt(a)
);

  if (LAT < 2 || LAT > 3) begin : g_check_lat
    $error("f24_sqrt: LAT must be 2 or 3");
  end

  localparam int unsigned R_W = SIG_W + 1;  // root bits: 17 + guard
  localparam int unsigned X_W = 2 * R_W;    // radicand bits

  // ---- stage 1: classify, exponent, integer square root -----------------------------------------
  logic           a_zero;     // exponent 0: +-0 (subnormal patterns read as zero)
  logic           a_spec;     // exponent 127: Inf or NaN
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
    a_zero = (a_i[22:16] == 7'd0);
    a_spec = (a_i[22:16] == EXP_SPEC);
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

    // NaN for a NaN, a negative nonzero number or -Inf; +-0 for +-0; +Inf for +Inf.
    spec_d   = a_zero || a_spec || a_i[23];
    y_spec_d = a_zero                        ? {a_i[23], 23'd0}
             : (a_i[23] || a_i[15:0] != '0) ? F24_NAN
             :                                F24_POS_INF;
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
  f24_t y_rnd;  // the rounded root of a positive finite number
  f24_t y_d, y_q;

  always_comb begin
    y_rnd = f24_round_pack(1'b0, e_q, root_q[R_W-1:1], root_q[0], rem_nz_q);
    y_d   = spec_q ? y_spec_q : y_rnd;
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  // LAT = 3: one plain enabled delay register after the unit's two stages (the same word).
  if (LAT > 2) begin : g_delay
    f24_delay #(.W(24), .N(LAT - 2)) u_delay (
      .clk_i, .en_i, .d_i(y_q), .q_o(y_o)
    );
  end else begin : g_out
    assign y_o = y_q;
  end

endmodule
