// tex_addr: the texture address calculation of the texture path (Park et al. 2013, Fig. 6, after
// the MIP-level unit): one bilinear lookup per clock, the four texel byte addresses and the two
// weights.  Specification: model/texture.py lookup_addresses (steps 1-5 of the module docstring's
// "Bilinear lookup at level L") in the f24 engine, bit for bit:
//   ut = mul(u, su);  vt = mul(v, sv)                      su, sv: the texture's scale words
//   x = sub(mul(ut, 2^-L), 0.5);  y = sub(mul(vt, 2^-L), 0.5)
//   j0 = to_index(x);  i0 = to_index(y)                    floor, W = 20, saturating, NaN -> 0
//   fx = sub(x, from_int(j0));  fy = sub(y, from_int(i0))
//   j1 = clamp(j0 + 1, 0, W_L - 1), j0 = clamp(j0, 0, W_L - 1); i0, i1 likewise with H_L
//   addr(i, j) = base + level_off[L] + 4 (i W_L + j)        (modulo 2^ADDR_W)
//   outputs: addr(i0, j0), addr(i0, j1), addr(i1, j0), addr(i1, j1), fx, fy
// to_index and from_int are f24_to_index / f24_from_int with W = TEX_IDX_W = 20 =
// model.arith.INDEX_W: exactly F24Arith.to_index (floor(clip(x, -2^19, 2^19 - 1)), NaN -> 0)
// and F24Arith.from_int (RNE to 17 bits).  So NaN u gives j0 = 0 and fx = NaN; +Inf gives
// j0 = 2^19 - 1 and fx = +Inf; a huge finite x saturates j0 and fx = x - from_int(j0) is whatever
// the model computes (not in [0, 1]); the addresses are always those of clamped texels.
//
// mul(ut, 2^-L) is exponent arithmetic (f24_pow2_down below), without a register in front of the
// subtract's adder: for every pattern a and 0 <= L <= 15 it gives the bits of f24_mul(a, 2^-L)
// (the product is exact unless it falls below 2^-62, where f24_mul flushes to a signed zero;
// Inf stays Inf, NaN gives F24_NAN, zeros and subnormal patterns give a signed zero).
//
// Fully pipelined, fixed latency TEX_ADDR_LAT = 8 enabled clocks (pipe_pkg), one lookup per clock,
// the conventions of view_calc: every register advances only while en_i is 1 (the enclosing
// pipeline's stall), valid is reset by rst_ni (synchronous, active low), data registers have no
// reset; a lookup taken on an enabled edge with valid_i = 1 shows at the outputs after 8 enabled
// edges and holds while en_i is 0.  Configuration (cfg_*) must be static while busy.
//
// Configuration of each of NTEX textures (model.texture.Texture; index t of every cfg_* array is
// texture t): su, sv = Texture.scale_for (engine words), per level k < TEX_LEVELS its width W_k
// and height H_k (1 .. 32768; level_sizes), the base byte address and per-level byte offsets
// (Texture.level_offsets).  Only levels 0 .. levels - 1 of a texture are meaningful: level_i
// comes from mip_level, clamped to levels - 1 <= TEX_LEVELS - 1 (a level_i above TEX_LEVELS - 1
// is read as TEX_LEVELS - 1).
//
// Textures sharing the unit (NTEX > 1): each lookup names its texture with tex_i, which travels
// down the pipeline with the level; each stage reads the configuration of its own lookup's
// texture (su, sv in S0, W_L and H_L in S4, base and level_off in S5), so lookups of different
// textures may follow each other clock by clock.  dm_pipeline uses one unit for the colour
// texture (0) and the normal map (1).  A tex_i of NTEX or more reads texture NTEX - 1; with NTEX
// = 1 tex_i is ignored.  With NTEX > 1 the inputs and the selected scales are registered first,
// so the latency is TEX_ADDR_LAT + 1 (the stage numbers below count from that register).
//
// Stage schedule (S0 = the input ports; "a -> b": a unit takes operands in Sa, result in Sb):
//   S0  ut = mul(u, su), vt = mul(v, sv)  (su, sv of texture tex_i) 2 f24_mul       S0 -> S1
//       L (saturated to 0 .. 15) and the texture delayed S0 -> S5
//   S1  ut 2^-L, vt 2^-L (exponent arithmetic, in a register of its own: in front of the
//       adder it cost the adder's clock)                             register        S1 -> S2
//   S2  x = add(ut 2^-L, -0.5), y likewise                           2 f24_add       S2 -> S4
//   S4  j0 = floor(x), i0 = floor(y)                                2 f24_to_index  S4 -> S5
//       x, y delayed S4 -> S6; W_L, H_L read                        register        S4 -> S5
//   S5  from_int(j0), from_int(i0)                                  2 f24_from_int  S5 -> S6
//       clamps: j0c, dj = j1c - j0c (0 or 1), i0c, di; base + level_off[L]   register S5 -> S6
//   S6  fx = add(x, -from_int(j0)), fy likewise                     2 f24_add       S6 -> S8
//       r = i0c W_L + j0c; rs = di ? W_L : 0                         register        S6 -> S7
//   S7  addr = base + off + 4 (r + {0, dj, rs, rs + dj})             register        S7 -> S8
//   S8  outputs (straight from registers)
// Float units: 2 f24_mul, 4 f24_add, 2 f24_to_index, 2 f24_from_int; one 16 x 16 multiplier
// (the second row's address is the first's plus 4 W_L: i1c - i0c is 0 or 1).
module tex_addr
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W  = 8,          // side-band bits carried from tag_i to tag_o
  parameter int unsigned ADDR_W = TEX_ADDR_W, // byte address width (addresses wrap modulo 2^ADDR_W)
  parameter int unsigned NTEX   = 1,          // textures sharing the unit (lookups pick by tex_i)
  parameter int unsigned SEL_W  = (NTEX > 1) ? $clog2(NTEX) : 1  // tex_i width
) (
  input  logic                                 clk_i,
  input  logic                                 rst_ni,           // synchronous, active low: valid
  input  logic                                 en_i,             // clock enable (0 = stall)
  // configuration of the textures (static while busy), [t] = texture t
  input  f24_t [NTEX-1:0]                      cfg_su_i,         // u scale: engine(Wt / W)
  input  f24_t [NTEX-1:0]                      cfg_sv_i,         // v scale: engine(Ht / H)
  input  logic [NTEX-1:0][TEX_LEVELS-1:0][TEX_DIM_W-1:0] cfg_width_i,  // W_k of level k, >= 1
  input  logic [NTEX-1:0][TEX_LEVELS-1:0][TEX_DIM_W-1:0] cfg_height_i, // H_k of level k, >= 1
  input  logic [NTEX-1:0][ADDR_W-1:0]          cfg_base_i,       // byte address of the texture
  input  logic [NTEX-1:0][TEX_LEVELS-1:0][ADDR_W-1:0] cfg_level_off_i, // byte offset of level k
  // lookups
  input  logic                                 valid_i,
  input  logic [TAG_W-1:0]                     tag_i,
  input  logic [SEL_W-1:0]                     tex_i,            // the texture (NTEX > 1)
  input  f24_t                                 u_i,              // hit u, v in level-0 texel
  input  f24_t                                 v_i,              // units of the height map
  input  logic [MIP_LEVEL_W-1:0]               level_i,          // level L (mip_level)
  output logic                                 valid_o,
  output logic [TAG_W-1:0]                     tag_o,
  output logic [ADDR_W-1:0]                    addr00_o,         // c00 = T[i0, j0]
  output logic [ADDR_W-1:0]                    addr01_o,         // c01 = T[i0, j1]
  output logic [ADDR_W-1:0]                    addr10_o,         // c10 = T[i1, j0]
  output logic [ADDR_W-1:0]                    addr11_o,         // c11 = T[i1, j1]
  output f24_t                                 fx_o,             // weight along u (j0 -> j1)
  output f24_t                                 fy_o              // weight along v (i0 -> i1)
);

  // Stage numbers (pipe_pkg latencies); S_OUT = TEX_ADDR_LAT.
  localparam int unsigned S_P2  = F24_MUL_LAT;              // 1: 2^-L
  localparam int unsigned S_X   = S_P2 + 1;                 // 2: - 0.5
  localparam int unsigned S_IDX = S_X + F24_ADD_LAT;        // 4: floor; W_L, H_L read
  localparam int unsigned S_CLP = S_IDX + F24_TO_INDEX_LAT; // 5: from_int; clamps
  localparam int unsigned S_FX  = S_CLP + F24_FROM_INT_LAT; // 6: fx; row product
  localparam int unsigned S_SUM = S_FX + 1;                 // 7: address sums
  localparam int unsigned S_OUT = S_FX + F24_ADD_LAT;       // 8
  if (S_OUT != TEX_ADDR_LAT || S_SUM + 1 != S_OUT) begin : g_check_lat
    $error("tex_addr: stage schedule does not add up to TEX_ADDR_LAT");
  end
  if (TEX_IDX_W <= TEX_DIM_W) begin : g_check_w
    $error("tex_addr: the index width must exceed the dimension width");
  end

  localparam f24_t F24_NEG_HALF = 24'hbe0000;  // -0.5
  localparam int unsigned ROW_W = 2 * TEX_DIM_W;  // i W_L + j <= H_L W_L - 1 < 2^(2 TEX_DIM_W)

  typedef logic [TEX_LVL_W-1:0] lvl_t;
  typedef logic [TEX_DIM_W-1:0] dim_t;
  typedef logic signed [TEX_IDX_W-1:0] idx_t;

  // a * 2^-l, bit for bit f24_mul(a, 2^-l) for l <= 15 (2^-l = {0, 63 - l, 0}: the product's
  // significand is a's, exact; its biased exponent e - l; at or below 0 f24_round_pack flushes
  // to a signed zero).  A zero or subnormal operand gives a signed zero, Inf stays, NaN gives
  // F24_NAN.
  function automatic f24_t f24_pow2_down(input f24_t a, input lvl_t l);
    logic [7:0] e;  // biased exponent minus l, bit 7 the borrow
    e = {1'b0, a[22:16]} - {{(8 - TEX_LVL_W){1'b0}}, l};
    return (a[22:16] == EXP_SPEC)                      ? ((a[15:0] != 16'd0) ? F24_NAN : a)
         : (a[22:16] == 7'd0 || e[7] || e == 8'd0)    ? f24_zero(a[23])
         :                                               {a[23], e[6:0], a[15:0]};
  endfunction

  // Clamp-to-edge of a row / column pair: {step, kc} with kc = clamp(k, 0, n - 1) and
  // step = clamp(k + 1, 0, n - 1) - kc, which is 1 for 0 <= k < n - 1 and 0 otherwise.
  function automatic logic [TEX_DIM_W:0] clamp_pair(input idx_t k, input dim_t n);
    idx_t top;  // n - 1
    top = $signed(TEX_IDX_W'(n)) - idx_t'(1);
    return (k < 0)    ? {1'b0, dim_t'(0)}
         : (k >= top) ? {1'b0, dim_t'(top)}
         :              {1'b1, dim_t'(k)};
  endfunction

  // ---- S0: the texture; the scales; the level -------------------------------------------------
  typedef logic [SEL_W-1:0] sel_t;
  sel_t tex_in;
  lvl_t lvl_in;
  f24_t ut, vt;                                // S1
  if (NTEX > 1 && (1 << SEL_W) == NTEX) begin : g_sel_pow2
    assign tex_in = tex_i;                     // every tex_i names a texture
  end else if (NTEX > 1) begin : g_sel
    assign tex_in = (tex_i > sel_t'(NTEX - 1)) ? sel_t'(NTEX - 1) : tex_i;
  end else begin : g_one
    logic unused_tex;                          // one texture: tex_i is ignored
    assign unused_tex = ^tex_i;
    assign tex_in = '0;
  end
  assign lvl_in = (level_i > MIP_LEVEL_W'(TEX_LEVELS - 1)) ? lvl_t'(TEX_LEVELS - 1)
                                                          : lvl_t'(level_i);
  // The multipliers' operands: the ports (NTEX = 1), or with NTEX > 1 the input register, which
  // holds the lookup and its texture's scales (selected by tex_i in front of the register, not
  // in front of the multipliers: that select cost the unit its clock, 92.9 MHz out of context).
  f24_t u0, v0, su0, sv0;
  lvl_t lvl0;
  sel_t tex0;
  if (NTEX > 1) begin : g_in_reg
    always_ff @(posedge clk_i) begin
      if (en_i) begin
        u0   <= u_i;
        v0   <= v_i;
        su0  <= cfg_su_i[tex_in];
        sv0  <= cfg_sv_i[tex_in];
        lvl0 <= lvl_in;
        tex0 <= tex_in;
      end
    end
  end else begin : g_in_wire
    assign u0   = u_i;
    assign v0   = v_i;
    assign su0  = cfg_su_i[0];
    assign sv0  = cfg_sv_i[0];
    assign lvl0 = lvl_in;
    assign tex0 = tex_in;
  end
  f24_mul u_ut (.clk_i, .en_i, .a_i(u0), .b_i(su0), .y_o(ut));
  f24_mul u_vt (.clk_i, .en_i, .a_i(v0), .b_i(sv0), .y_o(vt));
  lvl_t lvl_q [1:S_CLP];                       // L in stages S1 .. S5
  sel_t tex_q [1:S_CLP];                       // the texture in stages S1 .. S5

  // ---- S1: 2^-L; S2: - 0.5 -------------------------------------------------------------------
  f24_t ul_q, vl_q;                            // S2: ut 2^-L, vt 2^-L
  f24_t x, y;                                  // S4
  f24_add u_x (.clk_i, .en_i, .a_i(ul_q), .b_i(F24_NEG_HALF), .y_o(x));
  f24_add u_y (.clk_i, .en_i, .a_i(vl_q), .b_i(F24_NEG_HALF), .y_o(y));

  // ---- S4: floor; the level's size ------------------------------------------------------------
  idx_t j0, i0;                                // S5
  logic unused_sat_j, unused_sat_i;            // saturation flags: the clamps cover them
  f24_to_index #(.W(TEX_IDX_W)) u_j0 (.clk_i, .en_i, .a_i(x), .idx_o(j0),
                                      .sat_o(unused_sat_j));
  f24_to_index #(.W(TEX_IDX_W)) u_i0 (.clk_i, .en_i, .a_i(y), .idx_o(i0),
                                      .sat_o(unused_sat_i));
  f24_t x_q [S_IDX+1:S_FX];                    // x, y in stages S5 .. S6
  f24_t y_q [S_IDX+1:S_FX];
  dim_t w_q [S_CLP:S_FX];                      // W_L in stages S5 .. S6
  dim_t h_q;                                   // H_L in stage S5

  // ---- S5: from_int; clamps; the level's start ----------------------------------------------
  f24_t fj, fi;                                // S6
  f24_from_int #(.W(TEX_IDX_W)) u_fj (.clk_i, .en_i, .k_i(j0), .y_o(fj));
  f24_from_int #(.W(TEX_IDX_W)) u_fi (.clk_i, .en_i, .k_i(i0), .y_o(fi));
  logic [TEX_DIM_W:0] jc, ic;                  // {step, clamped index}
  assign jc = clamp_pair(j0, w_q[S_CLP]);
  assign ic = clamp_pair(i0, h_q);
  dim_t              j0c_q, i0c_q;             // S6
  logic              dj_q [S_FX:S_SUM];        // j1c - j0c in stages S6 .. S7
  logic              di_q;                     // i1c - i0c in stage S6
  logic [ADDR_W-1:0] lb_q [S_FX:S_SUM];        // base + level_off[L] in stages S6 .. S7

  // ---- S6: fx, fy; the row product ------------------------------------------------------------
  f24_add u_fx (.clk_i, .en_i, .a_i(x_q[S_FX]), .b_i({~fj[23], fj[22:0]}), .y_o(fx_o));
  f24_add u_fy (.clk_i, .en_i, .a_i(y_q[S_FX]), .b_i({~fi[23], fi[22:0]}), .y_o(fy_o));
  logic [ROW_W-1:0] r_q;                       // S7: i0c W_L + j0c
  dim_t             rs_q;                      // S7: i1c - i0c = 1 ? W_L : 0

  // ---- S7: the four addresses -----------------------------------------------------------------
  logic [ADDR_W-1:0] a00, rs4, dj4;
  logic [ADDR_W-1:0] addr_q [4];               // S8
  assign a00 = lb_q[S_SUM] + (ADDR_W'(r_q) << 2);
  assign rs4 = ADDR_W'(rs_q) << 2;
  assign dj4 = ADDR_W'(dj_q[S_SUM]) << 2;
  assign addr00_o = addr_q[0];
  assign addr01_o = addr_q[1];
  assign addr10_o = addr_q[2];
  assign addr11_o = addr_q[3];

  // ---- registers ------------------------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      lvl_q[1] <= lvl0;
      tex_q[1] <= tex0;
      for (int s = 2; s <= S_CLP; s++) begin
        lvl_q[s] <= lvl_q[s-1];
        tex_q[s] <= tex_q[s-1];
      end
      // S1 -> S2
      ul_q <= f24_pow2_down(ut, lvl_q[S_P2]);
      vl_q <= f24_pow2_down(vt, lvl_q[S_P2]);
      x_q[S_IDX+1] <= x;
      y_q[S_IDX+1] <= y;
      for (int s = S_IDX + 2; s <= S_FX; s++) begin
        x_q[s] <= x_q[s-1];
        y_q[s] <= y_q[s-1];
      end
      // S4 -> S5
      w_q[S_CLP] <= cfg_width_i[tex_q[S_IDX]][lvl_q[S_IDX]];
      h_q        <= cfg_height_i[tex_q[S_IDX]][lvl_q[S_IDX]];
      // S5 -> S6
      w_q[S_FX]  <= w_q[S_CLP];
      {dj_q[S_FX], j0c_q} <= jc;
      {di_q, i0c_q}       <= ic;
      lb_q[S_FX] <= cfg_base_i[tex_q[S_CLP]] + cfg_level_off_i[tex_q[S_CLP]][lvl_q[S_CLP]];
      // S6 -> S7
      r_q  <= ROW_W'(i0c_q) * ROW_W'(w_q[S_FX]) + ROW_W'(j0c_q);
      rs_q <= di_q ? w_q[S_FX] : '0;
      dj_q[S_SUM] <= dj_q[S_FX];
      lb_q[S_SUM] <= lb_q[S_FX];
      // S7 -> S8
      addr_q[0] <= a00;
      addr_q[1] <= a00 + dj4;
      addr_q[2] <= a00 + rs4;
      addr_q[3] <= a00 + rs4 + dj4;
    end
  end

  // ---- valid and tag ---------------------------------------------------------------------------
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_OUT + ((NTEX > 1) ? 1 : 0))) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o());

endmodule
