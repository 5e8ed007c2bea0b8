// f24_div: y = a / b, correctly rounded (RNE), latency 2 enabled clocks, one operation per clock.
// Stage 1: operand classes and the special result, sign, exponent and the 19-bit significand
// quotient by a restoring division loop (combinational), with a sticky bit from the final
// remainder.
// Stage 2: normalise the quotient to 17 bits + guard + sticky, round, pack (f24_round_pack).
module f24_div
  import f24_pkg::*;
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the pipeline registers advance only while en_i is 1
  input  f24_t a_i,    // dividend
  input  f24_t b_i,    // divisor
  output f24_t y_o     // a / b
);

  localparam int unsigned Q_W = SIG_W + 2;  // quotient bits: 17 + guard + one for ma < mb

  // Each stage is a function of its inputs, evaluated where its register is enabled (so a
  // simulator evaluates a stage only in the clocks it advances; the hardware is the same).

  // ---- stage 1: classify, exponent, significand quotient ---------------------------------------
  typedef struct packed {
    logic               spec;    // result is a special (spec_y)
    f24_t               spec_y;
    logic               s;
    logic signed [11:0] e;       // biased exponent of a quotient in [1, 2)
    logic [Q_W-1:0]     quo;     // floor(ma * 2^18 / mb), in [2^17, 2^19)
    logic               rem_nz;  // the final remainder is not zero
  } quot_t;

  function automatic quot_t div_quot(input f24_t a, input f24_t b);
    logic           a_zero, b_zero;  // exponent 0: +-0 (subnormal patterns read as zero)
    logic           a_spec, b_spec;  // exponent 127: Inf or NaN
    logic           any_nan;
    logic           s;
    logic [16:0]    ma, mb;          // significands with the hidden one, value in [2^16, 2^17)
    logic [17:0]    rem;             // partial remainder, always < 2 * mb
    logic [Q_W-1:0] quo;
    a_zero  = (a[22:16] == 7'd0);
    b_zero  = (b[22:16] == 7'd0);
    a_spec  = (a[22:16] == EXP_SPEC);
    b_spec  = (b[22:16] == EXP_SPEC);
    any_nan = (a_spec && a[15:0] != 16'd0) || (b_spec && b[15:0] != 16'd0);
    s       = a[23] ^ b[23];
    ma      = {1'b1, a[15:0]};
    mb      = {1'b1, b[15:0]};

    // Restoring division: one quotient bit per step, most significant first.  ma < 2 * mb, so
    // the first bit is ma >= mb and every later remainder stays below 2 * mb (18 bits).
    rem = {1'b0, ma};
    quo = '0;
    for (int i = Q_W - 1; i >= 0; i--) begin
      if (rem >= {1'b0, mb}) begin
        quo[i] = 1'b1;
        rem    = rem - {1'b0, mb};
      end
      if (i != 0) rem = {rem[16:0], 1'b0};
    end

    // NaN for a NaN operand, 0/0 or Inf/Inf; Inf for Inf/finite or finite/0; zero for 0/finite
    // or finite/Inf.
    return '{spec:   a_spec || b_spec || a_zero || b_zero,
             spec_y: (any_nan || (a_zero && b_zero) || (a_spec && b_spec)) ? F24_NAN
                   : (a_spec || b_zero)                                    ? {s, EXP_SPEC, 16'd0}
                   :                                                         {s, 23'd0},
             s:      s,
             e:      $signed({5'd0, a[22:16]}) - $signed({5'd0, b[22:16]}) + 12'sd63,
             quo:    quo,
             rem_nz: (rem != 18'd0)};
  endfunction

  // ---- stage 2: normalise, round, pack ---------------------------------------------------------
  function automatic f24_t div_round(input quot_t q);
    logic [Q_W-1:0]     norm;   // q.quo with its leading one at the top bit
    logic signed [11:0] e;
    // ma >= mb: quotient in [1, 2), leading one at the top bit.  ma < mb: quotient in (1/2, 1),
    // shifted up by one (its last bit, and the remainder, go to the sticky bit).
    norm = q.quo << !q.quo[Q_W-1];
    e    = q.e - $signed({11'd0, !q.quo[Q_W-1]});
    return q.spec ? q.spec_y : f24_round_pack(q.s, e, norm[Q_W-1:2], norm[1], norm[0] | q.rem_nz);
  endfunction

  quot_t s1_q;
  f24_t  y_q;

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      s1_q <= div_quot(a_i, b_i);
      y_q  <= div_round(s1_q);
    end
  end

  assign y_o = y_q;

endmodule
