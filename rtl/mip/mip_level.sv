// mip_level: the MIP-level unit after Park et al., IEICE Electronics Express 2011, eq. (2), for
// the colour texture and the normal map of one hit per clock.  Specification: model/mip.py
// (model/texture.py ray_length and mip_level) in the f24 engine, bit for bit:
//   Pl  = add(Pl0, mul(t, seg))                 eye-to-hit ray length
//   lod = sub(log2(Pl), log2Pb[tri][tex])       log2: the approximate unit f24_log2
//   L   = clamp(to_index(add(lod, 0.5)), 0, levels[tex] - 1)
//   and L = 0 when cfg_mip_en_i = 0 (the model's mip=False)
// to_index is f24_to_index with W = MIP_IDX_W = 20 = model.arith.INDEX_W: floor, saturating to
// [-2^19, 2^19 - 1], NaN -> 0, exactly F24Arith.to_index.  So a NaN t, seg or Pl0, Pl = NaN,
// a negative Pl (log2 NaN) or lod NaN give level 0; Pl = +-0 (log2 = -Inf) gives level 0;
// Pl = +Inf gives levels - 1.
//
// Fully pipelined, fixed latency MIP_LAT = 12 enabled clocks (pipe_pkg), one hit per clock, with
// the conventions of view_calc: every register advances only while en_i is 1 (the enclosing
// pipeline's stall), valid is reset by rst_ni (synchronous, active low), data registers have no
// reset, a hit taken on an enabled edge with valid_i = 1 shows at the outputs after 12 enabled
// edges and holds while en_i is 0.  Configuration (cfg_*, the table contents) must be static
// while busy; the table's write port works whatever en_i is.
//
// Stage schedule (S0 = the input ports; "a -> b": a unit takes operands in Sa, result in Sb):
//   S0   t seg                                                     f24_mul      S0 -> S1
//        Pl0 delayed S0 -> S1; tri delayed S0 -> S5
//   S1   Pl = Pl0 + t seg                                          f24_add      S1 -> S3
//   S3   log2(Pl)                                                  f24_log2     S3 -> S6
//   S5   triangle table read (both textures)                       tri_table    S5 -> S6
//   S6   lod = log2(Pl) - log2Pb (colour, normal)                  2 f24_add    S6 -> S8
//   S8   lod + 0.5                                                 2 f24_add    S8 -> S10
//   S10  floor                                                     2 f24_to_index S10 -> S11
//   S11  clamp to [0, levels - 1], mip_en                          register     S11 -> S12
//   S12  outputs (straight from registers)
// log2 runs at LAT = F24_LOG2_LAT = 3 (table / product + sum / normalise + round: over 100 MHz;
// at its 2 clocks it limits the unit to about 50 MHz); the result is the same at either LAT.
// Float units: 1 f24_mul, 5 f24_add, 1 f24_log2, 2 f24_to_index; a 2 x TRIS-word tri_table.
module mip_level
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W = 8,   // side-band bits (fragment id, pixel, hit data, ...) carried
                                      // unchanged from tag_i to tag_o alongside the hit
  parameter int unsigned TRIS  = 16,  // triangle table entries
  parameter int unsigned TRI_W = (TRIS > 1) ? $clog2(TRIS) : 1  // triangle id width
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,               // synchronous, active low: valid bits
  input  logic                   en_i,                 // clock enable of the pipeline (0 = stall)
  // configuration (static while busy)
  input  logic                   cfg_mip_en_i,         // 0: level 0 always (MIP mapping off)
  input  logic [MIP_LEVEL_W:0]   cfg_levels_colour_i,  // colour texture's level count, 1 .. 32
  input  logic [MIP_LEVEL_W:0]   cfg_levels_normal_i,  // normal map's level count, 1 .. 32
  //                                 (0 acts as 1, counts above 32 as 32)
  // triangle table write port: word {triangle, texture} (texture 0 colour, 1 normal) = log2 Pb
  input  logic                   tt_we_i,
  input  logic [TRI_W:0]         tt_waddr_i,
  input  f24_t                   tt_wdata_i,
  // hits
  input  logic                   valid_i,
  input  logic [TAG_W-1:0]       tag_i,
  input  f24_t                   t_i,                  // hit depth t
  input  f24_t                   seg_i,                // world length per unit t (view_calc)
  input  f24_t                   pl0_i,                // eye to entry point (world = texels)
  input  logic [TRI_W-1:0]       tri_i,                // triangle id
  output logic                   valid_o,
  output logic [TAG_W-1:0]       tag_o,
  output logic [MIP_LEVEL_W-1:0] level_colour_o,
  output logic [MIP_LEVEL_W-1:0] level_normal_o
);

  // Stage numbers (pipe_pkg latencies); S_OUT = MIP_LAT.
  localparam int unsigned S_PL   = F24_MUL_LAT;              // 1
  localparam int unsigned S_LOG  = S_PL + F24_ADD_LAT;       // 3
  localparam int unsigned S_LOD  = S_LOG + F24_LOG2_LAT;     // 6
  localparam int unsigned S_TT   = S_LOD - TRI_TABLE_LAT;    // 5
  localparam int unsigned S_HALF = S_LOD + F24_ADD_LAT;      // 8
  localparam int unsigned S_IDX  = S_HALF + F24_ADD_LAT;     // 10
  localparam int unsigned S_CLMP = S_IDX + F24_TO_INDEX_LAT; // 11
  localparam int unsigned S_OUT  = S_CLMP + 1;               // 12
  if (S_OUT != MIP_LAT) begin : g_check_lat
    $error("mip_level: stage schedule does not add up to MIP_LAT");
  end

  localparam f24_t F24_HALF = 24'h3e0000;  // 0.5

  // ---- S0: t seg; S1: Pl ---------------------------------------------------------------------
  f24_t ts, pl, l2;
  f24_t pl0_q [1:S_PL];                 // Pl0 in stages S1 .. S_PL
  f24_mul u_ts (.clk_i, .en_i, .a_i(t_i), .b_i(seg_i), .y_o(ts));
  f24_add u_pl (.clk_i, .en_i, .a_i(pl0_q[S_PL]), .b_i(ts), .y_o(pl));
  // ---- S3: log2(Pl)
  f24_log2 #(.LAT(F24_LOG2_LAT)) u_l2 (.clk_i, .en_i, .a_i(pl), .y_o(l2));

  // ---- S5: the triangle table ------------------------------------------------------------------
  logic [TRI_W-1:0] tri_q [1:S_TT];     // the triangle id in stages S1 .. S5
  f24_t pb [2];                         // S6: log2 Pb of the colour texture, the normal map
  tri_table #(.TRIS(TRIS), .TRI_W(TRI_W)) u_table (
    .clk_i, .we_i(tt_we_i), .waddr_i(tt_waddr_i), .wdata_i(tt_wdata_i),
    .re_i(en_i), .raddr_i(tri_q[S_TT]), .rdata_colour_o(pb[0]), .rdata_normal_o(pb[1]));

  // ---- S6 .. S12, per texture ----------------------------------------------------------------
  logic [MIP_LEVEL_W:0]   levels [2];
  logic [MIP_LEVEL_W-1:0] lvl_q  [2];   // S12
  assign levels[0] = cfg_levels_colour_i;
  assign levels[1] = cfg_levels_normal_i;

  for (genvar x = 0; x < 2; x++) begin : g_tex
    f24_t lod, lodh;
    logic signed [MIP_IDX_W-1:0] idx;
    logic                        unused_sat;
    logic [MIP_LEVEL_W-1:0]      top;    // levels - 1 (0 for a count of 0)
    logic [MIP_LEVEL_W-1:0]      lvl;
    // S6: lod = log2(Pl) - log2Pb (subtract: flip the sign bit)
    f24_add u_lod (.clk_i, .en_i, .a_i(l2), .b_i({~pb[x][23], pb[x][22:0]}), .y_o(lod));
    // S8: lod + 0.5
    f24_add u_half (.clk_i, .en_i, .a_i(lod), .b_i(F24_HALF), .y_o(lodh));
    // S10: floor
    f24_to_index #(.W(MIP_IDX_W)) u_idx (.clk_i, .en_i, .a_i(lodh), .idx_o(idx),
                                         .sat_o(unused_sat));
    // S11: clamp(idx, 0, levels - 1); level 0 with MIP mapping off
    // (a count of 0 acts as 1, one above 2^MIP_LEVEL_W as 2^MIP_LEVEL_W)
    assign top = (levels[x] == '0)         ? '0
               : levels[x][MIP_LEVEL_W]    ? '1
               :                             MIP_LEVEL_W'(levels[x] - 1'b1);
    assign lvl = (!cfg_mip_en_i || idx < 0)         ? '0
               : (idx > $signed(MIP_IDX_W'(top))) ? top
               :                                    MIP_LEVEL_W'(idx);
    always_ff @(posedge clk_i) begin
      if (en_i) lvl_q[x] <= lvl;
    end
  end

  assign level_colour_o = lvl_q[0];
  assign level_normal_o = lvl_q[1];

  // ---- delay lines: Pl0 to S1, tri to S5 -------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      pl0_q[1] <= pl0_i;
      for (int s = 2; s <= S_PL; s++) pl0_q[s] <= pl0_q[s-1];
      tri_q[1] <= tri_i;
      for (int s = 2; s <= S_TT; s++) tri_q[s] <= tri_q[s-1];
    end
  end

  // ---- valid and tag ---------------------------------------------------------------------------
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_OUT)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o, .tag_o);

endmodule
