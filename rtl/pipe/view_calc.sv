// view_calc: the view-calculation unit (Park et al. 2013, Fig. 6, before FIFO #0): a fragment's
// unit world view vector V into tangent space through the triangle's TBN, scaled to the contract
// ray.  Specification: model/view.py (view_calc) in the f24 engine, bit for bit:
//   x = dot(T, V); y = dot(B, V); z = dot(N, V)
//       dot(a, b) = add(add(mul(ax, bx), mul(ay, by)), mul(az, bz))
//   down = -z (sign flip, exact); k = div(D, down)
//   du = mul(x, k); dv = mul(y, k); seg = k
//   where not (down > 0) (z >= 0, either zero, or NaN): du = dv = seg = NaN (0x7F8000)
//
// Fully pipelined, fixed latency VIEW_CALC_LAT = 15 enabled clocks (pipe_pkg), one fragment per
// clock.  Every register (valid, tag, data, the float units) advances only while en_i is 1, so
// the enclosing pipeline stalls the whole unit with en_i = 0.  A fragment is taken on an enabled
// edge with valid_i = 1; its result shows at valid_o / tag_o / du_o / dv_o / seg_o after 15
// enabled edges and holds while en_i is 0.  valid is reset by rst_ni (synchronous, active low,
// independent of en_i); data registers have no reset.  cfg_depth_i must be static while busy.
//
// Stage schedule (S0 = the input ports; "a -> b": a unit takes operands in Sa, result in Sb).
// The divider is the pipelined one, f24_div #(.LAT(F24_DIV_LAT)) with f24_pkg::F24_DIV_LAT = 8;
// everything after it moves with that latency (the stage numbers below are for 8):
//   S0  9 products T.V, B.V, N.V: mul(col[i], V[i])                f24_mul  S0 -> S1
//   S1  sx = add(p0, p1) per column                                  f24_add  S1 -> S3
//       p2 per column delayed S1 -> S3 (2 registers)
//   S3  x, y, z = add(sx, p2)                                       f24_add  S3 -> S5
//   S5  down = -z; ok = down > 0 (sign 0, exponent not 0, not NaN)
//       k = div(D, down)                                            f24_div  S5 -> S13
//       x, y delayed S5 -> S14 (9 registers), ok S5 -> S13
//   S13 ks = ok ? k : NaN                                           register S13 -> S14
//       (a register of its own: the select in front of the multipliers cost their fmax)
//   S14 du = mul(x, ks), dv = mul(y, ks) (mul(., NaN) = NaN)       f24_mul  S14 -> S15
//       seg = ks                                                    register S14 -> S15
//   S15 outputs (straight from registers)
// Float units: 11 f24_mul, 6 f24_add, 1 f24_div.  Applying the NaN of an unusable view by
// forcing the multipliers' operand k to NaN gives exactly the model's NaN (every NaN a unit
// produces is 0x7F8000) and keeps the outputs free of logic after the registers.
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
  localparam int unsigned S_SUM1 = F24_MUL_LAT;           // 1
  localparam int unsigned S_SUM2 = S_SUM1 + F24_ADD_LAT;  // 3
  localparam int unsigned S_DIV  = S_SUM2 + F24_ADD_LAT;  // 5
  localparam int unsigned S_KS   = S_DIV + F24_DIV_LAT;   // 13
  localparam int unsigned S_SCL  = S_KS + 1;              // 14
  localparam int unsigned S_OUT  = S_SCL + F24_MUL_LAT;   // 15
  if (S_OUT != VIEW_CALC_LAT) begin : g_check_lat
    $error("view_calc: stage schedule does not add up to VIEW_CALC_LAT");
  end

  // ---- S0: the nine products ----------------------------------------------------------------
  f24_t col [3][3];  // col[c][i]: component i of column c (T, B, N)
  f24_t vv  [3];
  f24_t prod [3][3]; // S1: mul(col[c][i], vv[i])
  assign col[0] = '{tx_i, ty_i, tz_i};
  assign col[1] = '{bx_i, by_i, bz_i};
  assign col[2] = '{nx_i, ny_i, nz_i};
  assign vv     = '{vx_i, vy_i, vz_i};

  for (genvar c = 0; c < 3; c++) begin : g_col
    for (genvar i = 0; i < 3; i++) begin : g_cmp
      f24_mul u_prod (.clk_i, .en_i, .a_i(col[c][i]), .b_i(vv[i]), .y_o(prod[c][i]));
    end
  end

  // ---- S1: first sums; the third product waits ---------------------------------------------
  f24_t sum1 [3];                       // S3: add(p0, p1)
  f24_t p2_q [3][S_SUM1+1:S_SUM2];      // p2_q[c][s]: the third product in stage s
  f24_t dot  [3];                       // S5: x, y, z
  for (genvar c = 0; c < 3; c++) begin : g_dot
    f24_add u_sum1 (.clk_i, .en_i, .a_i(prod[c][0]), .b_i(prod[c][1]), .y_o(sum1[c]));
    // ---- S3: second sums
    f24_add u_sum2 (.clk_i, .en_i, .a_i(sum1[c]), .b_i(p2_q[c][S_SUM2]), .y_o(dot[c]));
  end

  // ---- S5: down, the usability test, the divider ---------------------------------------------
  f24_t down;
  logic down_pos;                       // down > 0: positive, nonzero, not NaN (+Inf counts)
  f24_t k;                              // S_KS: div(D, down)
  assign down     = {~dot[2][23], dot[2][22:0]};
  assign down_pos = !down[23] && (down[22:16] != 7'd0)
                    && !((down[22:16] == EXP_SPEC) && (down[15:0] != 16'd0));
  f24_div #(.LAT(F24_DIV_LAT)) u_k (.clk_i, .en_i, .a_i(cfg_depth_i), .b_i(down), .y_o(k));

  f24_t x_q  [S_DIV+1:S_SCL];           // x, y in stages S6 .. S_SCL
  f24_t y_q  [S_DIV+1:S_SCL];
  logic ok_q [S_DIV+1:S_KS];            // down > 0 in stages S6 .. S_KS

  // ---- S_SCL: scale -----------------------------------------------------------------------------
  f24_t ks_q;                           // S_SCL: k, or NaN for an unusable view
  f24_t seg_q;                          // S_OUT
  f24_mul u_du (.clk_i, .en_i, .a_i(x_q[S_SCL]), .b_i(ks_q), .y_o(du_o));
  f24_mul u_dv (.clk_i, .en_i, .a_i(y_q[S_SCL]), .b_i(ks_q), .y_o(dv_o));
  assign seg_o = seg_q;

  // ---- delay lines and the S_SCL -> S_OUT register -------------------------------------------
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      for (int c = 0; c < 3; c++) begin
        p2_q[c][S_SUM1+1] <= prod[c][2];
        for (int s = S_SUM1 + 2; s <= S_SUM2; s++) p2_q[c][s] <= p2_q[c][s-1];
      end
      x_q[S_DIV+1]  <= dot[0];
      y_q[S_DIV+1]  <= dot[1];
      ok_q[S_DIV+1] <= down_pos;
      for (int s = S_DIV + 2; s <= S_SCL; s++) begin
        x_q[s] <= x_q[s-1];
        y_q[s] <= y_q[s-1];
      end
      for (int s = S_DIV + 2; s <= S_KS; s++) ok_q[s] <= ok_q[s-1];
      ks_q  <= ok_q[S_KS] ? k : F24_NAN;
      seg_q <= ks_q;
    end
  end

  // ---- valid and tag ---------------------------------------------------------------------------
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_OUT)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o);

endmodule
