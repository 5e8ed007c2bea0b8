// SPDX-License-Identifier: Apache-2.0
// f24_div: y = a / b, correctly rounded (RNE), latency LAT enabled clocks, one operation per clock.
// LAT = 2 (the default, the paper's):
//   Stage 1: operand classes and the special result, sign, exponent and the 19-bit significand
//   quotient by a restoring division loop (combinational), with a sticky bit from the final
//   remainder.
//   Stage 2: normalise the quotient to 17 bits + guard + sticky, round, pack (f24_round_pack).
// LAT > 2 (for clock speed; the result is the same, bit for bit): the 19 steps of the restoring
// loop are spread over stages 1 .. LAT-1, STEP = ceil(19 / (LAT-1)) quotient bits per stage (the
// last stage of the loop takes what is left; a stage past the 19th bit only passes the state on).
// Stage 1 also does the classification, special result, sign and exponent; every loop stage
// carries the partial remainder, the quotient bits so far, the divisor and the special / sign /
// exponent fields in its register.  Stage LAT-1 ends with the sticky bit of the final remainder;
// stage LAT normalises, rounds and packs as above.
module f24_div
  import f24_pkg::*;
#(
  // Latency in enabled clocks, 2 .. 20: 2 = the whole division loop in one stage (the paper's),
  // more = the loop over LAT-1 stages for a faster clock (same results).  f24_pkg::F24_DIV_LAT
  // is the latency the design instantiates.
  parameter int unsigned LAT = 2
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the pipeline registers advance only while en_i is 1
  input  f24_t a_i,    // dividend
  input  f24_t b_i,    // divisor
  output f24_t y_o     // a / b
);

  localparam int unsigned Q_W  = SIG_W + 2;  // quotient bits: 17 + guard + one for ma < mb
  localparam int unsigned NL   = (LAT > 1) ? LAT - 1 : 1;  // stages of the division loop
  localparam int unsigned STEP = (Q_W + NL - 1) / NL;  // quotient bits per loop stage

  if (LAT < 2 || LAT > Q_W + 1) begin : g_check_lat
    $error("f24_div: LAT must be in 2..20");
  end

  // Each stage is a function of its inputs, evaluated where its register is enabled (so a
  // simulator evaluates a stage only in the clocks it advances; the hardware is the same).

  // ---- the division loop (stages 1 .. LAT-1) ----------------------------------------------------
  // What every stage after the first carries unchanged to the rounding stage.
  typedef struct packed {
    logic               spec;    // result is a special (spec_y)
    f24_t               spec_y;
    logic               s;
    logic signed [11:0] e;       // biased exponent of a quotient in [1, 2)
  } head_t;

  // The state between two loop stages.
  typedef struct packed {
    head_t              h;
    logic [FRAC_W-1:0]  fb;      // the divisor's fraction (mb = {1, fb})
    logic [17:0]        rem;     // partial remainder, shifted for the next bit, < 2 * mb
    logic [Q_W-1:0]     quo;     // the quotient bits so far (the bits still to come are 0)
  } part_t;

  // Restoring division steps for quotient bits hi down to lo (none when hi < lo), most
  // significant first.  ma < 2 * mb, so the first bit is ma >= mb and every later remainder stays
  // below 2 * mb (18 bits).
  function automatic part_t div_steps(input part_t p, input int hi, input int lo);
    part_t       q;
    logic [16:0] mb;
    q  = p;
    mb = {1'b1, p.fb};
    for (int i = hi; i >= lo; i--) begin
      if (q.rem >= {1'b0, mb}) begin
        q.quo[i] = 1'b1;
        q.rem    = q.rem - {1'b0, mb};
      end
      if (i != 0) q.rem = {q.rem[16:0], 1'b0};
    end
    return q;
  endfunction

  // Stage 1: classify, exponent, the special result; then the first loop steps (hi .. lo).
  function automatic part_t div_first(input f24_t a, input f24_t b, input int lo);
    logic a_zero, b_zero;  // exponent 0: +-0 (subnormal patterns read as zero)
    logic a_spec, b_spec;  // exponent 127: Inf or NaN
    logic any_nan;
    logic s;
    a_zero  = (a[22:16] == 7'd0);
    b_zero  = (b[22:16] == 7'd0);
    a_spec  = (a[22:16] == EXP_SPEC);
    b_spec  = (b[22:16] == EXP_SPEC);
    any_nan = (a_spec && a[15:0] != 16'd0) || (b_spec && b[15:0] != 16'd0);
    s       = a[23] ^ b[23];
    // NaN for a NaN operand, 0/0 or Inf/Inf; Inf for Inf/finite or finite/0; zero for 0/finite
    // or finite/Inf.  The remainder starts as ma, the dividend's significand with the hidden one.
    return div_steps('{h:  '{spec:   a_spec || b_spec || a_zero || b_zero,
                             spec_y: (any_nan || (a_zero && b_zero) || (a_spec && b_spec))
                                   ? F24_NAN
                                   : (a_spec || b_zero) ? {s, EXP_SPEC, 16'd0} : {s, 23'd0},
                             s:      s,
                             e:      $signed({5'd0, a[22:16]}) - $signed({5'd0, b[22:16]})
                                   + 12'sd63},
                       fb:     b[15:0],
                       rem:    {2'b01, a[15:0]},
                       quo:    '0},
                     Q_W - 1, lo);
  endfunction

  // ---- the quotient at the end of the loop (stage LAT-1's register) -----------------------------
  typedef struct packed {
    head_t              h;
    logic [Q_W-1:0]     quo;     // floor(ma * 2^18 / mb), in [2^17, 2^19)
    logic               rem_nz;  // the final remainder is not zero
  } quot_t;

  // The divisor is not needed past the loop (hence the waiver on p.fb).
  /* verilator lint_off UNUSEDSIGNAL */
  function automatic quot_t div_quot(input part_t p);
    return '{h: p.h, quo: p.quo, rem_nz: (p.rem != 18'd0)};
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // ---- stage LAT: normalise, round, pack -------------------------------------------------------
  function automatic f24_t div_round(input quot_t q);
    logic [Q_W-1:0]     norm;   // q.quo with its leading one at the top bit
    logic signed [11:0] e;
    // ma >= mb: quotient in [1, 2), leading one at the top bit.  ma < mb: quotient in (1/2, 1),
    // shifted up by one (its last bit, and the remainder, go to the sticky bit).
    norm = q.quo << !q.quo[Q_W-1];
    e    = q.h.e - $signed({11'd0, !q.quo[Q_W-1]});
    return q.h.spec ? q.h.spec_y
                    : f24_round_pack(q.h.s, e, norm[Q_W-1:2], norm[1], norm[0] | q.rem_nz);
  endfunction

  // Quotient bits of loop stage j (1 .. NL): hi(j) down to lo(j).
  function automatic int step_hi(input int j);
    return int'(Q_W) - 1 - (j - 1) * int'(STEP);
  endfunction
  function automatic int step_lo(input int j);
    return (int'(Q_W) - j * int'(STEP) > 0) ? int'(Q_W) - j * int'(STEP) : 0;
  endfunction

  quot_t q_q;  // stage LAT-1: the quotient and sticky bit
  f24_t  y_q;  // stage LAT: the result

  if (LAT == 2) begin : g_loop1
    always_ff @(posedge clk_i) begin
      if (en_i) q_q <= div_quot(div_first(a_i, b_i, 0));
    end
  end else begin : g_loopn
    part_t p_q [1:NL-1];  // p_q[j]: the state after loop stage j
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        p_q[1] <= div_first(a_i, b_i, step_lo(1));
        for (int j = 2; j < int'(NL); j++) p_q[j] <= div_steps(p_q[j-1], step_hi(j), step_lo(j));
        q_q <= div_quot(div_steps(p_q[NL-1], step_hi(NL), 0));
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= div_round(q_q);
  end

  assign y_o = y_q;

endmodule
