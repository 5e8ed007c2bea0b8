// SPDX-License-Identifier: Apache-2.0
// f24_to_index: f24 -> signed W-bit texel index, idx = floor(a) saturated to [-2^(W-1), 2^(W-1)-1].
// sat_o is 1 when the value was clamped or a is NaN (NaN gives idx 0); +-Inf saturate; zeros and
// subnormal patterns give 0.  Floor rounds toward minus infinity: -0.5 -> -1, -1.0 -> -1.
// Latency LAT enabled clocks (1, the default, or 2), one conversion per clock; the result is the
// same at both.  LAT = 2 adds one plain enabled delay register (f24_delay) after the unit's
// registers: its one stage is shorter than the float adder's and multiplier's, so a second
// register inside it would buy no clock speed.  Golden model: model.f24_conv.to_index.
module f24_to_index
  import f24_pkg::*;
#(
  parameter int unsigned W   = 20,  // index width in bits, two's complement (2 .. 64)
  parameter int unsigned LAT = 1    // latency in enabled clocks, 1 (the default) or 2
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

  if (LAT < 1 || LAT > 2) begin : g_check_lat
    $error("f24_to_index: LAT must be 1 or 2");
  end

  localparam int unsigned FW = W + 15;  // |a| * 2^16 for |a| < 2^(W-1): 17-bit sig << (W-2)

  localparam logic signed [W-1:0] IDX_MAX = {1'b0, {(W-1){1'b1}}};  //  2^(W-1) - 1
  localparam logic signed [W-1:0] IDX_MIN = {1'b1, {(W-1){1'b0}}};  // -2^(W-1)
  localparam logic [6:0]          E_SAT   = 7'(63 + W - 1);          // biased exponent of 2^(W-1)

  typedef struct packed {
    logic signed [W-1:0] idx;
    logic                sat;
  } index_t;

  // The conversion as a function of a, evaluated where the output registers are enabled (a
  // simulator evaluates it only in the clocks the unit advances; the hardware is the same).
  function automatic index_t to_index(input f24_t a);
    logic          s;
    logic [6:0]    ea;       // biased exponent
    logic [FW-1:0] fix;      // |a| in fixed point with 16 fraction bits (see below)
    s  = a[23];
    ea = a[22:16];
    // |a| * 2^16, exact for 1 <= |a| < 2^(W-1) (shift 0 .. W-2; larger exponents saturate below).
    // For 0 < |a| < 1 every fixed-point value in (0, 2^16) has the same floor (0, or -1 when
    // negated), so 1 stands for all of them.  Zeros give 0.
    // The shift ea - 63 is ea[5:0] + 1 for ea >= 64: the significand shifted by one more, then
    // by ea[5:0] straight from the operand's bits (no subtraction in front of the shifter).
    fix = ea[6]         ? (FW'({1'b1, a[15:0]}) << 1) << ea[5:0]
        : (ea == 7'd63) ? FW'({1'b1, a[15:0]})
        :                 FW'(ea != 7'd0);
    // |a| >= 2^(W-1), Inf or NaN: saturate; only exactly -2^(W-1) is in range; NaN gives 0.
    // Else floor(a): the two's complement fixed-point value without its 16 fraction bits
    // (dropping them rounds toward minus infinity): -1.5 -> -2, -1.0 -> -1, -0.5 -> -1.
    return (ea >= E_SAT)
        ? '{idx: (ea == EXP_SPEC && a[15:0] != 16'd0) ? '0 : (s ? IDX_MIN : IDX_MAX),
            sat: !(s && ea == E_SAT && a[15:0] == 16'd0)}
        : '{idx: $signed(W'((s ? -{1'b0, fix} : {1'b0, fix}) >> 16)), sat: 1'b0};
  endfunction

  index_t q, r;  // q: the unit's register; r: the result after LAT - 1 delay registers

  always_ff @(posedge clk_i) begin
    if (en_i) q <= to_index(a_i);
  end

  if (LAT > 1) begin : g_delay
    f24_delay #(.W($bits(index_t)), .N(LAT - 1)) u_delay (
      .clk_i, .en_i, .d_i(q), .q_o(r)
    );
  end else begin : g_out
    assign r = q;
  end

  assign idx_o = r.idx;
  assign sat_o = r.sat;

endmodule
