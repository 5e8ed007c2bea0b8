// SPDX-License-Identifier: Apache-2.0
// f24_mul: y = a * b, correctly rounded (RNE), latency LAT enabled clocks, one operation per clock.
// The result word is the same at every LAT.  Written as straight data flow (each signal assigned once, choices by ?:), which simulates
// cheaper than if/else chains.
//
// The clock holds the 17 x 17 multiplier (a MULT18X18D, combinational: about half of the clock
// period), so everything that does not need the product is computed beside it, and after it come
// only a 2:1 mux, one carry chain and a last 2:1 mux:
//   - beside the multiplier, from the operands alone: the classes (zero, Inf / NaN), and from
//     t = ea + eb + 1 (the biased exponent of a product in [1, 2), plus 64) three flags for each
//     alignment h = 0 / 1 of the product (h = its bit 33, one more in the exponent): flush
//     (exponent below 0, or a zero operand), Inf / NaN (exponent above 126, or a special operand),
//     and "in [1, 126]" (the fraction is kept);
//   - after the multiplier: the fraction f aligned by h, the exponent field t + h (bit logic,
//     not a second chain), {exponent, f} + 1 in one carry chain (a fraction of all ones carries
//     into the exponent: exactly 2.0 renormalised), and the round-up bit (guard and sticky, RNE)
//     for either alignment; the round-up bit then picks {exponent, f} or the incremented one.
//   - the flush and Inf / NaN flags pick exponent 0 / 127 last, and out of [1, 126] the fraction
//     is 0 (the NaN's 0x8000); these need h alone, not the rounding: an exponent of 0 that rounds
//     up to 1 is exactly 2^-62 (fraction 0, the chain gives it), one of 126 that rounds up to 127
//     is Inf (fraction 0 again).
// Equal to the previous single round-and-pack of the normalised product (f24_pkg::f24_round_pack
// with its range compare after the rounding): checked by a Yosys SAT miter of the two
// combinational functions and by the cocotb test against the model.
//
// LAT = 2 (for clock speed): a register after the multiplier.  Stage 1 holds the MULT18X18D, the
// OR of the product's 15 bits below both guard positions (the sticky bit of the h = 0 alignment)
// and, beside them, everything computed from the operands alone (sign, NaN, t and the six range
// flags); stage 2 the alignment, rounding and packing.  LAT = 3: the two stages, then one plain
// enabled delay register (f24_delay).
module f24_mul
  import f24_pkg::*;
