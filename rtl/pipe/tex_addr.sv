// SPDX-License-Identifier: Apache-2.0
// tex_addr: the texture address calculation of the texture path (Park et al. 2013, Fig. 6, after
// the MIP-level unit): one bilinear lookup every other clock at most, the four texel byte
// addresses and the two weights.  Specification: model/texture.py lookup_addresses (steps 1-5
// of the module docstring's "Bilinear lookup at level L") in the f24 engine, bit for bit:
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
// Fixed latency LAT = pipe_pkg::tex_addr_lat(ADD_LAT, MUL_LAT) enabled clocks whatever NTEX:
// 10 at the f24_add / f24_mul depths (ADD_LAT, MUL_LAT) = (2, 1) (pipe_pkg's TEX_ADDR_LAT at
// the package defaults), 13 at (3, 2).  One lookup every other enabled clock at most, at every
// depth: valid_i must not be 1 on two consecutive enabled clocks (asserted: lookup_spacing;
// dm_pipeline admits a hit every 4th clock at most, its two lookups 2 clocks apart).  The
// conventions of view_calc otherwise: every register advances only while en_i is 1 (the
// enclosing pipeline's stall), valid is reset by rst_ni (synchronous, active low), data
// registers have no reset; a lookup taken on an enabled edge with valid_i = 1 shows at the
// outputs after LAT enabled edges and holds while en_i is 0.  Configuration (cfg_* and the level
// tables) must be static while busy.
//
// Configuration of each of NTEX textures (model.texture.Texture; index t of every cfg_* array is
// texture t): su, sv = Texture.scale_for (engine words) and the base byte address on ports; per
// level k < TEX_LEVELS its byte offset from the base (Texture.level_offsets) and its width W_k
// and height H_k (1 .. 32768; level_size) in the level tables, two memories of NTEX x
// TEX_LEVELS words in LUT RAM written through the lvt_* port, one word per clock with
// lvt_we_i = 1 (the write port ignores en_i): word address {kind, texture, level}, kind 0 the
// offset, kind 1 the size {H_k, W_k} (TEX_DIM_W bits each, W_k in the low bits); a write to a
// texture of NTEX or more is ignored.  The tables are not reset: every entry a lookup reads
// must be written first.  (Read from flip-flop arrays through 32:1 and 64:1 multiplexers
// instead, the tables of two textures took about 1,900 LUT4 on the ECP5.)  Only levels 0 ..
// levels - 1 of a texture are meaningful: level_i comes from mip_level, clamped to levels - 1
// <= TEX_LEVELS - 1 (a level_i above TEX_LEVELS - 1 is read as TEX_LEVELS - 1).
//
// Textures sharing the unit (NTEX > 1): each lookup names its texture with tex_i, which travels
// down the pipeline with the level; each stage reads the configuration of its own lookup's
// texture (su or sv in front of the item register, W_L or H_L in I_IDX, base and level_off in
// I_MEET: each table has one read port),
// so lookups of different textures may follow each other.  dm_pipeline uses one unit for the
// colour texture (0) and the normal map (1).  A tex_i of NTEX or more reads texture NTEX - 1;
// with NTEX = 1 tex_i is ignored.
//
// Axis items (as in traverse_setup).  A lookup is two items on one set of float units: its u
// item (u, su, W_L: x, j0, fx) enters the item register with the lookup, its v item (v, sv, H_L:
// y, i0, fy) on the next enabled clock, from hold registers of v_i, the level and the texture
// (loaded on every enabled clock; the v item's clock takes no lookup).  So one multiplier, one
// adder, one to_index and one f24_frac serve both axes, each fully used at a lookup per two
// clocks.  Item stage Ik holds the u item of the lookup taken k enabled clocks ago or the v item
// of the one taken k + 1 ago; the item's axis, level and texture travel with it (ax_q, lvl_q,
// tex_q).  Where the axes meet (the row product, the address sums) the u item's clamp and W_L
// are held a clock (cu_q, w_q) and met by the v item's in I_MEET; fx, the u item's weight, is
// held a clock (fx_q) to come out with fy.  I_MEET = I_OUT - 2 puts the addresses in the
// clock of fy: with ADD_LAT above 2 the clamps and W_L wait I_MEET - I_FX = ADD_LAT - 2 clocks
// in delay registers (cl_q, n_q: 17 + 16 bits a clock, fewer than the 128 of the addresses).
// The item register (one clock) is where the u / v select and the texture's scale select sit,
// not in front of the multiplier (the scale select there cost the unit its clock, 92.9 MHz out
// of context).
//
// Stage schedule (S0 = the input ports; Ik: item stages, the u item's clock k, the v item's
// k + 1; "a -> b": a unit takes operands in Ia, result in Ib; the stage numbers at (ADD_LAT,
// MUL_LAT) = (2, 1), then (3, 2)):
//   S0      the u item: u, su of texture tex_i; the v item (next clock): v, sv held
//           L saturated to 0 .. 15, the texture and the axis travel I1 -> I_MEET
//                                                                 register     -> I1
//   I_MUL   t = mul(u, su) (mul(v, sv))                           f24_mul      I1 -> I_P2
//   I_P2    = 1 + MUL_LAT (2, 3): t 2^-L (exponent arithmetic, in a register of its own: in
//           front of the adder it cost the adder's clock)         register     -> I_X
//   I_X     = I_P2 + 1 (3, 4): x = add(t 2^-L, -0.5) (y)          f24_add      -> I_IDX
//   I_IDX   = I_X + ADD_LAT (5, 7): j0 = floor(x) (i0)            f24_to_index -> I_CLP
//           fx = sub(x, from_int(j0)) (fy): the word of f24_from_int and f24_add in one unit,
//           in their clocks                             f24_frac, ADD_LAT + 2 -> I_OUT
//           W_L (H_L for the v item) read                         register     -> I_CLP
//   I_CLP   = I_IDX + 1 (6, 8): clamp: {dj, j0c} ({di, i0c})      register     -> I_FX
//           W_L delayed I_CLP -> I_MEET - 1, held there for the v item (w_q)
//   I_FX    = I_CLP + 1 (7, 9): the clamp delayed I_FX -> I_MEET (where the chain's adder
//           took its operands)
//   I_MEET  = I_OUT - 2 (7, 10): u item: {dj, j0c} held a clock (cu_q)
//           v item: r = i0c W_L + j0c; rs = di ? W_L : 0; base + level_off[L]
//                                                                 register     -> I_SUM
//   I_SUM   = I_MEET + 1 (8, 11): (v item) addr = base + off + 4 (r + {0, dj, rs, rs + dj})
//                                                                 register     -> I_OUT
//   I_OUT   = I_FX + ADD_LAT (9, 12): u item: fx held a clock (fx_q); v item: the outputs
//           (straight from registers), the lookup's clock LAT = I_OUT + 1 (10, 13)
// Float units: 1 f24_mul #(.LAT(MUL_LAT)), 1 f24_add #(.LAT(ADD_LAT)), 1 f24_to_index,
// 1 f24_frac (before it: an f24_from_int and a second f24_add; before the axes shared them: 2,
// 4, 2, 2 and no f24_frac); one 16 x 16 multiplier (the second
// row's address is the first's plus 4 W_L: i1c - i0c is 0 or 1).
module tex_addr
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned ADD_LAT = F24_ADD_LAT, // f24_add latency (2 .. 4: the two adders)
  parameter int unsigned MUL_LAT = F24_MUL_LAT, // f24_mul latency (1 .. 3: the multiplier)
  parameter int unsigned TAG_W  = 8,          // side-band bits carried from tag_i to tag_o
  parameter int unsigned ADDR_W = TEX_ADDR_W, // byte address width (addresses wrap modulo 2^ADDR_W)
  parameter int unsigned NTEX   = 1,          // textures sharing the unit (lookups pick by tex_i)
  parameter int unsigned SEL_W  = (NTEX > 1) ? $clog2(NTEX) : 1, // tex_i width
  parameter int unsigned LVT_W  = 1 + SEL_W + TEX_LVL_W,         // level-table word address
  parameter int unsigned LVT_DW = (ADDR_W > 2 * TEX_DIM_W) ? ADDR_W : 2 * TEX_DIM_W // its data
) (
  input  logic                                 clk_i,
  input  logic                                 rst_ni,           // synchronous, active low: valid
  input  logic                                 en_i,             // clock enable (0 = stall)
  // configuration of the textures (static while busy), [t] = texture t
  input  f24_t [NTEX-1:0]                      cfg_su_i,         // u scale: engine(Wt / W)
  input  f24_t [NTEX-1:0]                      cfg_sv_i,         // v scale: engine(Ht / H)
  input  logic [NTEX-1:0][ADDR_W-1:0]          cfg_base_i,       // byte address of the texture
  // level tables (static while busy): write lvt_wdata_i into word lvt_waddr_i = {kind, texture,
  // level}; kind 0: the level's byte offset from the base, 1: {H_k [31:16], W_k [15:0]} (>= 1)
  input  logic                                 lvt_we_i,
  input  logic [LVT_W-1:0]                     lvt_waddr_i,
  input  logic [LVT_DW-1:0]                    lvt_wdata_i,
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

  // Item stage numbers (from ADD_LAT, MUL_LAT); the outputs at the lookup's clock LAT.
  localparam int unsigned I_MUL = 1;                         // 1: the item register, mul
  localparam int unsigned I_P2  = I_MUL + MUL_LAT;           // 2 (3): 2^-L
  localparam int unsigned I_X   = I_P2 + 1;                  // 3 (4): - 0.5
  localparam int unsigned I_IDX = I_X + ADD_LAT;             // 5 (7): floor; W_L / H_L read
  localparam int unsigned I_CLP = I_IDX + F24_TO_INDEX_LAT;  // 6 (8): from_int; clamp
  localparam int unsigned I_FX  = I_CLP + F24_FROM_INT_LAT;  // 7 (9): fx
  localparam int unsigned I_OUT = I_FX + ADD_LAT;            // 9 (12): the v item's clock LAT
  localparam int unsigned I_MEET = I_OUT - 2;                // 7 (10): the axes meet (the v
                                                             //   item's clamp delayed from I_FX)
  localparam int unsigned I_SUM = I_MEET + 1;                // 8 (11): address sums (v item)
  localparam int unsigned LAT   = I_OUT + 1;                 // 10 (13)
  if (ADD_LAT < 2 || MUL_LAT < 1) begin : g_check_units
    $error("tex_addr: ADD_LAT must be at least 2 and MUL_LAT at least 1");
  end
  if (LAT != tex_addr_lat(ADD_LAT, MUL_LAT) || I_MEET < I_FX
      || I_SUM + 1 != I_OUT) begin : g_check_lat
    $error("tex_addr: stage schedule does not add up to pipe_pkg::tex_addr_lat");
  end
  if (TEX_IDX_W <= TEX_DIM_W) begin : g_check_w
    $error("tex_addr: the index width must exceed the dimension width");
  end
  if (LVT_DW < ADDR_W || LVT_DW < 2 * TEX_DIM_W || LVT_W != 1 + SEL_W + TEX_LVL_W)
  begin : g_check_lvt
    $error("tex_addr: a level-table word holds an offset (ADDR_W bits) or a size (2 TEX_DIM_W)");
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

  // ---- the level tables (LUT RAM, one write port, one asynchronous read port each) ------------
  // Word {t, k} of either table is entry t * TEX_LEVELS + k.
  localparam int unsigned LVT_N  = NTEX * TEX_LEVELS;
  localparam int unsigned LVT_IW = $clog2(LVT_N);
  function automatic logic [LVT_IW-1:0] lvt_index(input logic [SEL_W-1:0] t,
                                                  input logic [TEX_LVL_W-1:0] k);
    return LVT_IW'(32'(t) * TEX_LEVELS + 32'(k));
  endfunction
  logic [ADDR_W-1:0]    off_mem  [LVT_N];      // level offsets, read in I_MEET
  logic [2*TEX_DIM_W-1:0] size_mem [LVT_N];    // {H_k, W_k}, read in I_IDX
  logic                 lvt_kind;
  logic [SEL_W-1:0]     lvt_tex;
  logic [TEX_LVL_W-1:0] lvt_lvl;
  assign {lvt_kind, lvt_tex, lvt_lvl} = lvt_waddr_i;
  always_ff @(posedge clk_i) begin
    if (lvt_we_i && 32'(lvt_tex) < NTEX) begin
      if (lvt_kind) size_mem[lvt_index(lvt_tex, lvt_lvl)] <= lvt_wdata_i[2*TEX_DIM_W-1:0];
      else          off_mem[lvt_index(lvt_tex, lvt_lvl)] <= ADDR_W'(lvt_wdata_i);
    end
  end

  // ---- S0: the texture; the level; the item register ------------------------------------------
  typedef logic [SEL_W-1:0] sel_t;
  sel_t tex_in;
  lvl_t lvl_in;
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
  // The v item's inputs, held from the lookup's clock to its own (loaded on every enabled clock:
  // only the one after a lookup reads them).
  f24_t vh_q;
  lvl_t lvlh_q;
  sel_t texh_q;
  // The item register: the multiplier's operands, and the item's axis (1: v), level, texture in
  // item stages I1 .. I_MEET.  A clock without a lookup loads the v item (or a bubble's junk).
  f24_t a1_q, b1_q;
  logic ax_q  [I_MUL:I_MEET];
  lvl_t lvl_q [I_MUL:I_MEET];
  sel_t tex_q [I_MUL:I_MEET];
  f24_t t;                                     // I_P2: u su (v sv)
  f24_mul #(.LAT(MUL_LAT)) u_t (.clk_i, .en_i, .a_i(a1_q), .b_i(b1_q), .y_o(t));

  // ---- I_P2: 2^-L; I_X: - 0.5 -----------------------------------------------------------------
  f24_t tl_q;                                  // I_X: t 2^-L
  f24_t x;                                     // I_IDX: x (y)
  f24_add #(.LAT(ADD_LAT)) u_x (.clk_i, .en_i, .a_i(tl_q), .b_i(F24_NEG_HALF), .y_o(x));

  // ---- I_IDX: floor; the level's size --------------------------------------------------------
  idx_t k0;                                    // I_CLP: j0 (i0)
  logic unused_sat;                            // saturation flag: the clamp covers it
  f24_to_index #(.W(TEX_IDX_W)) u_k0 (.clk_i, .en_i, .a_i(x), .idx_o(k0), .sat_o(unused_sat));
  // fx = x - from_int(j0) (fy), the word of f24_from_int and f24_add, from x in I_IDX to I_OUT
  f24_t f;                                     // I_OUT: fx (fy)
  f24_frac #(.LAT(I_OUT - I_IDX)) u_f (.clk_i, .en_i, .a_i(x), .y_o(f));
  dim_t n_q [I_CLP:I_MEET-1];                  // W_L (H_L) in item stages I_CLP .. I_MEET - 1
  logic [2*TEX_DIM_W-1:0] sz_idx;              // {H_L, W_L} of the item in I_IDX
  assign sz_idx = size_mem[lvt_index(tex_q[I_IDX], lvl_q[I_IDX])];

  // ---- I_CLP: clamp ---------------------------------------------------------------------------
  logic [TEX_DIM_W:0] cl_q [I_FX:I_MEET];      // {dj, j0c} ({di, i0c}) in I_FX .. I_MEET
  logic [TEX_DIM_W:0] cu_q;                    // the u item's {dj, j0c}, a clock later
  dim_t               w_q;                     // W_L of the last u item in I_MEET - 1

  // ---- I_MEET: the axes meet, the row product ---------------------------------------------------
  f24_t fx_q;                                  // fx, a clock later
  logic [ROW_W-1:0]  r_q;                      // I_SUM: i0c W_L + j0c
  dim_t              rs_q;                     // I_SUM: i1c - i0c = 1 ? W_L : 0
  logic              dj_q;                     // I_SUM: j1c - j0c
  logic [ADDR_W-1:0] lb_q;                     // I_SUM: base + level_off[L]
  logic [ADDR_W-1:0] off_meet;                 // level_off[L] of the item in I_MEET
  assign off_meet = off_mem[lvt_index(tex_q[I_MEET], lvl_q[I_MEET])];
  assign fx_o = fx_q;
  assign fy_o = f;

  // ---- I_SUM: the four addresses ---------------------------------------------------------------
  logic [ADDR_W-1:0] a00, rs4, dj4;
  logic [ADDR_W-1:0] addr_q [4];               // I_OUT
  assign a00 = lb_q + (ADDR_W'(r_q) << 2);
  assign rs4 = ADDR_W'(rs_q) << 2;
  assign dj4 = ADDR_W'(dj_q) << 2;
  assign addr00_o = addr_q[0];
  assign addr01_o = addr_q[1];
  assign addr10_o = addr_q[2];
  assign addr11_o = addr_q[3];

  // ---- registers ------------------------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      // S0 -> I1: the u item of a lookup, else the v item of the last one
      vh_q   <= v_i;
      lvlh_q <= lvl_in;
      texh_q <= tex_in;
      a1_q   <= valid_i ? u_i : vh_q;
      b1_q   <= valid_i ? cfg_su_i[tex_in] : cfg_sv_i[texh_q];
      ax_q[I_MUL]  <= !valid_i;
      lvl_q[I_MUL] <= valid_i ? lvl_in : lvlh_q;
      tex_q[I_MUL] <= valid_i ? tex_in : texh_q;
      for (int s = I_MUL + 1; s <= I_MEET; s++) begin
        ax_q[s]  <= ax_q[s-1];
        lvl_q[s] <= lvl_q[s-1];
        tex_q[s] <= tex_q[s-1];
      end
      // I_P2 -> I_X
      tl_q <= f24_pow2_down(t, lvl_q[I_P2]);
      // I_IDX -> I_CLP
      n_q[I_CLP] <= ax_q[I_IDX] ? sz_idx[2*TEX_DIM_W-1:TEX_DIM_W] : sz_idx[TEX_DIM_W-1:0];
      // I_CLP -> I_FX
      cl_q[I_FX] <= clamp_pair(k0, n_q[I_CLP]);
      // -> I_MEET: the clamp and the level's size wait for fx's adder (no clock at ADD_LAT 2)
      for (int s = I_CLP + 1; s <= I_MEET - 1; s++) n_q[s] <= n_q[s-1];
      for (int s = I_FX + 1; s <= I_MEET; s++) cl_q[s] <= cl_q[s-1];
      if (!ax_q[I_MEET-1]) w_q <= n_q[I_MEET-1];  // held while the v item passes I_MEET - 1
      // I_MEET -> I_SUM (the v item in I_MEET meets the u item's clamp in cu_q and its W_L in
      // w_q)
      cu_q <= cl_q[I_MEET];
      r_q  <= ROW_W'(cl_q[I_MEET][TEX_DIM_W-1:0]) * ROW_W'(w_q) + ROW_W'(cu_q[TEX_DIM_W-1:0]);
      rs_q <= cl_q[I_MEET][TEX_DIM_W] ? w_q : '0;
      dj_q <= cu_q[TEX_DIM_W];
      lb_q <= cfg_base_i[tex_q[I_MEET]] + off_meet;
      // I_SUM -> I_OUT
      addr_q[0] <= a00;
      addr_q[1] <= a00 + dj4;
      addr_q[2] <= a00 + rs4;
      addr_q[3] <= a00 + rs4 + dj4;
      // I_OUT: fx waits for fy
      fx_q <= f;
    end
  end

  // ---- valid and tag ---------------------------------------------------------------------------
  /* verilator lint_off UNUSEDSIGNAL */  // only stage_v[1] is read (the spacing check)
  logic [LAT:1] stage_v;  // stage_v[1]: the last enabled clock took a lookup
  /* verilator lint_on UNUSEDSIGNAL */
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(LAT)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o, .stage_valid_o(stage_v));

  // The simulation checks are in tex_addr_assert.sv (bound into every instance).

endmodule
