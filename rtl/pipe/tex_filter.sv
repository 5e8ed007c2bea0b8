// SPDX-License-Identifier: Apache-2.0
// tex_filter: the bilinear filter of the texture path (Park et al. 2013, Fig. 6, after the
// texture cache): four RGBA unorm8 texels and the two weights of tex_addr in, the filtered
// channels out, one lookup every other clock at most.  Specification: model/texture.py
// filter_texels (steps 6-7 of the module docstring's "Bilinear lookup at level L") in the f24
// engine, bit for bit, per channel:
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
// Handshake and timing: a lookup is taken on a clock edge with valid_i && ready_o; the driver
// holds it (valid_i and the data) until then.  ready_o = en_i && !ph_q, where ph_q toggles on
// every enabled clock (reset to 0): it never depends on valid_i, and with en_i = 1 (dm_pipeline)
// it is a register.  So a lookup is taken on every other enabled clock at most, and one offered on
// the other clocks waits one enabled clock.  Fixed latency TEX_FILTER_LAT = 15 enabled clocks
// (pipe_pkg): a lookup taken on an edge shows at the outputs after 15 enabled edges and holds
// while en_i is 0.  Every register advances only while en_i is 1 (the enclosing pipeline's
// stall; nothing is taken then); valid and ph_q are reset by rst_ni (synchronous, active low,
// whatever en_i is); data registers have no reset.
//
// Alignment (as in shade_unit): a lookup is taken only when ph_q = 0, so every two lookups in the
// unit are an even number of enabled clocks apart, a lookup in stage k means ph_q = k mod 2
// (asserted: core_aligned), and a float unit serves two operations of a lookup whose stages
// differ by an odd number: lookup p at Sa and Sb, any later lookup at Sa + 2j and Sb + 2j, never
// in the same clock (asserted: shared_free).  Every adder and multiplier takes its operands from
// registers, as before the sharing: the adders and the fx multiplier of the rows take their two
// operations in consecutive stages as streams (one value in Sa, the other in Sa + 1, through the
// same registers); the conversions select the ports or the bottom row's held codes by sv[1] (a
// conversion is short: 200 MHz alone); the last adder's two operations (bot - top, top + m) come
// from different units' outputs, so a 2:1 select by sv[7] loads its operand registers (a lookup
// in S7: the first operation, else the second).  With that select in front of the adder instead
// (12 clocks) the block placed out of context at 80.5 MHz, an adder's first stage behind the
// select, against 93.4 before the sharing.  The operand registers put the two operations 4
// clocks apart (add, multiply, register), an even number, so m waits a clock more (5 apart).
// A phase toggle rather than "not in the clock after a take": lookups 3, 5, ... clocks apart
// would need hold registers and input selects (about 176 bits) to realign them, which cost more
// LUTs than the clock a lookup may wait in the texture cache's output buffer.
//
// Stage schedule per channel (S0 = the input ports; "a -> b": a unit takes operands in Sa, result
// in Sb; "@a / @b": a unit's two operations):
//   S0  c00 = from_unorm(t00) @0 / c10 = from_unorm(t10) @1     f24_from_unorm   -> S1 / S2
//       c01 = from_unorm(t01) @0 / c11 = from_unorm(t11) @1     f24_from_unorm   -> S1 / S2
//       (the codes of t10, t11 held a clock in registers); fx delayed S0 -> S3 and held there for
//       S4; fy delayed S0 -> S10; c00, c10 (a stream) delayed S1 / S2 -> S4 / S5
//   S1  d0 = sub(c01, c00) @1 / d1 = sub(c11, c10) @2            f24_add          -> S3 / S4
//   S3  m0 = mul(fx, d0) @3 / m1 = mul(fx, d1) @4                f24_mul          -> S4 / S5
//   S4  top = add(c00, m0) @4 / bot = add(c10, m1) @5            f24_add          -> S6 / S7
//       top delayed S6 -> S12
//   S7  the last adder's operand registers: bot, -top @7 / top, m @12         reg -> S8 / S13
//   S8  d = sub(bot, top) @8 / out = add(top, m) @13             f24_add          -> S10 / S15
//   S10 m = mul(fy, d) @10                                       f24_mul          -> S11
//       m delayed S11 -> S12
//   S15 outputs (straight from the last adder's registers)
// 15 clocks: the 11 of one unit per operation, the bottom row a clock behind the top row on the
// same units, the operand registers and m's extra clock.
// Float units per channel: 2 f24_from_unorm, 3 f24_add, 2 f24_mul (3 or 4 channels); before the
// sharing 4, 6 and 3.  Every unit but the fy multiplier serves two operations (fully used at one
// lookup per two clocks).
module tex_filter
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W = 8,     // side-band bits carried from tag_i to tag_o
  parameter bit          ALPHA = 1'b0   // 1: filter A too (a_o); 0: R, G, B only
) (
  input  logic               clk_i,
  input  logic               rst_ni,   // synchronous, active low: clears the valid bits, ph_q
  input  logic               en_i,     // clock enable of the whole unit (0 = stall)
  input  logic               valid_i,
  output logic               ready_o,  // a lookup is taken on an edge with valid_i && ready_o
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

  // Stage numbers (pipe_pkg latencies); S_OUT = TEX_FILTER_LAT.  Each shared unit's first
  // operation is in the stage named here, its second in the stage after (S_D1's: S_A1).
  localparam int unsigned S_D0  = F24_FROM_UNORM_LAT;           // 1: row differences
  localparam int unsigned S_M0  = S_D0 + F24_ADD_LAT;           // 3: times fx
  localparam int unsigned S_A0  = S_M0 + F24_MUL_LAT;           // 4: top, bot
  localparam int unsigned S_D1  = S_A0 + 1 + F24_ADD_LAT + 1;   // 8: bot - top (bot a clock
                                                                //    later; operand register)
  localparam int unsigned S_M1  = S_D1 + F24_ADD_LAT;           // 10: times fy
  localparam int unsigned S_A1  = S_M1 + F24_MUL_LAT + 2;       // 13: top + ... (m delayed a
                                                                //     clock; operand register)
  localparam int unsigned S_OUT = S_A1 + F24_ADD_LAT;           // 15
  if (S_OUT != TEX_FILTER_LAT) begin : g_check_lat
    $error("tex_filter: stage schedule does not add up to TEX_FILTER_LAT");
  end
  if ((S_A1 - S_D1) % 2 != 1) begin : g_check_parity
    $error("tex_filter: the last adder's two operations must be an odd number of stages apart");
  end

  localparam int unsigned CH = ALPHA ? 4 : 3;  // channels filtered

  // ---- handshake, phase, valid and tag ---------------------------------------------------------
  logic            ph_q;                       // enabled-clock parity: 0 = a lookup may enter
  logic            take;                       // a lookup enters S1 at this edge
  logic [S_OUT:1]  sv;                         // sv[k]: a lookup in stage k

  assign ready_o = en_i && !ph_q;
  assign take    = valid_i && ready_o;

  always_ff @(posedge clk_i) begin
    if (!rst_ni)   ph_q <= 1'b0;
    else if (en_i) ph_q <= !ph_q;
  end

  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_OUT)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i(take), .tag_i, .valid_o, .tag_o, .stage_valid_o(sv));

  // ---- the weights -----------------------------------------------------------------------------
  // fx: delayed to S_M0 - 1, then loaded into fxh_q as the lookup enters S_M0 and held there for
  // S_M0 + 1 too (no lookup is in S_M0 - 1 the clock after).
  f24_t fx_q [1:S_M0-1];                       // fx in stages S1 .. S2
  f24_t fxh_q;                                 // fx in S3 and S4
  f24_t fy_q [1:S_M1];                         // fy in stages S1 .. S10

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      fx_q[1] <= fx_i;
      for (int s = 2; s <= S_M0 - 1; s++) fx_q[s] <= fx_q[s-1];
      if (sv[S_M0-1]) fxh_q <= fx_q[S_M0-1];
      fy_q[1] <= fy_i;
      for (int s = 2; s <= S_M1; s++) fy_q[s] <= fy_q[s-1];
    end
  end

  // ---- per channel -----------------------------------------------------------------------------
  f24_t out [4];

  for (genvar c = 0; c < CH; c++) begin : g_ch
    logic [7:0] k10_q, k11_q;                  // S1: the codes of t10, t11
    f24_t cl;                                  // c00 (S1), c10 (S2)
    f24_t cr;                                  // c01 (S1), c11 (S2)
    f24_t dr;                                  // d0 (S3), d1 (S4)
    f24_t mr;                                  // m0 (S4), m1 (S5)
    f24_t tb;                                  // top (S6), bot (S7)
    f24_t dm_out;                              // d (S10), out (S15)
    f24_t m;                                   // S11
    f24_t m_q;                                 // m in S12
    f24_t cl_q  [S_D0+1:S_A0];                 // the stream c00, c10: c00 in S2 .. S4
    f24_t top_q [S_D1-1:S_A1-1];               // top in stages S7 .. S12
    f24_t oa_q, ob_q;                          // the last adder's operands: S8 and S13

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        k10_q <= t10_i[8*c +: 8];
        k11_q <= t11_i[8*c +: 8];
        cl_q[S_D0+1] <= cl;
        for (int s = S_D0 + 2; s <= S_A0; s++) cl_q[s] <= cl_q[s-1];
        top_q[S_D1-1] <= tb;
        for (int s = S_D1; s <= S_A1 - 1; s++) top_q[s] <= top_q[s-1];
        m_q <= m;
        // the last adder's operands: bot, -top (a lookup in S7), else top, m (in S12)
        oa_q <= sv[S_D1-1] ? tb : top_q[S_A1-1];
        ob_q <= sv[S_D1-1] ? {~top_q[S_D1-1][23], top_q[S_D1-1][22:0]} : m_q;
      end
    end

    // S0 / S1: the codes of the top row from the ports, those of the bottom row a clock later
    // from the hold registers (no lookup is taken while one is in S1)
    f24_from_unorm #(.W(8)) u_cl (.clk_i, .en_i, .k_i(sv[1] ? k10_q : t00_i[8*c +: 8]),
                                  .y_o(cl));
    f24_from_unorm #(.W(8)) u_cr (.clk_i, .en_i, .k_i(sv[1] ? k11_q : t01_i[8*c +: 8]),
                                  .y_o(cr));
    // S1 / S2: differences along u (subtract: flip the sign bit)
    f24_add u_dr (.clk_i, .en_i, .a_i(cr), .b_i({~cl[23], cl[22:0]}), .y_o(dr));
    // S3 / S4: times fx
    f24_mul u_mr (.clk_i, .en_i, .a_i(fxh_q), .b_i(dr), .y_o(mr));
    // S4 / S5: the two rows
    f24_add u_tb (.clk_i, .en_i, .a_i(cl_q[S_A0]), .b_i(mr), .y_o(tb));
    // S8: difference along v / S13: the result
    f24_add u_dvo (.clk_i, .en_i, .a_i(oa_q), .b_i(ob_q), .y_o(dm_out));
    // S10: times fy
    f24_mul u_m (.clk_i, .en_i, .a_i(fy_q[S_M1]), .b_i(dm_out), .y_o(m));

    assign out[c] = dm_out;
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

  // The simulation checks are in tex_filter_assert.sv (bound into every instance).

endmodule
