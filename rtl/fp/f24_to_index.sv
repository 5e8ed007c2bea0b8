// f24_to_index: f24 -> signed W-bit texel index, idx = floor(a) saturated to [-2^(W-1), 2^(W-1)-1].
// sat_o is 1 when the value was clamped or a is NaN (NaN gives idx 0); +-Inf saturate; zeros and
// subnormal patterns give 0.  Floor rounds toward minus infinity: -0.5 -> -1, -1.0 -> -1.
// Latency 1 enabled clock, one conversion per clock.  Golden model: model.f24_conv.to_index.
module f24_to_index
  import f24_pkg::*;
#(
  parameter int unsigned W = 20  // index width in bits, two's complement (2 .. 64)
) (
  input  logic                clk_i,  // clock
  input  logic                en_i,   // clock enable: the output registers advance only while 1
  input  f24_t                a_i,    // operand
  output logic signed [W-1:0] idx_o,  // floor(a_i), saturated
  output logic                sat_o   // idx_o was clamped, or a_i is NaN
);

  if (W < 2 || W > 64) begin : g_check_w
    $error("f24_to_index: W must be in 2..64");
  end

  localparam int unsigned FW = W + 15;  // |a| * 2^16 for |a| < 2^(W-1): 17-bit sig << (W-2)

  localparam logic signed [W-1:0] IDX_MAX = {1'b0, {(W-1){1'b1}}};  //  2^(W-1) - 1
  localparam logic signed [W-1:0] IDX_MIN = {1'b1, {(W-1){1'b0}}};  // -2^(W-1)

  f24_class_t         c;
  logic               s;
  logic signed [8:0]  e;        // unbiased exponent, -62 .. 63 for normal operands
  logic [FW-1:0]      fix;      // |a| in fixed point with 16 fraction bits (valid for 0 <= e <= W-2)
  logic [W-2:0]       ipart;    // floor(|a|)
  logic               frac_nz;  // |a| is not an integer
  logic [W-1:0]       mag;      // ceil(|a|) for negative a, floor(|a|) otherwise
  logic signed [W-1:0] idx_d, idx_q;
  logic               sat_d, sat_q;

  always_comb begin
    c       = f24_classify(a_i);
    s       = a_i[23];
    e       = $signed({2'b00, a_i[22:16]}) - 9'sd63;
    fix     = '0;
    ipart   = '0;
    frac_nz = 1'b1;  // |a| < 1 (e < 0): integer part 0, fraction nonzero
    if (e >= 9'sd0) begin
      // The shift only matters for e <= W-2; larger exponents saturate below.
      fix     = FW'({1'b1, a_i[15:0]}) << e[5:0];
      ipart   = fix[FW-1:16];
      frac_nz = |fix[15:0];
    end
    mag = s ? {1'b0, ipart} + {{(W-1){1'b0}}, frac_nz} : {1'b0, ipart};
    // |a| < 2^(W-1) here, so mag <= 2^(W-1) and its negation fits in W bits.
    idx_d = s ? -$signed(mag) : $signed(mag);
    sat_d = 1'b0;
    if (c.nan) begin
      idx_d = '0;
      sat_d = 1'b1;
    end else if (c.zero) begin
      idx_d = '0;
    end else if (c.inf || e > $signed(9'(W - 1))) begin
      idx_d = s ? IDX_MIN : IDX_MAX;  // |a| >= 2^W
      sat_d = 1'b1;
    end else if (e == $signed(9'(W - 1))) begin
      // 2^(W-1) <= |a| < 2^W: only exactly -2^(W-1) is in range.
      idx_d = s ? IDX_MIN : IDX_MAX;
      sat_d = !(s && a_i[15:0] == 16'd0);
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      idx_q <= idx_d;
      sat_q <= sat_d;
    end
  end

  assign idx_o = idx_q;
  assign sat_o = sat_q;

endmodule
