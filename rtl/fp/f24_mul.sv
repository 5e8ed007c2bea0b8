// f24_mul: y = a * b, correctly rounded (RNE), latency 1 enabled clock, one operation per clock.
// Written as straight data flow (each signal assigned once, choices by ?:), which simulates
// cheaper than if/else chains.
module f24_mul
  import f24_pkg::*;
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the output register advances only while en_i is 1
  input  f24_t a_i,
  input  f24_t b_i,
  output f24_t y_o
);

  // The product as a function of the operands, evaluated where the output register is enabled
  // (a simulator evaluates it only in the clocks the unit advances; the hardware is the same).
  function automatic f24_t mul(input f24_t a, input f24_t b);
    logic        a_zero, b_zero;  // exponent 0: +-0 (subnormal patterns read as zero)
    logic        a_spec, b_spec;  // exponent 127: Inf or NaN
    logic        any_nan;
    logic        s;
    logic [33:0] prod;            // 17 x 17 bits: [2^32, 2^34)
    logic [33:0] norm;            // prod with its leading one at bit 33
    logic signed [11:0] e;        // biased exponent of norm
    a_zero  = (a[22:16] == 7'd0);
    b_zero  = (b[22:16] == 7'd0);
    a_spec  = (a[22:16] == EXP_SPEC);
    b_spec  = (b[22:16] == EXP_SPEC);
    any_nan = (a_spec && a[15:0] != 16'd0) || (b_spec && b[15:0] != 16'd0);
    s       = a[23] ^ b[23];
    prod    = {1'b1, a[15:0]} * {1'b1, b[15:0]};
    // A product in [1, 2) is shifted up by one; one in [2, 4) bumps the exponent instead.
    norm    = prod << !prod[33];
    e       = $signed({5'd0, a[22:16]}) + $signed({5'd0, b[22:16]}) - 12'sd63
            + $signed({11'd0, prod[33]});
    // An Inf or NaN operand: NaN for a NaN or for 0 * Inf, else Inf.  Then a zero operand: zero.
    // Else the rounded product of two finite nonzero operands.
    return (a_spec || b_spec) ? ((any_nan || a_zero || b_zero) ? F24_NAN : {s, EXP_SPEC, 16'd0})
         : (a_zero || b_zero) ? {s, 23'd0}
         :                      f24_round_pack(s, e, norm[33:17], norm[16], |norm[15:0]);
  endfunction

  f24_t y_q;

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= mul(a_i, b_i);
  end

  assign y_o = y_q;

endmodule