#(
  // Latency in enabled clocks, 1 .. 3: 1 = the paper's (one stage); 2 = a register after the
  // multiplier; 3 = the two stages and a delay register.  The same result at every LAT.
  parameter int unsigned LAT = 1
) (
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the registers advance only while en_i is 1
  input  f24_t a_i,
  input  f24_t b_i,
  output f24_t y_o
);

  if (LAT < 1 || LAT > 3) begin : g_check_lat
    $error("f24_mul: LAT must be in 1..3");
  end

  // x >= k for a constant k, as plain logic from the bottom bit up (a comparison written with >=
  // would become a carry chain of its own; this one is a few LUTs beside the multiplier).
  function automatic logic ge(input logic [7:0] x, input logic [7:0] k);
    logic r;
    r = 1'b1;  // x >= k over the bits below the current one (none yet: equal)
    for (int i = 0; i < 8; i++) r = k[i] ? (x[i] && r) : (x[i] || r);
    return r;
  endfunction

  // The product and the flags from the operands (the register of stage 1 at LAT >= 2).
  typedef struct packed {
    logic        s;               // sign of the result (before a NaN clears it)
    logic        nan;             // the result is NaN: a NaN operand, or 0 * Inf
    logic [6:0]  t;               // ea + eb + 1, low 7 bits (see mul_prod)
    logic        lo0, lo1;        // flush to zero for h = 0 / 1
    logic        hi0, hi1;        // Inf / NaN exponent for h = 0 / 1
    logic        in0, in1;        // exponent in [1, 126] for h = 0 / 1: keep the fraction
    logic [33:15] prod;           // the product's bits from the lower guard position up
    logic        st_l;            // OR of the product's bits 14:0
  } prod_t;

  // Stage 1: the multiplier and, beside it, everything that needs the operands alone.
  function automatic prod_t mul_prod(input f24_t a, input f24_t b);
    logic        a_zero, b_zero;  // exponent 0: +-0 (subnormal patterns read as zero)
    logic        a_spec, b_spec;  // exponent 127: Inf or NaN
    logic        spec, zero;      // some operand is Inf / NaN; some operand is zero
    logic        fin;             // both operands finite and nonzero: the rounded product
    logic [7:0]  t;               // ea + eb + 1 = (biased exponent of a product in [1, 2)) + 64
    logic [33:0] prod;            // 17 x 17 bits: [2^32, 2^34)
    a_zero = (a[22:16] == 7'd0);
    b_zero = (b[22:16] == 7'd0);
    a_spec = (a[22:16] == EXP_SPEC);
    b_spec = (b[22:16] == EXP_SPEC);
    spec   = a_spec || b_spec;
    zero   = a_zero || b_zero;
    fin    = !spec && !zero;
    // Beside the multiplier: the exponent and its range for k = h = 0 and 1.  The biased exponent
    // of a product in [1, 2) is ea + eb - 63 = t - 64.
    t      = {1'b0, a[22:16]} + {1'b0, b[22:16]} + 8'd1;
    prod   = {1'b1, a[15:0]} * {1'b1, b[15:0]};
    return '{s:    a[23] ^ b[23],
             nan:  spec && (zero || (a_spec && a[15:0] != 16'd0) || (b_spec && b[15:0] != 16'd0)),
             t:    t[6:0],
             lo0:  !spec && (zero || !ge(t, 8'd64)),
             lo1:  !spec && (zero || !ge(t, 8'd63)),
             hi0:  spec || (!zero && ge(t, 8'd191)),
             hi1:  spec || (!zero && ge(t, 8'd190)),
             in0:  fin && ge(t, 8'd65) && !ge(t, 8'd191),
             in1:  fin && ge(t, 8'd64) && !ge(t, 8'd190),
             prod: prod[33:15],
             st_l: |prod[14:0]};
  endfunction

  // Stage 2 (the same stage as the multiplier at LAT = 1): alignment, rounding, packing.
  function automatic f24_t mul_round(input prod_t p);
    logic        h;               // prod in [2^33, 2^34): the exponent is one higher
    logic        st_h;            // sticky bit below the guard bit for h = 1 (p.st_l: h = 0)
    logic        up;              // round up: above halfway, or halfway with an odd significand
    logic [6:0]  eh;              // exponent field of the truncated product: t + h, bit 6 flipped
    logic        cy;              // carry of t + h
    logic [15:0] f;               // fraction of the truncated product
    logic [6:0]  ehi;             // {eh, f} + 1: the rounded-up exponent field and fraction
    logic [15:0] fi;
    logic        lo, hi, in;      // lo*, hi*, in* for k = h
    // A product in [1, 2) keeps bits 31:16 as its fraction, one in [2, 4) bits 32:17 and one more
    // in the exponent.
    h      = p.prod[33];
    st_h   = p.st_l || p.prod[15];
    up     = h ? (p.prod[16] && (st_h || p.prod[17])) : (p.prod[15] && (p.st_l || p.prod[16]));
    f      = h ? p.prod[32:17] : p.prod[31:16];
    // t + h as bit logic (h is late: no second carry chain), bit 6 flipped for the bias.
    cy     = h;
    for (int i = 0; i < 7; i++) begin
      eh[i] = p.t[i] ^ cy;
      cy    = cy && p.t[i];
    end
    eh[6]  = !eh[6];
    {ehi, fi} = {eh, f} + 23'd1;
    lo     = h ? p.lo1 : p.lo0;
    hi     = h ? p.hi1 : p.hi0;
    in     = h ? p.in1 : p.in0;
    // A flushed result: exponent 0.  An Inf / NaN one: 127.  Else the exponent field, rounded up
    // or not; out of [1, 126] before rounding the fraction is 0 (or the NaN's), and a rounding
    // that carries into the exponent leaves the fraction 0 too.
    return {p.s && !p.nan,
            lo ? 7'd0 : hi ? EXP_SPEC : up ? ehi : eh,
            !in ? {p.nan, 15'd0} : up ? fi : f};
  endfunction

  // Each stage is a function of its inputs, evaluated where its register is enabled (a simulator
  // evaluates it only in the clocks the unit advances; the hardware is the same).
  prod_t p_q;  // LAT >= 2: stage 1
  f24_t  y_q;  // the last stage

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      if (LAT == 1) begin
        y_q <= mul_round(mul_prod(a_i, b_i));
      end else begin
        p_q <= mul_prod(a_i, b_i);
        y_q <= mul_round(p_q);
      end
    end
  end

  if (LAT > 2) begin : g_delay
    f24_delay #(.W(24), .N(LAT - 2)) u_delay (
      .clk_i, .en_i, .d_i(y_q), .q_o(y_o)
    );
  end else begin : g_out
    assign y_o = y_q;
  end

endmodule
