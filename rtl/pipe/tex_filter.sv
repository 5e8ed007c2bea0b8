// tex_filter: the bilinear filter of the texture path (Park et al. 2013, Fig. 6, after the
// texture cache): four RGBA unorm8 texels and the two weights of tex_addr in, the filtered
// channels out, one lookup per clock.  Specification: model/texture.py filter_texels (steps 6-7
// of the module docstring's "Bilinear lookup at level L") in the f24 engine, bit for bit, per
// channel:
//   c = from_unorm(code, 8)                                 f24_from_unorm W = 8
//   top = add(c00, mul(fx, sub(c01, c00)))
//   bot = add(c10, mul(fx, sub(c11, c10)))
//   out = add(top, mul(fy, sub(bot, top)))
// Texels: the 32-bit little-endian word of the texel's four bytes in memory (model.texture's
// memory_image stores R, G, B, A at increasing addresses): R in bits 7:0, G in 15:8, B in 23:16,
// A in 31:24.  fx, fy are any f24 words (tex_addr's, in [0, 1] for finite coordinates; NaN, Inf
// and out-of-range weights go through the same operations as in the model).
//
// The pipeline uses R, G, B of the colour texture and of the normal map: A is filtered only
// with ALPHA = 1 (a_o is 0 otherwise, and bits 31:24 of the texels are ignored).
//
// Fully pipelined, fixed latency TEX_FILTER_LAT = 11 enabled clocks (pipe_pkg), one lookup per
// clock, the conventions of view_calc: every register advances only while en_i is 1 (the
// enclosing pipeline's stall), valid is reset by rst_ni (synchronous, active low), data registers
// have no reset; a lookup taken on an enabled edge with valid_i = 1 shows at the outputs after 11
// enabled edges and holds while en_i is 0.
//
// Stage schedule per channel (S0 = the input ports; "a -> b": a unit takes operands in Sa, result
// in Sb):
//   S0  c00, c01, c10, c11 = from_unorm(code)                  4 f24_from_unorm  S0 -> S1
//       fx delayed S0 -> S3, fy delayed S0 -> S8
//   S1  d0 = sub(c01, c00), d1 = sub(c11, c10)                  2 f24_add         S1 -> S3
//       c00, c10 delayed S1 -> S4
//   S3  m0 = mul(fx, d0), m1 = mul(fx, d1)                      2 f24_mul         S3 -> S4
//   S4  top = add(c00, m0), bot = add(c10, m1)                  2 f24_add         S4 -> S6
//   S6  d = sub(bot, top)                                       f24_add           S6 -> S8
//       top delayed S6 -> S9
//   S8  m = mul(fy, d)                                          f24_mul           S8 -> S9
//   S9  out = add(top, m)                                       f24_add           S9 -> S11
//   S11 outputs (straight from the adders' registers)
// Float units per channel: 4 f24_from_unorm, 6 f24_add, 3 f24_mul (3 or 4 channels).
module tex_filter
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W = 8,     // side-band bits carried from tag_i to tag_o
  parameter bit          ALPHA = 1'b0   // 1: filter A too (a_o); 0: R, G, B only
) (
  input  logic               clk_i,
  input  logic               rst_ni,   // synchronous, active low: clears the valid bits
  input  logic               en_i,     // clock enable of the whole pipeline (0 = stall)
  input  logic               valid_i,
  input  logic [TAG_W-1:0]   tag_i,
  input  logic [TEXEL_W-1:0] t00_i,    // c00 = T[i0, j0]: {A, B, G, R}
  input  logic [TEXEL_W-1:0] t01_i,    // c01 = T[i0, j1]
  input  logic [TEXEL_W-1:0] t10_i,    // c10 = T[i1, j0]
  input  logic [TEXEL_W-1:0] t11_i,    // c11 = T[i1, j1]
  input  f24_t               fx_i,     // weight along u (tex_addr)
  input  f24_t               fy_i,     // weight along v
  output logic               valid_o,
  output logic [TAG_W-1:0]   tag_o,
  output f24_t               r_o,
  output f24_t               g_o,
  output f24_t               b_o,
  output f24_t               a_o       // 0 unless ALPHA
);

  // Stage numbers (pipe_pkg latencies); S_OUT = TEX_FILTER_LAT.
  localparam int unsigned S_D0  = F24_FROM_UNORM_LAT;    // 1: row differences
  localparam int unsigned S_M0  = S_D0 + F24_ADD_LAT;    // 3: times fx
  localparam int unsigned S_A0  = S_M0 + F24_MUL_LAT;    // 4: top, bot
  localparam int unsigned S_D1  = S_A0 + F24_ADD_LAT;    // 6: bot - top
  localparam int unsigned S_M1  = S_D1 + F24_ADD_LAT;    // 8: times fy
  localparam int unsigned S_A1  = S_M1 + F24_MUL_LAT;    // 9: top + ...
  localparam int unsigned S_OUT = S_A1 + F24_ADD_LAT;    // 11
  if (S_OUT != TEX_FILTER_LAT) begin : g_check_lat
    $error("tex_filter: stage schedule does not add up to TEX_FILTER_LAT");
  end

  localparam int unsigned CH = ALPHA ? 4 : 3;  // channels filtered

  // ---- the weights' delay lines --------------------------------------------------------------
  f24_t fx_q [1:S_M0];                         // fx in stages S1 .. S3
  f24_t fy_q [1:S_M1];                         // fy in stages S1 .. S8

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      fx_q[1] <= fx_i;
      for (int s = 2; s <= S_M0; s++) fx_q[s] <= fx_q[s-1];
      fy_q[1] <= fy_i;
      for (int s = 2; s <= S_M1; s++) fy_q[s] <= fy_q[s-1];
    end
  end

  // ---- per channel -----------------------------------------------------------------------------
  f24_t out [4];

  for (genvar c = 0; c < CH; c++) begin : g_ch
    f24_t c00, c01, c10, c11;                  // S1
    f24_t d0, d1;                              // S3
    f24_t m0, m1;                              // S4
    f24_t top, bot;                            // S6
    f24_t d;                                   // S8
    f24_t m;                                   // S9
    f24_t c00_q [S_D0+1:S_A0];                 // c00 in stages S2 .. S4
    f24_t c10_q [S_D0+1:S_A0];                 // c10 in stages S2 .. S4
    f24_t top_q [S_D1+1:S_A1];                 // top in stages S7 .. S9

    // S0: the four codes of channel c
    f24_from_unorm #(.W(8)) u_c00 (.clk_i, .en_i, .k_i(t00_i[8*c +: 8]), .y_o(c00));
    f24_from_unorm #(.W(8)) u_c01 (.clk_i, .en_i, .k_i(t01_i[8*c +: 8]), .y_o(c01));
    f24_from_unorm #(.W(8)) u_c10 (.clk_i, .en_i, .k_i(t10_i[8*c +: 8]), .y_o(c10));
    f24_from_unorm #(.W(8)) u_c11 (.clk_i, .en_i, .k_i(t11_i[8*c +: 8]), .y_o(c11));
    // S1: differences along u (subtract: flip the sign bit)
    f24_add u_d0 (.clk_i, .en_i, .a_i(c01), .b_i({~c00[23], c00[22:0]}), .y_o(d0));
    f24_add u_d1 (.clk_i, .en_i, .a_i(c11), .b_i({~c10[23], c10[22:0]}), .y_o(d1));
    // S3: times fx
    f24_mul u_m0 (.clk_i, .en_i, .a_i(fx_q[S_M0]), .b_i(d0), .y_o(m0));
    f24_mul u_m1 (.clk_i, .en_i, .a_i(fx_q[S_M0]), .b_i(d1), .y_o(m1));
    // S4: the two rows
    f24_add u_top (.clk_i, .en_i, .a_i(c00_q[S_A0]), .b_i(m0), .y_o(top));
    f24_add u_bot (.clk_i, .en_i, .a_i(c10_q[S_A0]), .b_i(m1), .y_o(bot));
    // S6: difference along v
    f24_add u_d (.clk_i, .en_i, .a_i(bot), .b_i({~top[23], top[22:0]}), .y_o(d));
    // S8: times fy
    f24_mul u_m (.clk_i, .en_i, .a_i(fy_q[S_M1]), .b_i(d), .y_o(m));
    // S9: the result
    f24_add u_out (.clk_i, .en_i, .a_i(top_q[S_A1]), .b_i(m), .y_o(out[c]));

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        c00_q[S_D0+1] <= c00;
        c10_q[S_D0+1] <= c10;
        for (int s = S_D0 + 2; s <= S_A0; s++) begin
          c00_q[s] <= c00_q[s-1];
          c10_q[s] <= c10_q[s-1];
        end
        top_q[S_D1+1] <= top;
        for (int s = S_D1 + 2; s <= S_A1; s++) top_q[s] <= top_q[s-1];
      end
    end
  end

  if (!ALPHA) begin : g_no_alpha
    logic unused_alpha;                        // the texels' A bytes are not filtered
    assign unused_alpha = ^{t00_i[31:24], t01_i[31:24], t10_i[31:24], t11_i[31:24]};
    assign out[3] = '0;
  end

  assign r_o = out[0];
  assign g_o = out[1];
  assign b_o = out[2];
  assign a_o = out[3];

  // ---- valid and tag ---------------------------------------------------------------------------
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_OUT)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o());

endmodule
