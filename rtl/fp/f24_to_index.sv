// SPDX-License-Identifier: Apache-2.0
// f24_to_index: f24 -> signed W-bit texel index, idx = floor(a) saturated to [-2^(W-1), 2^(W-1)-1].
// sat_o is 1 when the value was clamped or a is NaN (NaN gives idx 0); +-Inf saturate; zeros and
// subnormal patterns give 0.  Floor rounds toward minus infinity: -0.5 -> -1, -1.0 -> -1.
// Latency LAT enabled clocks (1, the default, or 2), one conversion per clock; the result is the
// same at both.  LAT = 2 adds one plain enabled delay register (f24_delay) after the unit's
// registers: its one stage is shorter than the float adder's and multiplier's, so a second
// register inside it would buy no clock speed.  Golden model: model.f24_conv.to_index.
//
// Structure: the 17-bit significand is negated first (a short carry chain: ({0, sig} - s) ^ s),
// then the two's complement value is shifted left by the exponent's low bits into a window that
// drops the 16 fraction bits: dropping fraction bits of a two's complement number rounds toward
// minus infinity, which is floor for either sign, so no sticky bit and no negation after the
// shift.  |a| < 2 and the saturated range are chosen last.  Equal to the previous form (shift
// of the magnitude, then a negation of the whole fixed-point word): checked by a Yosys SAT miter
// of the two for W = 2 .. 64 (a selection) and by the cocotb test against the model.
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

  localparam int unsigned FW = W + 16;  // sext(v) << k for k <= W - 2, 16 fraction bits
  // Shift-amount bits: ea[5:0] = k - 1 <= W - 3 for every exponent that is not saturated.
  localparam int unsigned SW = (W <= 4) ? 1 : $clog2(W - 2);

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
    logic               s;        // sign of a nonzero a (a zero or subnormal pattern gives 0)
    logic [6:0]         ea;       // biased exponent
    logic [17:0]        v;        // the signed significand: +-{1, f}, two's complement
    // fix[15:0] are the fraction bits that the floor drops: not used.
    /* verilator lint_off UNUSEDSIGNAL */
    logic [FW-1:0]      fix;      // floor(a) * 2^16 + fraction bits, for 2 <= |a| < 2^(W-1)
    /* verilator lint_on UNUSEDSIGNAL */
    logic signed [W-1:0] lo;      // floor(a) for |a| < 2 (ea <= 63)
    s   = a[23] && (a[22:16] != 7'd0);
    ea  = a[22:16];
    // Negate the 17-bit significand first (a short carry chain), then shift the two's complement
    // value: dropping the fraction bits of a two's complement number rounds toward minus
    // infinity, which is floor for either sign (-1.5 -> -2, -1.0 -> -1).  The negation is
    // ({0, sig} - s) ^ s: a decrement and an inversion, no multiplexer in front of the chain.
    v   = ({1'b0, 1'b1, a[15:0]} - 18'(s)) ^ {18{s}};
    // a = v * 2^(k - 16), k = ea - 63.  For ea >= 64, k = ea[5:0] + 1: the value shifted by one,
    // then by ea[5:0] straight from the operand's bits (no subtraction in front of the shifter);
    // only the bits below SW matter below saturation (k <= W - 2).
    fix = FW'($signed({v, 1'b0})) << ea[SW-1:0];
    // ea = 63 (|a| in [1, 2)): v >> 16 in two's complement, 1 or -1 (v = -2^16 for a = -1.0) or
    // -2; ea <= 62 (0 < |a| < 1): 0 or -1 (the sign); zeros and subnormal patterns: 0.
    lo  = (ea == 7'd63) ? W'($signed(v[17:16])) : {W{s}};
    // |a| >= 2^(W-1), Inf or NaN: saturate; only exactly -2^(W-1) is in range; NaN gives 0.
    return (ea >= E_SAT)
        ? '{idx: (ea == EXP_SPEC && a[15:0] != 16'd0) ? '0 : (a[23] ? IDX_MIN : IDX_MAX),
            sat: !(a[23] && ea == E_SAT && a[15:0] == 16'd0)}
        : '{idx: ea[6] ? $signed(fix[FW-1:16]) : lo, sat: 1'b0};
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
