// SPDX-License-Identifier: Apache-2.0
// mip_level: the MIP-level unit after Park et al., IEICE Electronics Express 2011, eq. (2), for
// the colour texture and the normal map of a hit (hits under the input rule below, the two
// levels in consecutive clocks).  Specification: model/mip.py
// (model/texture.py ray_length and mip_level) in the f24 engine, bit for bit:
//   Pl  = add(Pl0, mul(t, seg))                 eye-to-hit ray length
//   lod = sub(log2(Pl), log2Pb[tri][tex])       log2: the approximate unit f24_log2
//   L   = clamp(to_index(add(lod, 0.5)), 0, levels[tex] - 1)
//   and L = 0 when cfg_mip_en_i = 0 (the model's mip=False)
// to_index(add(lod, 0.5)) is f24_round_index (the word of f24_add and f24_to_index) with W =
// MIP_IDX_W = 7: floor, saturating to [-64, 63], NaN -> 0.  The model's to_index saturates at
// model.arith.INDEX_W = 20 bits instead; the clamp to [0, levels - 1] (levels <= 32) gives the
// same level from either, since both saturations lie outside [0, 31].  So a NaN t, seg or Pl0,
// Pl = NaN, a negative Pl (log2 NaN) or lod NaN give level 0; Pl = +-0 (log2 = -Inf) gives level
// 0; Pl = +Inf gives levels - 1.
//
// Fully pipelined, fixed latency: the two textures share one lod datapath, and one adder
// serves a hit's three additions (Pl, then the two lods).  A hit taken on an enabled edge with
// valid_i = 1 gives two results, each a valid_o clock with the hit's tag: the colour texture's
// level (tex_o = 0) pipe_pkg::mip_lat(ADD_LAT, MUL_LAT) enabled edges later (14 at the float
// units' paper depths (ADD_LAT, MUL_LAT) = (2, 1); 20 at (3, 2), pipe_pkg::MIP_LAT) and the
// normal map's (tex_o = 1) on the next enabled edge.
// Input rule (asserted: spacing, share_gap): valid_i must not be 1 on the enabled clock after a
// hit (the lod datapath), nor G or G + 1 enabled clocks after one, G = pipe_pkg::mip_gap(ADD_LAT)
// (6 at ADD_LAT 2, 9 at 3): the clocks in which the later hit's Pl addition would meet the
// earlier hit's lod additions on the adder.  G is 1 or 2 mod 4, so hits a multiple of 4 clocks
// apart always pass: dm_pipeline admits hits on a grid of 4 clocks.
// tag_o holds the hit's tag from its colour result until the next
// hit's colour result (the job register's tag holds the normal map's between jobs): dm_pipeline
// reads it for the normal map's lookup, held a clock, a clock after that result.  The
// conventions of view_calc otherwise: every register advances only while en_i is 1 (the
// enclosing pipeline's stall), valid is reset by rst_ni (synchronous, active low), data
// registers have no reset, results hold while en_i is 0.  Configuration (cfg_*, the table
// contents) must be static while busy; the table's write port works whatever en_i is.
//
// Stage schedule (S0 = the input ports; "a -> b": a unit takes operands in Sa, result in Sb;
// A = ADD_LAT, M = MUL_LAT, G = mip_gap(A); the stage numbers "x / y": x at (A, M) = (2, 1),
// y at (3, 2)):
//   S0               t seg                                       f24_mul      S0 -> S_PL
//                    Pl0 delayed S0 -> S_PL; tri delayed S0 -> S_TT
//   S_PL = M         the adder's operand registers <- Pl0, t seg (1 / 2)  register -> S_PLA
//   S_PLA = S_PL+1   Pl = Pl0 + t seg (2 / 3)                    f24_add      -> S_LOG
//   S_LOG = S_PLA+A  log2(Pl) (4 / 6)                            f24_log2     -> S_L2
//   S_L2 = S_LOG+3   log2(Pl) delayed PAD = G - A - 4 clocks (0 / 2: the pad that makes G
//                    1 or 2 mod 4)                               registers    -> S_JOB
//   S_TT = S_JOB-1   triangle table read (both textures; 6 / 10) tri_table    -> S_JOB
//   S_JOB = S_PL+G   the job (7 / 11): the adder's operand registers <- the colour job
//                    {log2(Pl), -log2Pb colour} now, the normal map's {log2(Pl), -log2Pb
//                    normal} (held) the next enabled clock        register     -> S_LOD
//   S_LOD = S_JOB+1  lod = log2(Pl) - log2Pb (8 / 12): the adder, G clocks after Pl's
//                                                                f24_add      -> S_HALF
//   S_HALF = S_LOD+A  floor(lod + 0.5) (10 / 15)    f24_round_index, A + 1 clocks -> S_CLMP
//                     (S_IDX = S_HALF+A: where f24_add's sum would enter f24_to_index)
//   S_CLMP = S_IDX+1  clamp to [0, levels[tex] - 1], mip_en (13 / 19)  register -> S_OUT
//   S_OUT = S_CLMP+1  outputs (14 / 20; straight from registers); the normal map's a clock
//                     after the colour's
// The adder takes its operands only from its operand registers, loaded by the select of the
// three additions (Pl in the clock a hit is in S_PL, the colour lod in S_JOB, the normal map's
// the clock after; never two at once under the input rule: asserted, share_free).  Its sum
// goes to both f24_log2 (read as Pl by the hit in S_LOG) and f24_round_index (read as lod by
// the job in S_HALF); each reads the other's sums too, which no valid result uses.
// log2 runs at LAT = F24_LOG2_LAT = 3 (table / product + sum / normalise + round: over 100 MHz;
// at its 2 clocks it limits the unit to about 50 MHz); the result is the same at either LAT.
// Float units: 1 f24_mul, 1 f24_add, 1 f24_log2, 1 f24_round_index (lod + 0.5 and its floor in
// one unit: before it, an f24_add and an f24_to_index #(.W(20))); a 2 x TRIS-word tri_table.
// (Before the adder was shared: 2 f24_add, MIP_LAT 13 / 17, a hit every other clock at most;
// before the textures shared the lod datapath: 5 f24_add and 2 f24_to_index, both levels of a
// hit per clock, MIP_LAT 12.)
module mip_level
  import f24_pkg::*;
  import pipe_pkg::*;
