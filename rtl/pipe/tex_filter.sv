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
// the other clocks waits one enabled clock.  Fixed latency S_OUT =
// pipe_pkg::tex_filter_lat(ADD_LAT, MUL_LAT) enabled clocks at the f24_add / f24_mul depths
// ADD_LAT, MUL_LAT: 15 at (2, 1) (pipe_pkg's TEX_FILTER_LAT at the package defaults), 21 at
// (3, 2); a lookup taken on an edge shows at the outputs after S_OUT enabled edges and holds
// while en_i is 0.  The rate (a lookup every other enabled clock) is the same at every depth.
// Every register advances only while en_i is 1 (the enclosing pipeline's stall; nothing is taken
// then); valid and ph_q are reset by rst_ni (synchronous, active low, whatever en_i is); data
// registers have no reset.
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
// from different units' outputs, so a 2:1 select by sv[S_D1 - 1] loads its operand registers (a
// lookup in S_D1 - 1: the first operation, else the second).  With that select in front of the
// adder instead (12 clocks) the block placed out of context at 80.5 MHz, an adder's first stage
// behind the select, against 93.4 before the sharing.  The operand registers put the two operations
// ADD_LAT + MUL_LAT + 1 clocks apart (add, multiply, register): 4 at (2, 1), 6 at (3, 2); when
// that is even m waits M_DLY = (ADD_LAT + MUL_LAT) % 2 = 1 clock more (5, 7 apart), a register
// made only at the depths that need it.
// A phase toggle rather than "not in the clock after a take": lookups 3, 5, ... clocks apart
// would need hold registers and input selects (about 176 bits) to realign them, which cost more
// LUTs than the clock a lookup may wait in the texture cache's output buffer.
//
// Stage schedule per channel (S0 = the input ports; "a -> b": a unit takes operands in Sa, result
// in Sb; "@a / @b": a unit's two operations; the stage numbers at (ADD_LAT, MUL_LAT) = (2, 1),
// then (3, 2)):
//   S0    c00 = from_unorm(t00) @0 / c10 = from_unorm(t10) @1   f24_from_unorm -> S1 / S2
//         c01 = from_unorm(t01) @0 / c11 = from_unorm(t11) @1   f24_from_unorm -> S1 / S2
//         (the codes of t10, t11 held a clock in registers); fx delayed S0 -> S_M0 - 1 and held
//         there for S_M0, S_M0 + 1; fy delayed S0 -> S_M1; c00, c10 (a stream) delayed
//         S1 / S2 -> S_A0 / S_A0 + 1
//   S_D0  = 1 (1, 1): d0 = sub(c01, c00) / d1 = sub(c11, c10)   f24_add        -> S_M0
//   S_M0  = S_D0 + ADD_LAT (3, 4): m0 = mul(fx, d0) / m1 = mul(fx, d1)
//                                                               f24_mul        -> S_A0
//   S_A0  = S_M0 + MUL_LAT (4, 6): top = add(c00, m0) / bot = add(c10, m1)
//                                                               f24_add        -> S_D1 - 2
//         top delayed S_D1 - 2 -> S_A1 - 1
//   S_D1 - 1 (7, 10) / S_A1 - 1 (12, 17): the last adder's operand registers: bot, -top / top, m
//                                                               reg            -> S_D1 / S_A1
//   S_D1  = S_A0 + ADD_LAT + 2 (8, 11): d = sub(bot, top)        f24_add        -> S_M1
//   S_M1  = S_D1 + ADD_LAT (10, 14): m = mul(fy, d)              f24_mul        -> S_M1 + MUL_LAT
//         m delayed M_DLY (1, 1) clocks to S_A1 - 1
//   S_A1  = S_M1 + MUL_LAT + 1 + M_DLY (13, 18): out = add(top, m)
//                                                               f24_add        -> S_OUT
//   S_OUT = S_A1 + ADD_LAT (15, 21): outputs (straight from the last adder's registers)
// S_OUT = 1 + 4 ADD_LAT + 2 MUL_LAT + 3 + M_DLY: one unit per operation, the bottom row a clock
// behind the top row on the same units, the operand registers and m's parity clock.
// Float units per channel: 2 f24_from_unorm, 3 f24_add #(.LAT(ADD_LAT)), 2 f24_mul
// #(.LAT(MUL_LAT)) (3 or 4 channels); before the sharing 4, 6 and 3.  Every unit but the fy
// multiplier serves two operations (fully used at one lookup per two clocks).
module tex_filter
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned ADD_LAT = F24_ADD_LAT,  // f24_add latency (2 .. 4: the three adders)
  parameter int unsigned MUL_LAT = F24_MUL_LAT,  // f24_mul latency (1 .. 3: the two multipliers)
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

  // Stage numbers (from ADD_LAT, MUL_LAT; at (2, 1), then (3, 2)); S_OUT =
  // pipe_pkg::tex_filter_lat(ADD_LAT, MUL_LAT).  Each shared unit's first operation is in the
  // stage named here, its second in the stage after (S_D1's: S_A1).
  localparam int unsigned S_D0  = F24_FROM_UNORM_LAT;           // 1, 1: row differences
  localparam int unsigned S_M0  = S_D0 + ADD_LAT;               // 3, 4: times fx
  localparam int unsigned S_A0  = S_M0 + MUL_LAT;               // 4, 6: top, bot
  localparam int unsigned S_D1  = S_A0 + 1 + ADD_LAT + 1;       // 8, 11: bot - top (bot a clock
                                                                //   later; operand register)
  localparam int unsigned S_M1  = S_D1 + ADD_LAT;               // 10, 14: times fy
  // m's delay: the operand registers put the last adder's operations ADD_LAT + MUL_LAT + 1
  // clocks apart (add, multiply, register); M_DLY makes that odd.
  localparam int unsigned M_DLY = (ADD_LAT + MUL_LAT) % 2;      // 1, 1
  localparam int unsigned S_A1  = S_M1 + MUL_LAT + 1 + M_DLY;   // 13, 18: top + ... (m delayed
                                                                //   M_DLY; operand register)
  localparam int unsigned S_OUT = S_A1 + ADD_LAT;               // 15, 21
  if (ADD_LAT < 2 || MUL_LAT < 1) begin : g_check_units
    $error("tex_filter: ADD_LAT must be at least 2 and MUL_LAT at least 1");
  end
  if (S_OUT != tex_filter_lat(ADD_LAT, MUL_LAT)) begin : g_check_lat
    $error("tex_filter: stage schedule does not add up to pipe_pkg::tex_filter_lat");
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
  f24_t fx_q [1:S_M0-1];                       // fx in stages S1 .. S_M0 - 1
  f24_t fxh_q;                                 // fx in S_M0 and S_M0 + 1
  f24_t fy_q [1:S_M1];                         // fy in stages S1 .. S_M1

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
    f24_t dr;                                  // d0 (S_M0), d1 (S_M0 + 1)
    f24_t mr;                                  // m0 (S_A0), m1 (S_A0 + 1)
    f24_t tb;                                  // top (S_D1 - 2), bot (S_D1 - 1)
    f24_t dm_out;                              // d (S_M1), out (S_OUT)
    f24_t m;                                   // S_M1 + MUL_LAT
    f24_t m_op;                                // m in S_A1 - 1 (the operand select's input)
    f24_t cl_q  [S_D0+1:S_A0];                 // the stream c00, c10: c00 in S2 .. S_A0
    f24_t top_q [S_D1-1:S_A1-1];               // top in stages S_D1 - 1 .. S_A1 - 1
    f24_t oa_q, ob_q;                          // the last adder's operands: S_D1 and S_A1

    always_ff @(posedge clk_i) begin
      if (en_i) begin
        k10_q <= t10_i[8*c +: 8];
        k11_q <= t11_i[8*c +: 8];
        cl_q[S_D0+1] <= cl;
        for (int s = S_D0 + 2; s <= S_A0; s++) cl_q[s] <= cl_q[s-1];
        top_q[S_D1-1] <= tb;
        for (int s = S_D1; s <= S_A1 - 1; s++) top_q[s] <= top_q[s-1];
        // the last adder's operands: bot, -top (a lookup in S_D1 - 1), else top, m (S_A1 - 1)
        oa_q <= sv[S_D1-1] ? tb : top_q[S_A1-1];
        ob_q <= sv[S_D1-1] ? {~top_q[S_D1-1][23], top_q[S_D1-1][22:0]} : m_op;
      end
    end

    // m, delayed M_DLY clocks (S_M1 + MUL_LAT -> S_A1 - 1) for the parity of the last adder
    if (M_DLY == 0) begin : g_m_now
      assign m_op = m;
    end else begin : g_m_dly
      f24_t m_q;                               // m a clock later
      always_ff @(posedge clk_i) begin
        if (en_i) m_q <= m;
      end
      assign m_op = m_q;
    end

    // S0 / S1: the codes of the top row from the ports, those of the bottom row a clock later
    // from the hold registers (no lookup is taken while one is in S1)
    f24_from_unorm #(.W(8)) u_cl (.clk_i, .en_i, .k_i(sv[1] ? k10_q : t00_i[8*c +: 8]),
                                  .y_o(cl));
    f24_from_unorm #(.W(8)) u_cr (.clk_i, .en_i, .k_i(sv[1] ? k11_q : t01_i[8*c +: 8]),
                                  .y_o(cr));
    // S_D0 / S_D0 + 1: differences along u (subtract: flip the sign bit)
    f24_add #(.LAT(ADD_LAT)) u_dr (.clk_i, .en_i, .a_i(cr), .b_i({~cl[23], cl[22:0]}), .y_o(dr));
    // S_M0 / S_M0 + 1: times fx
    f24_mul #(.LAT(MUL_LAT)) u_mr (.clk_i, .en_i, .a_i(fxh_q), .b_i(dr), .y_o(mr));
    // S_A0 / S_A0 + 1: the two rows
    f24_add #(.LAT(ADD_LAT)) u_tb (.clk_i, .en_i, .a_i(cl_q[S_A0]), .b_i(mr), .y_o(tb));
    // S_D1: difference along v / S_A1: the result
    f24_add #(.LAT(ADD_LAT)) u_dvo (.clk_i, .en_i, .a_i(oa_q), .b_i(ob_q), .y_o(dm_out));
    // S_M1: times fy
    f24_mul #(.LAT(MUL_LAT)) u_m (.clk_i, .en_i, .a_i(fy_q[S_M1]), .b_i(dm_out), .y_o(m));

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
