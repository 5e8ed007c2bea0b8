// f24_mul: y = a * b, correctly rounded (RNE), latency 1 enabled clock, one operation per clock.
module f24_mul
  import f24_pkg::*;
(
  input  logic clk_i,  // clock
  input  logic en_i,   // clock enable: the output register advances only while en_i is 1
  input  f24_t a_i,
  input  f24_t b_i,
  output f24_t y_o
);

  f24_class_t ca, cb;
  logic        s;
  logic [33:0] prod;  // 17 x 17 bits: [2^32, 2^34)
  logic signed [11:0] e;
  logic [16:0] sig;
  logic        guard, sticky;
  f24_t        y_d, y_q;

  always_comb begin
    ca   = f24_classify(a_i);
    cb   = f24_classify(b_i);
    s    = a_i[23] ^ b_i[23];
    prod = {1'b1, a_i[15:0]} * {1'b1, b_i[15:0]};
    e    = $signed({5'd0, a_i[22:16]}) + $signed({5'd0, b_i[22:16]}) - 12'sd63;
    if (prod[33]) begin
      e      = e + 12'sd1;
      sig    = prod[33:17];
      guard  = prod[16];
      sticky = |prod[15:0];
    end else begin
      sig    = prod[32:16];
      guard  = prod[15];
      sticky = |prod[14:0];
    end
    if (ca.nan || cb.nan || (ca.zero && cb.inf) || (ca.inf && cb.zero)) y_d = F24_NAN;
    else if (ca.inf || cb.inf) y_d = f24_inf(s);
    else if (ca.zero || cb.zero) y_d = f24_zero(s);
    else y_d = f24_round_pack(s, e, sig, guard, sticky);
  end

  always_ff @(posedge clk_i) begin
    if (en_i) y_q <= y_d;
  end

  assign y_o = y_q;

endmodule
