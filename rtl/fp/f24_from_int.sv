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

  // The conversion as a function of k, evaluated where the output register is enabled (a
  // simulator evaluates it only in the clocks the unit advances; the hardware is the same).
  function automatic f24_t from_int(input logic signed [W-1:0] k);
    logic               s;
    logic [W-1:0]       mag;    // |k|; -2^(W-1) gives 2^(W-1), which fits unsigned
    logic [63:0]        ml;     // mag left-aligned in 64 bits
    logic [5:0]         lz;     // leading zeros of ml (garbage for mag = 0, which is not used)
    logic [63:0]        nx;     // ml << lz: leading one at bit 63
    logic signed [11:0] e;      // biased exponent of the leading one
    s   = k[W-1];
    mag = s ? W'(-k) : W'(k);
    ml  = 64'(mag) << (64 - W);
    lz  = (W <= 32) ? {1'b0, f24_clz32(ml[63:32])} : f24_clz64(ml);
    nx  = ml << lz;
    e   = 12'sd63 + 12'(W - 1) - $signed({6'd0, lz});
    // 17 significand bits, guard bit and sticky (narrow W: the padding makes them exact zeros);
    // 0 gives +0.
    return (mag == '0) ? '0 : f24_round_pack(s, e, nx[63:47], nx[46], |nx[45:0]);
  endfunction

  f24_t y_q;

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= from_int(k_i);
  end

  assign y_o = y_q;

endmodule
