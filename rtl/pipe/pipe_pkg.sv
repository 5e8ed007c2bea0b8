// SPDX-License-Identifier: Apache-2.0
// pipe_pkg: latencies and widths of the displacement-mapping pipeline's fixed-latency units
// (view_calc, mip_level), so that the pipeline top can size its buffers and delay lines.
//
// Every latency counts enabled clocks (edges with en_i = 1), like the float units of rtl/fp/: an
// operand set presented on an enabled edge shows at the unit's outputs after LAT enabled edges
// and holds while en_i is 0.  The unit latencies below restate the README's table of rtl/fp/;
// the stage schedules of view_calc and mip_level are built from them, and the cocotb tests
// (tb/view_calc, tb/mip_level) check the sums against the RTL.  The same holds for the texture
// path's tex_addr and tex_filter (tb/tex_addr, tb/tex_filter).
package pipe_pkg;

  // Each unit uses only its own constants.
  /* verilator lint_off UNUSEDPARAM */

  // ---- float units (rtl/fp/, README "Units") ----------------------------------------------------
  // The depths the blocks build their adders and multipliers at (each block's ADD_LAT / MUL_LAT
  // defaults to these; the blocks also take the paper's (2, 1)).  One clock more than the paper's
  // for each: a third adder stage, a register after the multiplier's DSP (the same result words),
  // the depths that take the units past 100 MHz on an ECP5 (docs/synthesis.md).
  localparam int unsigned F24_ADD_LAT      = 3;  // f24_add (and subtract)
  localparam int unsigned F24_MUL_LAT      = 2;  // f24_mul
  localparam int unsigned F24_LOG2_LAT     = 3;  // f24_log2 #(.LAT(3)): table / product + sum /
                                                 // normalise + round (LAT 2 stays near 50 MHz)
  localparam int unsigned F24_RSQRT_LAT    = 3;  // f24_rsqrt #(.LAT(3)) (shade_unit): table /
                                                 // product + sum / round (LAT 2: near 70 MHz)
  localparam int unsigned F24_TO_INDEX_LAT = 1;  // f24_to_index
  localparam int unsigned F24_FROM_INT_LAT   = 1;  // f24_from_int
  localparam int unsigned F24_FROM_UNORM_LAT = 1;  // f24_from_unorm
  // f24_div: f24_pkg::F24_DIV_LAT (the divider's LAT parameter, set where the units use it).

  // ---- view_calc (model/view.py) ------------------------------------------------------------
  // z = dot(N, V): the products' operand register, mul, add, add; then div(D, -z); the NaN
  // select of k into the scale's operand register; mul(x, k); mul(y, k) a clock later (one
  // multiplier for both), du held a clock.  A fragment every 4th clock at most (z, x and y on
  // the same units in consecutive clocks).  view_calc_lat: at view_calc's ADD_LAT / MUL_LAT
  // (the f24_add / f24_mul LATs it instantiates): 17 at (2, 1), 21 at (3, 2).
  function automatic int unsigned view_calc_lat(int unsigned add_lat, int unsigned mul_lat);
    return 1 + mul_lat + 2 * add_lat + f24_pkg::F24_DIV_LAT + 1 + mul_lat + 1;
  endfunction
  localparam int unsigned VIEW_CALC_LAT = view_calc_lat(F24_ADD_LAT, F24_MUL_LAT);  // 21

  // ---- tri_table / mip_level (model/texture.py "MIP level", model/mip.py) -------------------------
  localparam int unsigned TRI_TABLE_LAT = 1;   // registered read
  localparam int unsigned MIP_LEVEL_W   = 5;   // level output width: levels 0 .. 31
  // The floor's width in mip_level (f24_round_index): [-64, 63] holds the clamp's range [0, 31],
  // so the clamped level equals the model's, whose floor saturates at model.arith.INDEX_W (20)
  // bits.
  localparam int unsigned MIP_IDX_W     = MIP_LEVEL_W + 2;
  // mip_level's one adder serves a hit's three additions: Pl = Pl0 + t seg, then, mip_gap
  // enabled clocks later, the colour texture's lod = log2(Pl) - log2Pb and the normal map's a
  // clock after that.  So a hit may not follow another by mip_gap or mip_gap + 1 enabled clocks
  // (nor by 1: the lod datapath).  mip_gap = the adder, log2 (F24_LOG2_LAT), the job register,
  // and a pad of 0 .. 2 clocks that makes it 1 or 2 mod 4: hits a multiple of 4 clocks apart
  // (dm_pipeline's full rate) never meet that rule.  6 at ADD_LAT 2, 9 at 3 and 4.
  function automatic int unsigned mip_gap(int unsigned add_lat);
    return add_lat + F24_LOG2_LAT + 1 + ((5 - (add_lat + F24_LOG2_LAT + 1) % 4) % 4) % 3;
  endfunction
  // Pl = Pl0 + t seg (mul; the adder's operand registers; add); log2; the pad; the texture's
  // job register (colour, then the normal map a clock later) into the adder's operand
  // registers; lod = - log2Pb (add); + 0.5 and floor (f24_round_index, the clocks of an add and
  // a to_index); clamp to the level range and the mip_en select (one register).  The colour
  // level's latency; the normal map's is one more.  mip_lat: at mip_level's ADD_LAT / MUL_LAT
  // (the f24_add / f24_mul LATs it instantiates): 14 at (2, 1), 20 at (3, 2).
  function automatic int unsigned mip_lat(int unsigned add_lat, int unsigned mul_lat);
    return mul_lat + mip_gap(add_lat) + 1 + 2 * add_lat + F24_TO_INDEX_LAT + 1;
  endfunction
  localparam int unsigned MIP_LAT = mip_lat(F24_ADD_LAT, F24_MUL_LAT);  // 20

  // ---- tex_addr / tex_filter (model/texture.py lookup_addresses, filter_texels) --------------
  localparam int unsigned TEX_LEVELS  = 16;  // levels a texture configuration holds: textures up
                                             // to 32768 texels a side (1 + ceil(log2 32768) = 16)
  localparam int unsigned TEX_LVL_W   = 4;   // a level 0 .. TEX_LEVELS - 1
  localparam int unsigned TEX_DIM_W   = 16;  // a level's width / height, 1 .. 32768
  localparam int unsigned TEX_ADDR_W  = 32;  // byte address of a texel (default of tex_addr)
  // The level tables (dm_pipeline's lvt_* write port): one 32-bit word per entry, word address
  // {kind [1:0], texture, level}: kind LVT_HEIGHT_OFF the height pyramid's level offset from
  // cfg_base_i (Pyramid.level_offsets; texture bit 0; held by traverse_addr in each ring),
  // LVT_TEX_OFF a texture level's byte offset from its base (Texture.level_offsets),
  // LVT_TEX_SIZE its size {height [31:16], width [15:0]} (both held by tex_addr); kind 0 is
  // ignored.  The same word addresses as dm_pipeline_fpga_top's register words 0x20 .. 0x7F.
  localparam int unsigned LVT_ADDR_W  = 3 + TEX_LVL_W;  // 7
  localparam int unsigned LVT_HEIGHT_OFF = 1;  // kinds (the two top bits of the word address)
  localparam int unsigned LVT_TEX_OFF    = 2;
  localparam int unsigned LVT_TEX_SIZE   = 3;
  localparam int unsigned TEX_IDX_W   = 20;  // f24_to_index / f24_from_int width (INDEX_W)
  localparam int unsigned TEXEL_W     = 32;  // an RGBA unorm8 texel: R in bits 7:0 .. A in 31:24
  // the item register (u, then v a clock later on the same units); scale (mul); 2^-L (exponent
  // arithmetic, one register); - 0.5 (add); floor (to_index); from_int; fx = x - j0 (add); fy a
  // clock after fx.  The addresses are ready in the same stage.  tex_addr's latency at its
  // ADD_LAT, MUL_LAT (the f24_add, f24_mul depths): 10 at (2, 1), 13 at (3, 2).
  function automatic int unsigned tex_addr_lat(input int unsigned add_lat,
                                               input int unsigned mul_lat);
    return 1 + mul_lat + 1 + add_lat + F24_TO_INDEX_LAT + F24_FROM_INT_LAT + add_lat + 1;
  endfunction
  localparam int unsigned TEX_ADDR_LAT = tex_addr_lat(F24_ADD_LAT, F24_MUL_LAT);  // 13
  // from_unorm; per row sub, mul, add (top, then bot a clock later on the same units); then sub,
  // mul, add (between the rows), the last adder's two operations from operand registers and an
  // odd number of clocks apart (m delayed (add_lat + mul_lat) % 2 clocks: a clock at (2, 1) and
  // at (3, 2)).  tex_filter's latency at its ADD_LAT, MUL_LAT: 15 at (2, 1), 21 at (3, 2).
  function automatic int unsigned tex_filter_lat(input int unsigned add_lat,
                                                 input int unsigned mul_lat);
    return F24_FROM_UNORM_LAT + 1 + 2 * (add_lat + mul_lat + add_lat) + 2 + (add_lat + mul_lat) % 2;
  endfunction
  localparam int unsigned TEX_FILTER_LAT = tex_filter_lat(F24_ADD_LAT, F24_MUL_LAT);  // 21

  /* verilator lint_on UNUSEDPARAM */

endpackage
