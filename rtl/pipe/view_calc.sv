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
// Fully pipelined, fixed latency VIEW_CALC_LAT = 17 enabled clocks (pipe_pkg), one fragment every
// other enabled clock at most: x and y share their float units (valid_i must not be 1 on two
// consecutive enabled clocks; asserted; dm_pipeline admits a fragment every other clock at
// most).  Every register (valid, tag, data, the float units) advances only while en_i is 1, so
// the enclosing pipeline stalls the whole unit with en_i = 0.  A fragment is taken on an enabled
// edge with valid_i = 1; its result shows at valid_o / tag_o / du_o / dv_o / seg_o after 17
// enabled edges and holds while en_i is 0.  valid is reset by rst_ni (synchronous, active low,
// independent of en_i); data registers have no reset.  cfg_depth_i must be static while busy.
//
// Stage schedule (S0 = the input ports; "a -> b": a unit takes operands in Sa, result in Sb).
// The divider is the pipelined one, f24_div #(.LAT(F24_DIV_LAT)) with f24_pkg::F24_DIV_LAT = 8;
// everything after it moves with that latency (the stage numbers below are for 8).  Two lanes
// of three multipliers and two adders: lane N computes z = dot(N, V) from the ports; lane TB
// computes x = dot(T, V) from its operand register one clock later and y = dot(B, V) (B and V
// held) the clock after that.
//   S0  N.V products: mul(N[i], V[i])                              f24_mul x3 S0 -> S1
//       lane TB's operand register <- T, V (B, V held)              register   S0 -> S1
//   S1  z: add(p0, p1); p2 delayed S1 -> S3                         f24_add    S1 -> S3
//       T.V products (S1), B.V products (S2): lane TB              f24_mul x3 S1 -> S2
//   S2  x: add(p0, p1) (S2), y: (S3); p2 delayed 2 clocks           f24_add    S2 -> S4
//   S3  z = add(sx, p2)                                             f24_add    S3 -> S5
//   S4  x = add(sx, p2) (S4 -> S6), y (S5 -> S7)                   f24_add
//   S5  down = -z; ok = down > 0 (sign 0, exponent not 0, not NaN)
//       k = div(D, down)                                            f24_div    S5 -> S13
//       x delayed S6 -> S14, y S7 -> S15, ok S5 -> S13
//   S13 ks = ok ? k : NaN                                           register   S13 -> S14
//       (a register of its own: the select in front of the multipliers cost their fmax)
//   S14 the scale's operands: (x, ks) now, (y, ks) the clock after  register   S14 -> S15
//   S15 du = mul(x, ks) (S15), dv = mul(y, ks) (S16)                f24_mul    S15 -> S16
//   S16 du held; seg = ks delayed S14 -> S17                        register   S16 -> S17
//   S17 outputs (straight from registers)
// Float units: 7 f24_mul, 4 f24_add, 1 f24_div (11, 6 and 1 before x and y shared them, at one
// fragment per clock and VIEW_CALC_LAT 15).  Applying the NaN of an unusable view by forcing
// the multipliers' operand k to NaN gives exactly the model's NaN (every NaN a unit produces is
// 0x7F8000) and keeps the outputs free of logic after the registers.
module view_calc
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W = 8  // side-band bits (fragment id, pixel, ...) carried unchanged
                                    // from tag_i to tag_o alongside the fragment
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

  // Stage numbers (pipe_pkg latencies); S_OUT = VIEW_CALC_LAT.
  localparam int unsigned S_SUM1 = F24_MUL_LAT;           // 1: lane N's first sum
  localparam int unsigned S_SUM2 = S_SUM1 + F24_ADD_LAT;  // 3: lane N's second sum
  localparam int unsigned S_DIV  = S_SUM2 + F24_ADD_LAT;  // 5: z; the divider
  localparam int unsigned S_X    = S_DIV + 1;             // 6: x (lane TB, one clock behind)
  localparam int unsigned S_KS   = S_DIV + F24_DIV_LAT;   // 13
  localparam int unsigned S_SC   = S_KS + 1;              // 14: the scale's operand register
  localparam int unsigned S_MUL  = S_SC + 1;              // 15: du (dv at 16)
  localparam int unsigned S_DU   = S_MUL + F24_MUL_LAT;   // 16: du held
  localparam int unsigned S_OUT  = S_DU + 1;              // 17
  if (S_OUT != VIEW_CALC_LAT) begin : g_check_lat
    $error("view_calc: stage schedule does not add up to VIEW_CALC_LAT");
  end

  // ---- valid bits of the stages (stage_v[s]: a fragment in stage s) and the tag: u_valid_tag ----
  logic [S_OUT:1] stage_v;

  // ---- lane N (S0 -> S5): z = dot(N, V) from the ports -------------------------------------
  // ---- lane TB (S1 -> S6, S2 -> S7): x = dot(T, V), then y = dot(B, V) ---------------------
  f24_t col  [2][3];                    // col[lane][i]: lane N from the ports, lane TB's register
  f24_t vv   [2][3];
  f24_t b_q  [3], v_h_q [3];            // B and V held for the second clock of lane TB
  f24_t prod [2][3];                    // mul(col[l][i], vv[l][i])
  f24_t sum1 [2];
  f24_t p2_q [2][S_SUM1+1:S_SUM2];      // p2_q[l][s]: the third product, two clocks on
  f24_t dot  [2];                       // lane N: z in S5; lane TB: x in S6, y in S7
  assign col[0] = '{nx_i, ny_i, nz_i};
  assign vv[0]  = '{vx_i, vy_i, vz_i};

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      if (valid_i) begin                // T now, B the next enabled clock
        col[1] <= '{tx_i, ty_i, tz_i};
        vv[1]  <= '{vx_i, vy_i, vz_i};
        b_q    <= '{bx_i, by_i, bz_i};
        v_h_q  <= '{vx_i, vy_i, vz_i};
      end else begin
        col[1] <= b_q;
        vv[1]  <= v_h_q;
      end
    end
  end

  for (genvar l = 0; l < 2; l++) begin : g_lane
    for (genvar i = 0; i < 3; i++) begin : g_cmp
      f24_mul u_prod (.clk_i, .en_i, .a_i(col[l][i]), .b_i(vv[l][i]), .y_o(prod[l][i]));
    end
    f24_add u_sum1 (.clk_i, .en_i, .a_i(prod[l][0]), .b_i(prod[l][1]), .y_o(sum1[l]));
    f24_add u_sum2 (.clk_i, .en_i, .a_i(sum1[l]), .b_i(p2_q[l][S_SUM2]), .y_o(dot[l]));
  end

  // ---- S5: down, the usability test, the divider ---------------------------------------------
  f24_t down;
  logic down_pos;                       // down > 0: positive, nonzero, not NaN (+Inf counts)
  f24_t k;                              // S_KS: div(D, down)
  assign down     = {~dot[0][23], dot[0][22:0]};
  assign down_pos = !down[23] && (down[22:16] != 7'd0)
                    && !((down[22:16] == EXP_SPEC) && (down[15:0] != 16'd0));
  f24_div #(.LAT(F24_DIV_LAT)) u_k (.clk_i, .en_i, .a_i(cfg_depth_i), .b_i(down), .y_o(k));

  f24_t xy_q [S_X+1:S_SC];              // lane TB's result: x in S7 .. S14, y a clock behind
  logic ok_q [S_DIV+1:S_KS];            // down > 0 in stages S6 .. S_KS

  // ---- S_SC .. S_OUT: scale -------------------------------------------------------------------
  f24_t ks_q [S_SC:S_OUT];              // k, or NaN for an unusable view, in S14 .. S17
  f24_t sa_q, sb_q;                     // S15: the multiplier's operands (x or y, ks)
  f24_t dxy;                            // S16: du, then dv
  f24_t du_q;                           // S17: du held
  f24_mul u_dxy (.clk_i, .en_i, .a_i(sa_q), .b_i(sb_q), .y_o(dxy));
  assign du_o  = du_q;
  assign dv_o  = dxy;
  assign seg_o = ks_q[S_OUT];

  // ---- delay lines and registers ----------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int l = 0; l < 2; l++) begin
        p2_q[l][S_SUM1+1] <= prod[l][2];
        for (int s = S_SUM1 + 2; s <= S_SUM2; s++) p2_q[l][s] <= p2_q[l][s-1];
      end
      xy_q[S_X+1]   <= dot[1];
      for (int s = S_X + 2; s <= S_SC; s++) xy_q[s] <= xy_q[s-1];
      ok_q[S_DIV+1] <= down_pos;
      for (int s = S_DIV + 2; s <= S_KS; s++) ok_q[s] <= ok_q[s-1];
      ks_q[S_SC] <= ok_q[S_KS] ? k : F24_NAN;
      for (int s = S_SC + 1; s <= S_OUT; s++) ks_q[s] <= ks_q[s-1];
      // S14: x with ks for a fragment in S14; the clock after, y (which runs a clock behind x,
      // so it is in the same register then) with the fragment's ks, one stage on by then
      sa_q <= xy_q[S_SC];
      sb_q <= stage_v[S_SC] ? ks_q[S_SC] : ks_q[S_SC+1];
      if (stage_v[S_DU]) du_q <= dxy;
    end
  end

  // ---- valid and tag ---------------------------------------------------------------------------
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_OUT)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o(stage_v));

  // The simulation checks are in view_calc_assert.sv (bound into every instance).

endmodule
