// SPDX-License-Identifier: Apache-2.0
// f24_from_unorm: W-bit unorm code k -> the f24 of k / (2^W - 1), correctly rounded (RNE).
// The binary expansion of k / (2^W - 1) is 0.kkkk... (k's W bits repeated forever), so the
// conversion is a leading-zero count, a shift of the repeated pattern, a guard bit and
// sticky = (k != 0): the bits past the guard are never all zero for k != 0 (and k / (2^W - 1) is
// never exactly halfway between two f24 values).  k = 2^W - 1 reads 0.111... and rounds up to
// exactly 1.0; k = 0 gives +0.  Latency LAT enabled clocks (1, the default, or 2), one conversion
// per clock; the result word is the same at both.  LAT = 2 adds one plain enabled delay register
// (f24_delay) after the unit's register: the conversion's one stage is far shorter than the
// float adder's and multiplier's, so a second register inside it would buy no clock speed.
// Golden model: model.f24_conv.from_unorm.
module f24_from_unorm
  import f24_pkg::*;
#(
  parameter int unsigned W   = 8,  // unorm width, 8 or 16
  parameter int unsigned LAT = 1   // latency in enabled clocks, 1 (the default) or 2
) (
  input  logic         clk_i,  // clock
  input  logic         en_i,   // clock enable: the registers advance only while en_i is 1
  input  logic [W-1:0] k_i,    // unorm code
  output f24_t         y_o     // k_i / (2^W - 1)
);

  if (W != 8 && W != 16) begin : g_check_w
    $error("f24_from_unorm: W must be 8 or 16");
  end

  if (LAT < 1 || LAT > 2) begin : g_check_lat
    $error("f24_from_unorm: LAT must be 1 or 2");
  end

  localparam int unsigned REP   = (W + 17 + W - 1) / W;   // copies: lz + 1 + 17 + guard <= W + 17
  localparam int unsigned REP_W = REP * W;

  // The conversion as a function of k, evaluated where the output register is enabled (a
  // simulator evaluates it only in the clocks the unit advances; the hardware is the same).
  function automatic f24_t from_unorm(input logic [W-1:0] k);
    logic [4:0]         lz;     // leading zeros of k (garbage for k = 0, which is not used)
    logic [REP_W-1:0]   rep;    // k repeated, then shifted so the leading one is the top bit
    logic signed [11:0] e;      // biased exponent: k / (2^W - 1) in [2^-(lz+1), 2^-lz)
    lz  = f24_clz32({k, {(32 - W){1'b0}}});
    rep = {REP{k}} << lz;
    e   = 12'sd62 - $signed({7'd0, lz});
    return (k == '0) ? '0 : f24_round_pack(1'b0, e, rep[REP_W-1 -: 17], rep[REP_W-18], 1'b1);
  endfunction

  f24_t y_q;

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= from_unorm(k_i);
  end

  if (LAT > 1) begin : g_delay
    f24_delay #(.W(24), .N(LAT - 1)) u_delay (
      .clk_i, .en_i, .d_i(y_q), .q_o(y_o)
    );
  end else begin : g_out
    assign y_o = y_q;
  end

endmodule
