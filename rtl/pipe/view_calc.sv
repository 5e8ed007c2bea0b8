// SPDX-License-Identifier: Apache-2.0
// view_calc: the view-calculation unit (Park et al. 2013, Fig. 6, before FIFO #0): a fragment's
// unit world view vector V into tangent space through the triangle's TBN, scaled to the contract
// ray.  Specification: model/view.py (view_calc) in the f24 engine, bit for bit:
//   x = dot(T, V); y = dot(B, V); z = dot(N, V)
//       dot(a, b) = add(add(mul(ax, bx), mul(ay, by)), mul(az, bz))
//   down = -z (sign flip, exact); k = div(D, down)
//   du = mul(x, k); dv = mul(y, k); seg = k
//   where not (down > 0) (z >= 0, either zero, or NaN): du = dv = seg = NaN (0x7F8000)
//
// Fully pipelined, fixed latency pipe_pkg::view_calc_lat(ADD_LAT, MUL_LAT) enabled clocks (17 at
// the float units' paper depths (ADD_LAT, MUL_LAT) = (2, 1), pipe_pkg::VIEW_CALC_LAT; 21 at
// (3, 2)), one fragment every 4th enabled clock at most: z, x and y share one dot-product
// datapath in consecutive clocks (valid_i must not be 1 within 3 enabled clocks after a
// fragment; asserted: spacing; dm_pipeline admits a fragment every 4th clock at most, the rate
// its back end takes hits at).  Every register (valid, tag, data, the float units) advances
// only while en_i is 1, so the enclosing pipeline stalls the whole unit with en_i = 0.  A
// fragment is taken on an enabled edge with valid_i = 1; its result shows at valid_o / tag_o /
// du_o / dv_o / seg_o after that many enabled edges and holds while en_i is 0.  valid is reset
// by rst_ni (synchronous, active low, independent of en_i); data registers have no reset.
// cfg_depth_i must be static while busy.
//
// Sharing.  A shared float unit serves the operations of a fragment in consecutive stages (at
// most 3 apart), so with fragments 4 or more enabled clocks apart two fragments never ask for
// one unit in the same clock, at any unit latency; no phase alignment is needed.  The one
// register that holds a fragment's word across more than one clock of a later fragment's
// schedule is the scale register ks_q: loaded in S_KS, read as seg in S_KS + MUL_LAT + 2, so
// MUL_LAT + 2 <= 4 (MUL_LAT 1 or 2; checked at elaboration).  No float unit takes an operand
// through a select: the dot-product multipliers' column operands are registers (col_q) loaded
// by the select in the clock before each product, a unit fed by one source (the view vector's
// register, a unit's result register, a delay register) takes it directly.
//
// Stage schedule (S0 = the input ports; "@a": the unit works on its operands in Sa; A = ADD_LAT,
// M = MUL_LAT).  The divider is the pipelined one, f24_div #(.LAT(F24_DIV_LAT)) with
// f24_pkg::F24_DIV_LAT = 8 (the stage numbers below are for 8; "a / b": a at (A, M) = (2, 1),
// b at (3, 2)).
//   S0                  col_q[i] <- N[i] (the ports); T, B -> hold registers; vv_q[i] <- V[i]
//   S1, S2              col_q[i] <- T[i], then B[i] (from the hold registers)   registers
//   S_PROD = 1          products mul(col_q[i], vv_q[i]): N.V @1, T.V @2,
//                       B.V @3                                                  f24_mul x3
//   S_SUM1 = 1+M        p0 + p1: z, x, y in consecutive clocks (2 / 3; direct
//                       from the multipliers); p2 delayed A clocks             f24_add
//   S_SUM2 = S_SUM1+A   (p0 + p1) + p2: z, x, y (4 / 6)                        f24_add
//   S_DIV = S_SUM2+A    down = -z; ok = down > 0 (sign 0, exponent not 0, not NaN);
//                       k = div(D, down) (6 / 9; direct from the second adder)  f24_div
//                       x delayed S_DIV+1 -> S_KS, y a clock behind (one delay line),
//                       ok S_DIV -> S_KS
//   S_KS = S_DIV+8      ks_q <- ok ? k : NaN (held for y and seg); sa_q <- x, then y
//                       (14 / 17)                                               registers
//   S_MUL = S_KS+1      du = mul(x, ks), dv = mul(y, ks) a clock later (15 / 18) f24_mul
//   S_DU = S_MUL+M      du held (16 / 20)
//   S_OUT = S_DU+1      outputs (17 / 21; straight from registers: du held, dv, ks = seg)
// Float units: 4 f24_mul, 2 f24_add, 1 f24_div (7, 4, 1 at one fragment per 2 clocks with x and
// y sharing; 11, 6, 1 at one per clock): three multipliers for the nine products, one for the
// two scale multiplies.  Three multipliers would need the fragments aligned to a phase (hold
// registers for the words and the results, as in shade_unit), since the scale multiplies come
// 12 to 15 stages after the products (15 to 18 at (3, 2)).  Applying the NaN of an unusable
// view by forcing the multiplier's operand k to NaN gives exactly the model's NaN (every NaN a
// unit produces is 0x7F8000) and keeps the outputs free of logic after the registers.
module view_calc
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W   = 8,  // side-band bits (fragment id, pixel, ...) carried
                                       // unchanged from tag_i to tag_o alongside the fragment
  // Latencies of the float units instantiated (their LAT parameters); the stage schedule and the
  // latency, pipe_pkg::view_calc_lat(ADD_LAT, MUL_LAT), follow them; the words do not change.
  parameter int unsigned ADD_LAT = F24_ADD_LAT,  // f24_add, 2 .. 4
  parameter int unsigned MUL_LAT = F24_MUL_LAT   // f24_mul, 1 .. 2 (the scale register's hold)
) (
  input  logic             clk_i,
  input  logic             rst_ni,       // synchronous, active low: clears the valid bits
  input  logic             en_i,         // clock enable of the whole pipeline (0 = stall)
  input  f24_t             cfg_depth_i,  // D, the depth scale (texels per unit depth); static while busy
  input  logic             valid_i,
  input  logic [TAG_W-1:0] tag_i,
  input  f24_t             tx_i,         // T, the TBN's first column
  input  f24_t             ty_i,
  input  f24_t             tz_i,
  input  f24_t             bx_i,         // B, the second column
  input  f24_t             by_i,
  input  f24_t             bz_i,
  input  f24_t             nx_i,         // N, the third column
  input  f24_t             ny_i,
  input  f24_t             nz_i,
  input  f24_t             vx_i,         // V, the unit world view vector (eye towards surface)
  input  f24_t             vy_i,
  input  f24_t             vz_i,
  output logic             valid_o,
  output logic [TAG_W-1:0] tag_o,
  output f24_t             du_o,         // texels moved along u per unit of depth t
  output f24_t             dv_o,         // along v
  output f24_t             seg_o         // world length of the eye ray per unit of t
);

  // Stage numbers ("a / b": at (ADD_LAT, MUL_LAT) = (2, 1) / (3, 2)); S_OUT = the latency.
  localparam int unsigned SPACING = 4;                  // enabled clocks between fragments, min.
  localparam int unsigned S_PROD = 1;                   // 1: the products (z; x, y after it)
  localparam int unsigned S_SUM1 = S_PROD + MUL_LAT;    // 2 / 3: the first sums
  localparam int unsigned S_SUM2 = S_SUM1 + ADD_LAT;    // 4 / 6: the second sums
  localparam int unsigned S_DIV  = S_SUM2 + ADD_LAT;    // 6 / 9: z; the divider
  localparam int unsigned S_X    = S_DIV + 1;           // 7 / 10: x (y a clock later)
  localparam int unsigned S_KS   = S_DIV + F24_DIV_LAT; // 14 / 17: k; the scale's operand regs
  localparam int unsigned S_MUL  = S_KS + 1;            // 15 / 18: du (dv a clock later)
  localparam int unsigned S_DU   = S_MUL + MUL_LAT;     // 16 / 20: du held
  localparam int unsigned S_OUT  = S_DU + 1;            // 17 / 21
  if (S_OUT != view_calc_lat(ADD_LAT, MUL_LAT)) begin : g_check_lat
    $error("view_calc: stage schedule does not add up to pipe_pkg::view_calc_lat");
  end
  // ks_q (loaded in S_KS) is read as seg in S_OUT; the next fragment loads it SPACING clocks on.
  if (S_OUT - S_KS > SPACING) begin : g_check_hold
    $error("view_calc: MUL_LAT must be 1..2 (seg is read from ks_q, held SPACING clocks)");
  end

  // ---- valid bits of the stages (stage_v[s]: a fragment in stage s) and the tag: u_valid_tag ----
  logic [S_OUT:1] stage_v;

  // ---- S0 .. S3: the products, N.V, T.V, B.V on three multipliers -----------------------------
  f24_t col_q [3];                      // the column operand: N (S1), T (S2), B (S3)
  f24_t vv_q  [3];                      // V, held S1 .. S3
  f24_t t_q   [3], b_q [3];             // T and B held for the select
  f24_t prod  [3];                      // mul(col_q[i], vv_q[i])
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      if (valid_i) begin
        col_q <= '{nx_i, ny_i, nz_i};
        vv_q  <= '{vx_i, vy_i, vz_i};
        t_q   <= '{tx_i, ty_i, tz_i};
        b_q   <= '{bx_i, by_i, bz_i};
      end else if (stage_v[S_PROD]) begin
        col_q <= t_q;
      end else begin
        col_q <= b_q;
      end
    end
  end
  for (genvar i = 0; i < 3; i++) begin : g_prod
    f24_mul #(.LAT(MUL_LAT)) u_prod (.clk_i, .en_i, .a_i(col_q[i]), .b_i(vv_q[i]),
                                     .y_o(prod[i]));
  end

  // ---- S_SUM1 .. S_DIV + 2: the sums (z, then x, then y, a clock apart on the same two adders)
  f24_t sum1;                           // p0 + p1: S_SUM2 (z) .. S_SUM2 + 2 (y)
  f24_t p2_q [S_SUM1+1:S_SUM2];         // p2_q[s]: the third product, ADD_LAT clocks on
  f24_t dot;                            // z in S_DIV, x in S_DIV + 1, y in S_DIV + 2
  f24_add #(.LAT(ADD_LAT)) u_sum1 (.clk_i, .en_i, .a_i(prod[0]), .b_i(prod[1]), .y_o(sum1));
  f24_add #(.LAT(ADD_LAT)) u_sum2 (.clk_i, .en_i, .a_i(sum1), .b_i(p2_q[S_SUM2]), .y_o(dot));

  // ---- S_DIV: down, the usability test, the divider ------------------------------------------
  f24_t down;
  logic down_pos;                       // down > 0: positive, nonzero, not NaN (+Inf counts)
  f24_t k;                              // S_KS: div(D, down)
  assign down     = {~dot[23], dot[22:0]};
  assign down_pos = !down[23] && (down[22:16] != 7'd0)
                    && !((down[22:16] == EXP_SPEC) && (down[15:0] != 16'd0));
  f24_div #(.LAT(F24_DIV_LAT)) u_k (.clk_i, .en_i, .a_i(cfg_depth_i), .b_i(down), .y_o(k));

  f24_t xy_q [S_X+1:S_KS];              // x in S_X + 1 .. S_KS, y a clock behind
  logic ok_q [S_DIV+1:S_KS];            // down > 0 in stages S_DIV + 1 .. S_KS

  // ---- S_KS .. S_OUT: scale -------------------------------------------------------------------
  f24_t ks_q;                           // S_MUL .. S_OUT: k, or NaN for an unusable view (= seg)
  f24_t sa_q;                           // S_MUL: x, S_MUL + 1: y
  f24_t dxy;                            // S_DU: du, S_OUT: dv
  f24_t du_q;                           // S_OUT: du held
  f24_mul #(.LAT(MUL_LAT)) u_dxy (.clk_i, .en_i, .a_i(sa_q), .b_i(ks_q), .y_o(dxy));
  assign du_o  = du_q;
  assign dv_o  = dxy;
  assign seg_o = ks_q;

  // ---- delay lines and registers ----------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      p2_q[S_SUM1+1] <= prod[2];
      for (int s = S_SUM1 + 2; s <= S_SUM2; s++) p2_q[s] <= p2_q[s-1];
      xy_q[S_X+1]   <= dot;
      for (int s = S_X + 2; s <= S_KS; s++) xy_q[s] <= xy_q[s-1];
      ok_q[S_DIV+1] <= down_pos;
      for (int s = S_DIV + 2; s <= S_KS; s++) ok_q[s] <= ok_q[s-1];
      // S_KS: ks for the fragment in S_KS, held for its y (S_MUL + 1) and its seg (S_OUT, at
      // most SPACING clocks on): the next fragment reaches S_KS SPACING clocks later at the
      // earliest
      if (stage_v[S_KS]) ks_q <= ok_q[S_KS] ? k : F24_NAN;
      sa_q <= xy_q[S_KS];
      if (stage_v[S_DU]) du_q <= dxy;
    end
  end

  // ---- valid and tag ---------------------------------------------------------------------------
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_OUT)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o(stage_v));

  // The simulation checks are in view_calc_assert.sv (bound into every instance).

endmodule