#(
  parameter int unsigned TAG_W = 8,   // side-band bits (fragment id, pixel, hit data, ...) carried
                                      // unchanged from tag_i to tag_o alongside the hit
  parameter int unsigned TRIS  = 16,  // triangle table entries
  parameter int unsigned TRI_W = (TRIS > 1) ? $clog2(TRIS) : 1,  // triangle id width
  // Latencies of the float units instantiated (their LAT parameters); the stage schedule and the
  // latency, pipe_pkg::mip_lat(ADD_LAT, MUL_LAT), follow them; the levels do not change.
  parameter int unsigned ADD_LAT = F24_ADD_LAT,  // f24_add, 2 .. 4
  parameter int unsigned MUL_LAT = F24_MUL_LAT   // f24_mul, 1 .. 3
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
  output logic                   valid_o,              // a texture's level (two per hit)
  output logic [TAG_W-1:0]       tag_o,                // the hit's tag (both results)
  output logic                   tex_o,                // 0: colour texture, 1: normal map
  output logic [MIP_LEVEL_W-1:0] level_o
);

  // Stage numbers ("x / y": at (ADD_LAT, MUL_LAT) = (2, 1) / (3, 2)); S_OUT = the latency (the
  // colour result).
  localparam int unsigned GAP    = mip_gap(ADD_LAT);          // 6 / 9
  localparam int unsigned S_PL   = MUL_LAT;                  // 1 / 2
  localparam int unsigned S_PLA  = S_PL + 1;                 // 2 / 3
  localparam int unsigned S_LOG  = S_PLA + ADD_LAT;          // 4 / 6
  localparam int unsigned S_L2   = S_LOG + F24_LOG2_LAT;     // 7 / 9
  localparam int unsigned S_JOB  = S_PL + GAP;               // 7 / 11
  localparam int unsigned PAD    = S_JOB - S_L2;             // 0 / 2
  localparam int unsigned S_TT   = S_JOB - TRI_TABLE_LAT;    // 6 / 10
  localparam int unsigned S_LOD  = S_JOB + 1;                // 8 / 12
  localparam int unsigned S_HALF = S_LOD + ADD_LAT;          // 10 / 15
  localparam int unsigned S_IDX  = S_HALF + ADD_LAT;         // 12 / 18
  localparam int unsigned S_CLMP = S_IDX + F24_TO_INDEX_LAT; // 13 / 19
  localparam int unsigned S_OUT  = S_CLMP + 1;               // 14 / 20
  if (S_OUT != mip_lat(ADD_LAT, MUL_LAT) || S_JOB < S_L2 || GAP % 4 == 0 || GAP % 4 == 3
      || GAP + 1 > S_JOB) begin : g_check_lat
    $error("mip_level: stage schedule does not add up to pipe_pkg::mip_lat");
  end

  // ---- S0: t seg; S_PL: Pl's operands; S_PLA: Pl; S_LOG: log2(Pl) ------------------------
  f24_t ts, sum, l2, l2_job;
  f24_t pl0_q [1:S_PL];                 // Pl0 in stages S1 .. S_PL
  f24_t op_a_q, op_b_q;                 // the adder's operands: Pl0, t seg / log2(Pl), -log2Pb
  f24_mul #(.LAT(MUL_LAT)) u_ts (.clk_i, .en_i, .a_i(t_i), .b_i(seg_i), .y_o(ts));
  // the one adder: Pl (a hit in S_PLA), the colour lod and the normal map's (jobs in S_LOD)
  f24_add #(.LAT(ADD_LAT)) u_add (.clk_i, .en_i, .a_i(op_a_q), .b_i(op_b_q), .y_o(sum));
  f24_log2 #(.LAT(F24_LOG2_LAT)) u_l2 (.clk_i, .en_i, .a_i(sum), .y_o(l2));
  f24_delay #(.W(24), .N(PAD)) u_pad (.clk_i, .en_i, .d_i(l2), .q_o(l2_job));

  // ---- S_TT: the triangle table ----------------------------------------------------------------
  logic [TRI_W-1:0] tri_q [1:S_TT];     // the triangle id in stages S1 .. S_TT
  f24_t pb [2];                         // S_JOB: log2 Pb of the colour texture, the normal map
  tri_table #(.TRIS(TRIS), .TRI_W(TRI_W)) u_table (
    .clk_i, .we_i(tt_we_i), .waddr_i(tt_waddr_i), .wdata_i(tt_wdata_i),
    .re_i(en_i), .raddr_i(tri_q[S_TT]), .rdata_colour_o(pb[0]), .rdata_normal_o(pb[1]));

  // ---- S_JOB: the jobs -----------------------------------------------------------------------
  // The hit's valid and tag reach S_JOB through u_hit; its colour job goes into the adder's
  // operand registers at once, its normal-map job (held in nrm_*) the enabled clock after.
  logic             v6;                 // a hit in S_JOB
  logic [TAG_W-1:0] tag6;
  logic             nrm_pend_q;         // the held normal-map job waits
  logic [TAG_W-1:0] nrm_tag_q;
  f24_t             nrm_l2_q, nrm_pb_q;
  logic             job_valid_q, job_tex_q;
  logic [TAG_W-1:0] job_tag_q;

  /* verilator lint_off UNUSEDSIGNAL */  // read: hit_v[1], [S_PL], [GAP], [GAP + 1]
  logic [S_JOB:1]   hit_v;              // a hit in S1 .. S_JOB
  /* verilator lint_on UNUSEDSIGNAL */
  pipe_valid_tag #(.TAG_W(TAG_W), .DEPTH(S_JOB)) u_hit (
    .clk_i, .rst_ni, .en_i, .valid_i, .tag_i, .valid_o(v6), .tag_o(tag6), .stage_valid_o(hit_v));

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      nrm_pend_q  <= 1'b0;
      job_valid_q <= 1'b0;
    end else if (en_i) begin
      nrm_pend_q  <= v6;
      job_valid_q <= v6 || nrm_pend_q;
    end
  end
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      if (v6) begin
        nrm_tag_q <= tag6;
        nrm_l2_q  <= l2_job;
        nrm_pb_q  <= pb[1];
      end
      job_tex_q <= !v6;
      job_tag_q <= v6 ? tag6 : nrm_tag_q;
      // the adder's operands: Pl's for a hit in S_PL, else the colour job, else the normal
      // map's (subtract: log2Pb's sign bit flipped)
      if (hit_v[S_PL]) begin
        op_a_q <= pl0_q[S_PL];
        op_b_q <= ts;
      end else begin
        op_a_q <= v6 ? l2_job : nrm_l2_q;
        op_b_q <= v6 ? {~pb[0][23], pb[0][22:0]} : {~nrm_pb_q[23], nrm_pb_q[22:0]};
      end
    end
  end

  // ---- S_LOD .. S_OUT: the job's texture ----------------------------------------------------
  logic signed [MIP_IDX_W-1:0] idx;
  logic                        tex_q [S_LOD+1:S_CLMP];  // the job's texture, S_LOD+1 .. S_CLMP
  logic [MIP_LEVEL_W:0]        levels;
  logic [MIP_LEVEL_W-1:0]      top;    // levels - 1 (0 for a count of 0)
  logic [MIP_LEVEL_W-1:0]      lvl, lvl_q;
  // S_LOD: lod = log2(Pl) - log2Pb on the adder (its sum in S_HALF)
  // S_HALF: floor(lod + 0.5) (to_index(add(lod, 0.5))), in the clocks of the add and the floor
  f24_round_index #(.W(MIP_IDX_W), .LAT(ADD_LAT + F24_TO_INDEX_LAT)) u_idx (
    .clk_i, .en_i, .a_i(sum), .idx_o(idx));
  // S_CLMP: clamp(idx, 0, levels - 1); level 0 with MIP mapping off
  // (a count of 0 acts as 1, one above 2^MIP_LEVEL_W as 2^MIP_LEVEL_W)
  assign levels = tex_q[S_CLMP] ? cfg_levels_normal_i : cfg_levels_colour_i;
  assign top = (levels == '0)         ? '0
             : levels[MIP_LEVEL_W]    ? '1
             :                          MIP_LEVEL_W'(levels - 1'b1);
  assign lvl = (!cfg_mip_en_i || idx < 0)         ? '0
             : (idx > $signed(MIP_IDX_W'(top))) ? top
             :                                    MIP_LEVEL_W'(idx);
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      tex_q[S_LOD+1] <= job_tex_q;
      for (int s = S_LOD + 2; s <= S_CLMP; s++) tex_q[s] <= tex_q[s-1];
      lvl_q <= lvl;
    end
  end
  assign level_o = lvl_q;

  // ---- delay lines: Pl0 to S_PL, tri to S_TT ---------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (en_i) begin
      pl0_q[1] <= pl0_i;
      for (int s = 2; s <= S_PL; s++) pl0_q[s] <= pl0_q[s-1];
      tri_q[1] <= tri_i;
      for (int s = 2; s <= S_TT; s++) tri_q[s] <= tri_q[s-1];
    end
  end

  // ---- valid, texture and tag of the job, S_LOD -> S_OUT ----------------------------------
  pipe_valid_tag #(.TAG_W(TAG_W + 1), .DEPTH(S_OUT - S_LOD)) u_valid_tag (
    .clk_i, .rst_ni, .en_i, .valid_i(job_valid_q), .tag_i({job_tex_q, job_tag_q}), .valid_o,
    .tag_o({tex_o, tag_o}), .stage_valid_o());

  // The simulation checks are in mip_level_assert.sv (bound into every instance).

endmodule
