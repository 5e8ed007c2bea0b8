// SPDX-License-Identifier: Apache-2.0
// f24_one_minus: y = 1 - x for x in [+0, 1], correctly rounded (RNE): the same word as
// f24_add(1, -x) for every such x (tested on every f24 value in the range), in one clock instead
// of the adder's two.  The traverse ring's plane, 1 - H, with H = f24_from_unorm(code) in [0, 1].
// Latency LAT enabled clocks (1, the default, or 2), one operation per clock; the result word is
// the same at both.  Golden model: model.f24.add(1, neg(x)).
// LAT = 2 (for clock speed): stage 1 the right shift with its guard, sticky and round-up bits,
// and 2^16 - f with its leading-zero count; stage 2 the subtraction from 2^17 (a carry chain) and
// the normalising left shift, then the choice of the result.
//
// Why it is one fixed-point subtraction: write P = 2^17 (1 - x).  For x in [0.5, 1] the
// difference 1 - x is exact (Sterbenz) and x is a multiple of 2^-17, so P = 2^17 - x 2^17 is an
// integer of at most 17 bits: y = P 2^-17, normalised by its leading zeros, never rounded.  For
// x < 0.5 the result is in (0.5, 1], whose f24 spacing is 2^-17: rounding 1 - x to a multiple of
// 2^-17 is subtracting x rounded to a multiple of 2^-17 (ties to even either way, 2^17 being
// even), so P = 2^17 - RNE(x 2^17), between 2^16 and 2^17 (1.0), exponent fixed.
//   x = (2^16 + f) 2^(e - 79) (biased exponent e, fraction f), so x 2^17 = (2^16 + f) >> (62 - e).
//   e = 62:          P = 2^16 - f (f = 0: 0.5)                      leading-zero count, shift
//   45 <= e <= 61:   P = ~({1, f} >> s) + !up over 17 bits, s = 62 - e, up = RNE's round-up
//                    (guard and sticky of the shift); 2^17 gives 1.0, else exponent 62
//   e <= 44, x = +0: 1.0 (x 2^17 < 1/2);   x = 1.0: +0
// An input outside [+0, 1] (negative, above 1, Inf, NaN) gives an unspecified word: the client
// guarantees the range (the traverse ring asserts it; the unit has no reset to qualify an
// assertion of its own with, and its enable may be 1 on garbage while nothing uses the result).
module f24_one_minus
  import f24_pkg::*;
#(
  parameter int unsigned LAT = 1  // latency in enabled clocks, 1 (the default) or 2
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,    // in [+0, 1]
  output f24_t y_o     // 1 - a_i
);

  if (LAT < 1 || LAT > 2) begin : g_check_lat
    $error("f24_one_minus: LAT must be 1 or 2");
  end

  // Stage 1's result (the register between the stages at LAT = 2).
  typedef struct packed {
    logic        one;   // e = 0 or e <= 44: y = 1.0
    logic        zero;  // e >= 63: y = +0 (x = 1.0 in the domain)
    logic        e62;   // e = 62: exact, 2^16 - f normalised
    logic [16:0] hs;    // 45 <= e <= 61: sig >> s
    logic        up;    // 45 <= e <= 61: RNE's round-up bit of that shift
    logic [16:0] p62;   // e = 62: P = 2^16 - f, 1 .. 2^16
    logic [4:0]  lz;    // e = 62: leading zeros of p62 in 17 bits (p62 >= 1: at most 16)
  } om_t;

  // Stage 1: the shift and its rounding bits; 2^16 - f and its leading-zero count.
  /* verilator lint_off UNUSEDSIGNAL */  // x[23]: the range has sign 0 (asserted)
  function automatic om_t one_minus_shift(input f24_t x);
  /* verilator lint_on UNUSEDSIGNAL */
    logic [6:0]  e;
    logic [15:0] f;
    logic [16:0] sig;      // {1, f}
    logic [4:0]  t;        // 63 - e = ~e[5:0] (e <= 63), the right shift s = 62 - e plus 1,
                           // for t <= 18 (e >= 45; far covers the rest): ~e[4:0]
    logic        far;      // s >= 18 (e <= 44): x 2^17 < 1/2, so P = 2^17: y = 1.0
    logic [16:0] hs;       // sig >> s
    logic        guard, sticky;
    logic [16:0] p62;      // P for e = 62: 2^16 - f, 1 .. 2^16
    // wsh[35] is 0 (t >= 1): not stored in the word.
    /* verilator lint_off UNUSEDSIGNAL */
    logic [35:0] wsh;      // {sig, 19 zeros} >> t: hs, guard, then the sticky bits
    /* verilator lint_on UNUSEDSIGNAL */
    e      = x[22:16];
    f      = x[15:0];
    sig    = {1'b1, f};
    // No subtraction before the shift: t is e's complement, and {sig, 19 zeros} >> t puts
    // sig >> s at bits 34..18, the guard (sig bit s - 1) at bit 17 and the bits below it at
    // 16..0.
    t      = ~e[4:0];
    far    = (e <= 7'd44);
    wsh    = {sig, 19'd0} >> t;
    hs     = wsh[34:18];
    guard  = wsh[17];
    sticky = (wsh[16:0] != 17'd0);
    p62    = 17'h10000 - {1'b0, f};
    return '{one:  (e == 7'd0 || far),
             zero: (e >= 7'd63),
             e62:  (e == 7'd62),
             hs:   hs,
             up:   guard & (sticky | hs[0]),
             p62:  p62,
             lz:   f24_clz32({p62, 15'd0})};  // (p62 != 0: below 17)
  endfunction

  // Stage 2: 2^17 - hs - up, the normalising shift of 2^16 - f, the result.
  function automatic f24_t one_minus_pack(input om_t m);
    // q[16] is 1 (q >= 2^16) and nrm[16] is the leading one: neither is stored in the word.
    /* verilator lint_off UNUSEDSIGNAL */
    logic [17:0] q;        // P for 45 <= e <= 61: 2^16 .. 2^17
    logic [16:0] nrm;      // p62 shifted so that its leading one is bit 16
    /* verilator lint_on UNUSEDSIGNAL */
    q      = {1'b0, ~m.hs} + 18'(!m.up);   // 2^17 - hs - up
    nrm    = m.p62 << m.lz;
    if (m.one) begin
      return F24_ONE;                                          // 1 - 0, 1 - (x < 2^-18)
    end else if (m.zero) begin
      return '0;                                               // 1 - 1 (domain: x <= 1)
    end else if (m.e62) begin
      return {1'b0, 7'(7'd62 - {2'b0, m.lz}), nrm[15:0]};     // exact: 2^(-1-lz) .. 0.5
    end else begin
      return q[17] ? F24_ONE : {1'b0, 7'd62, q[15:0]};        // rounded, in (0.5, 1]
    end
  endfunction

  // Each stage is a function of its inputs, evaluated where its register is enabled (a simulator
  // evaluates it only in the clocks the unit advances; the hardware is the same).
  om_t  m_q;  // LAT = 2: stage 1
  f24_t y_q;  // the last stage

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      if (LAT == 1) begin
        y_q <= one_minus_pack(one_minus_shift(a_i));
      end else begin
        m_q <= one_minus_shift(a_i);
        y_q <= one_minus_pack(m_q);
      end
    end
  end

  assign y_o = y_q;

endmodule
