// f24_from_int: signed W-bit integer -> f24.  Exact when |k| has at most 17 significant bits,
// otherwise rounded to nearest, ties to even; 0 gives +0.  Latency 1 enabled clock, one conversion
// per clock.  Golden model: model.f24_conv.from_int.
module f24_from_int
  import f24_pkg::*;
#(
  parameter int unsigned W = 20  // integer width in bits, two's complement (2 .. 64)
) (
  input  logic                clk_i,  // clock
  input  logic                en_i,   // clock enable: the output register advances only while 1
  input  logic signed [W-1:0] k_i,    // integer to convert
  output f24_t                y_o     // k_i as f24
);

  if (W < 2 || W > 64) begin : g_check_w
    $error("f24_from_int: W must be in 2..64");
  end

  localparam int unsigned LZ_W = $clog2(W + 1);  // leading-zero count 0 .. W
  localparam int unsigned NX_W = W + 18;         // normalised magnitude padded with 18 zeros

  logic              s;
  logic [W-1:0]      mag;   // |k|; -2^(W-1) gives 2^(W-1), which fits unsigned
  logic [LZ_W-1:0]   lz;    // leading zeros of mag (W for mag = 0)
  logic [NX_W-1:0]   nx;    // mag << lz, then 18 zero bits: leading one at bit NX_W-1
  logic signed [11:0] e;    // biased exponent of the leading one
  f24_t              y_d, y_q;

  always_comb begin
    s   = k_i[W-1];
    mag = s ? W'(-k_i) : W'(k_i);
    lz  = LZ_W'(W);
    for (int unsigned i = 0; i < W; i++) begin
      if (mag[i]) lz = LZ_W'(W - 1 - i);  // the highest set bit is seen last
    end
    nx  = {mag, 18'd0} << lz;
    e   = 12'sd63 + 12'(W - 1) - 12'(lz);
    // 17 significand bits, guard bit and sticky (narrow W: the padding makes them exact zeros).
    if (mag == '0) y_d = f24_zero(1'b0);
    else y_d = f24_round_pack(s, e, nx[NX_W-1 -: 17], nx[W], |nx[W-1:0]);
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  assign y_o = y_q;

endmodule
