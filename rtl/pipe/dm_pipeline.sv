// SPDX-License-Identifier: Apache-2.0
// dm_pipeline: the displacement-mapping unit of Park et al. 2013, Fig. 6, from fragments to colours.
//
//   fragments -> [slot + context] -> view_calc -> FIFO #0 -> traverse_system (traverse unit,
//   height cache, AXI port H) -> hit: mip_level -> tex_addr (colour, then normal map) ->
//   request FIFOs -> tex_cache (AXI port T) -> tex_filter -> shade_unit -> out FIFO \
//                                 miss / invalid: -> miss FIFO ------------------> arbiter -> pixels
//
// The model it mirrors: model/shade.py render_pixels (view unit, trace, MIP level, two bilinear
// lookups, shading); every RTL pixel equals the f24 engine's.
//
// Contexts.  Each fragment in flight owns a slot (SLOTS of them, a free list); the slot id is the
// ray id inside traverse_system, and per-slot registers hold what later stages need (pixel id,
// Pl0, triangle, du, dv, seg, the traversal's flags).  A fragment is accepted only when a slot is
// free, so nothing in the unit can overflow on slots; the slot returns to the free list when its
// pixel leaves.
//
// Flow control.  The fixed-latency units (view_calc, mip_level, tex_addr, tex_filter,
// shade_unit) never stall (en_i = 1); admission into them is by credit instead (pipe_credit; the
// paper's controller that keeps FIFO #0 from overflowing):
//   - a fragment enters view_calc only if FIFO #0 has room for it and every fragment already in
//     view_calc (fragments in view_calc + FIFO #0 count < F0_DEPTH), and not in the 3 clocks
//     after another (view_calc computes z, x and y in consecutive clocks on the same float
//     units; a fragment every 4th clock matches the back end's hit every 4th clock);
//   - a hit leaves traverse_system only if the texture-request FIFOs have room for it and every
//     hit between admission and the FIFOs (< REQ_DEPTH) and the out FIFO has room for
//     every hit not yet out (< OUT_DEPTH);
//   - tex_filter takes a quad every other clock at most (its float units serve two clocks'
//     operations), so tex_cache's responses are taken at its ready (rsp_ready = the filter's
//     ready_o, a register, 1 on every other clock); until then a response waits in the cache's
//     output buffer, and a full cache queue stops taking requests (the request FIFOs and their
//     credit hold the hits back).  Nothing behind the filter backs up: shade_unit and the out
//     FIFO take every filtered quad (the out credit above);
//   - a miss / invalid ray leaves traverse_system when the miss FIFO has room;
//   - a hit is admitted at most every 4th clock: a hit needs two filtered quads and the filter
//     takes one per two clocks, so the back end takes a hit per 4 clocks at most and admitting
//     hits more often gains nothing.  That leaves room for the shared units in front of it:
//     mip_level's lod datapath serves both textures (the colour level, the normal map's the
//     clock after; one adder for Pl and both lods, which forbids hits pipe_pkg::mip_gap or one
//     more clocks apart: hits are admitted on a grid of 4 clocks, so a multiple of 4 apart)
//     and one tex_addr both lookups, each lookup as two axis items (u, v) in consecutive
//     clocks, so a hit's two lookups fill 4 clocks (colour, then the normal map's held a
//     clock: nl_*).
// The colour and normal-map requests of a pixel are pushed together into two FIFOs and sent to
// the cache alternately (colour first), so its responses, and the filter's results, come in
// pairs in that order (the cache and the filter keep order; asserted: tf_pairs); a pixel reaches
// shade_unit every four clocks at most.  The requests pass a register slice (u_rq_skid) on the
// way: the cache's req_ready_o ends at its register, and the cache takes them from its output
// register (a clock later).
//
// Outputs.  Pixels leave in completion order with their pixel id (px_id_o); px_hit_o /
// px_invalid_o / px_err_o (a height or texel read returned an AXI error) / px_iters_o describe
// the pixel; a pixel without a hit gets cfg_miss_rgb_i.  The output is a register (payload stable
// while px_valid_o && !px_ready_i).
module dm_pipeline
  import f24_pkg::*;
  import traverse_pkg::*;
  import pipe_pkg::*;
  import shade_pkg::*;
#(
  parameter int unsigned PIX_W      = 20,   // pixel id width (px_id_o = frag_id_i)
  parameter int unsigned SLOTS      = 128,  // fragments in flight (power of two)
  parameter int unsigned N_RINGS    = 1,    // traverse rings, each with its own height cache
  parameter bit          PARK       = 1'b0, // 1: each ring parks missed rays (traverse_loop)
  parameter int unsigned PARK_DEPTH = traverse_pkg::PARK_DEPTH_DEF, // park queue entries per ring (traverse_loop)
  parameter int unsigned PARK_WAIT  = 16,   // clocks before a parked ray beats new rays (traverse_loop)
  parameter int unsigned PARK_MAX   = 4 * traverse_pkg::LOOP_DEPTH, // bound on a parked ray's wait
  parameter int unsigned TRIS       = 16,   // triangle table entries
  parameter int unsigned F0_DEPTH   = 16,   // FIFO #0 (power of two)
  parameter int unsigned SETUP_DEPTH = 32,  // setup FIFO per ring (traverse_unit's SETUP_FIFO_DEPTH; power of two, > 26)
  parameter int unsigned REQ_DEPTH  = 16,   // texture-request FIFOs, pixels (power of two)
  parameter int unsigned OUT_DEPTH  = 64,   // shaded-pixel FIFO (power of two): hits in the back end
  parameter int unsigned MISS_DEPTH = 16,   // miss FIFO (power of two)
  parameter int unsigned H_ID_W     = 4,    // AXI ID width, height port
  parameter int unsigned T_ID_W     = 6,    // AXI ID width, texture port (> log2 of tex_cache MSHRS)
  // Cache geometry (README "Pipeline performance": chosen by a sweep over the scenes and views)
  parameter int unsigned T_LINE_BYTES = 128, // tex_cache line (32 texels of one row)
  parameter int unsigned T_SETS     = 32,   // tex_cache sets per sub-cache (4 sub-caches)
  parameter int unsigned T_WAYS     = 4,    // tex_cache ways: 4 x 32 x 4 x 128 B = 64 KiB
  parameter int unsigned T_WIN_WORDS = 2,   // tex_cache data-RAM window, words (+1 overlap word)
  parameter string       T_DIR_RAM  = "auto", // tex_cache's tags and reference counts: "auto"
                                            // (LUT RAM) or "block" (32 block RAMs, about 1,650
                                            // LUT4 fewer; tex_cache DIR_RAM)
  parameter int unsigned H_LINE_BYTES = 32, // height_cache line (one AXI burst per fill)
  parameter int unsigned H_SETS     = 512,  // height_cache sets per ring (power of two)
  parameter int unsigned H_WAYS     = 4,    // height_cache ways: 512 x 4 x 32 B = 64 KiB
  parameter int unsigned H_MSHRS    = 4,    // height_cache line fills in flight per ring (H_ID_W >
                                            // log2(N_RINGS) + log2(H_MSHRS))
  parameter int unsigned AXI_DATA_W = 64,   // AXI data width (both ports; <= 256: tex_cache window)
  parameter int unsigned TRI_W      = (TRIS > 1) ? $clog2(TRIS) : 1  // triangle id width
) (
  input  logic                                 clk_i,
  input  logic                                 rst_ni,
  // configuration (static while busy): traversal
  input  logic [3:0]                           cfg_method_i,
  input  logic [DIM_W-1:0]                     cfg_width_i,
  input  logic [DIM_W-1:0]                     cfg_height_i,
  input  logic [LVL_W-1:0]                     cfg_root_level_i,
  input  logic                                 cfg_bits16_i,
  input  logic [ADDR_W-1:0]                    cfg_base_i,
  input  logic [CODE_W-1:0]                    cfg_root_code_i,
  input  logic [ITER_W-1:0]                    cfg_iter_cap_i,
  // view unit, MIP levels, shading, miss colour
  input  f24_t                                 cfg_depth_i,          // D
  input  logic                                 cfg_mip_en_i,
  input  logic [MIP_LEVEL_W:0]                 cfg_levels_colour_i,
  input  logic [MIP_LEVEL_W:0]                 cfg_levels_normal_i,
  input  shade_cfg_t                           cfg_shade_i,
  input  logic [2:0][7:0]                      cfg_miss_rgb_i,
  // textures: [0] colour, [1] normal map
  input  f24_t [1:0]                           cfg_tex_su_i,
  input  f24_t [1:0]                           cfg_tex_sv_i,
  input  logic [1:0][TEX_ADDR_W-1:0]           cfg_tex_base_i,
  // level tables (LUT RAM; not reset, static while busy): write lvt_wdata_i into word
  // lvt_waddr_i = {kind [1:0], texture, level} (pipe_pkg::LVT_*): kind 1 the height pyramid's
  // level offset from cfg_base_i (every ring's traverse_addr), 2 a texture level's byte offset
  // from cfg_tex_base_i, 3 its size {height [31:16], width [15:0]} (tex_addr); kind 0 ignored
  input  logic                                 lvt_we_i,
  input  logic [LVT_ADDR_W-1:0]                lvt_waddr_i,
  input  logic [31:0]                          lvt_wdata_i,
  // triangle table (log2 Pb per triangle and texture)
  input  logic                                 tt_we_i,
  input  logic [TRI_W:0]                       tt_waddr_i,
  input  f24_t                                 tt_wdata_i,
  // fragments in
  input  logic                                 frag_valid_i,
  output logic                                 frag_ready_o,
  input  logic [PIX_W-1:0]                     frag_id_i,
  input  f24_t                                 frag_u0_i,
  input  f24_t                                 frag_v0_i,
  input  f24_t                                 frag_pl0_i,
  input  logic [TRI_W-1:0]                     frag_tri_i,
  input  f24_t [8:0]                           frag_tbn_i,   // T (0..2), B (3..5), N (6..8)
  input  f24_t [2:0]                           frag_view_i,
  // pixels out
  output logic                                 px_valid_o,
  input  logic                                 px_ready_i,
  output logic [PIX_W-1:0]                     px_id_o,
  output logic [2:0][7:0]                      px_rgb_o,
  output logic                                 px_hit_o,
  output logic                                 px_invalid_o,
  output logic                                 px_err_o,
  output logic [ITER_W-1:0]                    px_iters_o,
  // AXI4 read master: heights
  output logic [H_ID_W-1:0]                    m_axi_h_arid,
  output logic [ADDR_W-1:0]                    m_axi_h_araddr,
  output logic [7:0]                           m_axi_h_arlen,
  output logic [2:0]                           m_axi_h_arsize,
  output logic [1:0]                           m_axi_h_arburst,
  output logic                                 m_axi_h_arvalid,
  input  logic                                 m_axi_h_arready,
  input  logic [H_ID_W-1:0]                    m_axi_h_rid,
  input  logic [AXI_DATA_W-1:0]                m_axi_h_rdata,
  input  logic [1:0]                           m_axi_h_rresp,
  input  logic                                 m_axi_h_rlast,
  input  logic                                 m_axi_h_rvalid,
  output logic                                 m_axi_h_rready,
  // AXI4 read master: textures
  output logic [T_ID_W-1:0]                    m_axi_t_arid,
  output logic [TEX_ADDR_W-1:0]                m_axi_t_araddr,
  output logic [7:0]                           m_axi_t_arlen,
  output logic [2:0]                           m_axi_t_arsize,
  output logic [1:0]                           m_axi_t_arburst,
  output logic                                 m_axi_t_arvalid,
  input  logic                                 m_axi_t_arready,
  input  logic [T_ID_W-1:0]                    m_axi_t_rid,
  input  logic [AXI_DATA_W-1:0]                m_axi_t_rdata,
  input  logic [1:0]                           m_axi_t_rresp,
  input  logic                                 m_axi_t_rlast,
  input  logic                                 m_axi_t_rvalid,
  output logic                                 m_axi_t_rready,
  // statistics (48 bits, since reset or clr_stats_i)
  input  logic                                 clr_stats_i,
  output logic [47:0]                          stat_cycles_o,      // clocks with a pixel inside
  output logic [47:0]                          stat_pixels_o,      // pixels out
  output logic [47:0]                          stat_iters_o,       // traversal iterations
  output logic [47:0]                          stat_h_hits_o,      // height-cache lookups hit
  output logic [47:0]                          stat_h_misses_o,
  output logic [47:0]                          stat_h_bytes_o,
  output logic [47:0]                          stat_t_requests_o,  // texture quads
  output logic [47:0]                          stat_t_quad_hits_o,
  output logic [47:0]                          stat_t_line_misses_o,
  output logic [47:0]                          stat_t_texel_hits_o, // texels whose line hit
  output logic [47:0]                          stat_t_bytes_o,
  output logic                                 idle_o              // no pixel inside
);

  localparam int unsigned SLOT_W = $clog2(SLOTS);
  localparam int unsigned OUT_CW = $clog2(OUT_DEPTH) + 1;
  localparam int unsigned REQ_CW = $clog2(REQ_DEPTH) + 1;
  localparam int unsigned F0_CW  = $clog2(F0_DEPTH) + 1;

  if (LVL_W > TEX_LVL_W || ADDR_W != 32 || TEX_ADDR_W != 32) begin : g_check_lvt
    $error("dm_pipeline: a level-table word address holds a height level, its data 32 bits");
  end
  if ((1 << SLOT_W) != SLOTS || SLOTS < 2) begin : g_check_slots
    $error("dm_pipeline: SLOTS must be a power of two >= 2");
  end

  // ---- slots: free list (filled with 0 .. SLOTS-1 after reset) and per-slot context ----------
  logic              init_q;          // filling the free list
  logic [SLOT_W:0]   init_cnt_q;
  logic              free_push, free_pop, free_empty, free_full;
  logic [SLOT_W-1:0] free_push_id, free_head;
  logic [SLOT_W:0]   free_count;
  logic [SLOT_W:0]   live_q;          // slots in use (pixels inside)

  traverse_fifo #(.W(SLOT_W), .DEPTH(SLOTS), .RAM_STYLE("block")) u_free (
    .clk_i, .rst_ni, .wr_i(free_push), .wr_data_i(free_push_id), .rd_i(free_pop),
    .rd_data_o(free_head), .full_o(free_full), .empty_o(free_empty), .count_o(free_count));

  // Per-slot context, all of it block RAM (a 128-deep LUT RAM costs about 16 LUT4s per bit and
  // read port).  Every table is read only into a register of its own, loaded by its reader's
  // enable, which synthesis takes as the block RAM's read register: the fragment's id and the
  // traversal's result flags into the output register, Pl0, the triangle and seg at a hit's
  // admission (mi_ctx_q, mi_seg_q), du and dv at the colour result of the pixel's texture pair
  // (sh_duv_q, read for the normal-map result that follows it).  A slot is written only while
  // no reader can address it (at the fragment's acceptance, at view_calc's output), so the
  // tables need no read-during-write logic (no_rw_check).
  typedef struct packed {
    f24_t             pl0;
    logic [TRI_W-1:0] tri_id;
  } ctx_frag_t;
  typedef struct packed {
    logic              inv;
    logic              herr;
    logic [ITER_W-1:0] iters;
  } ctx_res_t;
  (* ram_style = "block" *)              logic [PIX_W-1:0] ctx_pix_q  [SLOTS];
  (* ram_style = "block", no_rw_check *) ctx_frag_t        ctx_frag_q [SLOTS];
  (* ram_style = "block" *)              ctx_res_t         ctx_res_q  [SLOTS];
  (* ram_style = "block", no_rw_check *) f24_t [1:0]       ctx_duv_q  [SLOTS];  // {du, dv}
  (* ram_style = "block", no_rw_check *) f24_t             ctx_seg_q  [SLOTS];

  // ---- accept: fragment -> view_calc ---------------------------------------------------------
  logic [F0_CW-1:0]  vc_cnt;          // fragments inside view_calc
  logic              f0_wr, f0_rd, f0_full, f0_empty;
  logic [F0_CW-1:0]  f0_count;
  logic              acc;

  logic              f0_room;

  // Not in the 3 clocks after an accepted fragment: view_calc's z, x and y share its float
  // units (a fragment every 4th clock at most, the rate the back end takes hits at).
  logic [2:0] acc_q;  // [k]: a fragment was accepted k + 1 clocks ago
  always_ff @(posedge clk_i) begin
    if (!rst_ni) acc_q <= '0;
    else         acc_q <= {acc_q[1:0], acc};
  end
  assign frag_ready_o = !init_q && !free_empty && f0_room && acc_q == '0;
  assign acc      = frag_valid_i && frag_ready_o;
  assign free_pop = acc;

  always_ff @(posedge clk_i) begin
    if (acc) begin
      ctx_pix_q[free_head]  <= frag_id_i;
      ctx_frag_q[free_head] <= '{pl0: frag_pl0_i, tri_id: frag_tri_i};
    end
  end

  localparam int unsigned VC_TAG_W = SLOT_W + 48;
  logic                vc_valid;
  logic [VC_TAG_W-1:0] vc_tag;
  f24_t                vc_du, vc_dv, vc_seg;

  view_calc #(.TAG_W(VC_TAG_W)) u_view (
    .clk_i, .rst_ni, .en_i(1'b1), .cfg_depth_i,
    .valid_i(acc), .tag_i({free_head, frag_u0_i, frag_v0_i}),
    .tx_i(frag_tbn_i[0]), .ty_i(frag_tbn_i[1]), .tz_i(frag_tbn_i[2]),
    .bx_i(frag_tbn_i[3]), .by_i(frag_tbn_i[4]), .bz_i(frag_tbn_i[5]),
    .nx_i(frag_tbn_i[6]), .ny_i(frag_tbn_i[7]), .nz_i(frag_tbn_i[8]),
    .vx_i(frag_view_i[0]), .vy_i(frag_view_i[1]), .vz_i(frag_view_i[2]),
    .valid_o(vc_valid), .tag_o(vc_tag), .du_o(vc_du), .dv_o(vc_dv), .seg_o(vc_seg));

  // The controller that keeps FIFO #0 from overflowing: fragments inside view_calc plus FIFO
  // #0's fill never exceed its depth.
  pipe_credit #(.LIMIT(F0_DEPTH), .CW(F0_CW)) u_f0_credit (
    .clk_i, .rst_ni, .take_i(acc), .give_i(vc_valid), .held_i(f0_count), .room_o(f0_room),
    .count_o(vc_cnt));

  logic [SLOT_W-1:0] vc_slot;
  assign vc_slot = vc_tag[VC_TAG_W-1 -: SLOT_W];
  always_ff @(posedge clk_i) begin
    if (vc_valid) begin
      ctx_duv_q[vc_slot] <= {vc_du, vc_dv};
      ctx_seg_q[vc_slot] <= vc_seg;
    end
  end

  // ---- FIFO #0 -> traverse_system ------------------------------------------------------------
  localparam int unsigned F0_W = SLOT_W + 4 * 24;
  logic [F0_W-1:0] f0_head;
  assign f0_wr = vc_valid;

  traverse_fifo #(.W(F0_W), .DEPTH(F0_DEPTH), .RAM_STYLE("block")) u_fifo0 (
    .clk_i, .rst_ni, .wr_i(f0_wr), .wr_data_i({vc_tag, vc_du, vc_dv}), .rd_i(f0_rd),
    .rd_data_o(f0_head), .full_o(f0_full), .empty_o(f0_empty), .count_o(f0_count));

  logic              ray_ready;
  logic              res_valid, res_ready, res_hit, res_inv, res_capped, res_herr;
  logic [SLOT_W-1:0] res_id;
  f24_t              res_t, res_u, res_v;
  logic [ITER_W-1:0] res_iters;
  logic [47:0]       t_cycles, t_rays_in, t_rays_out, t_lookups, t_cross, t_ups, t_desc;
  logic              t_idle;
  logic [47:0]       h_lines;

  assign f0_rd = !f0_empty && ray_ready;

  traverse_rings #(.N_RINGS(N_RINGS), .SETUP_FIFO_DEPTH(SETUP_DEPTH), .PARK(PARK),
                   .PARK_DEPTH(PARK_DEPTH),
                   .PARK_WAIT(PARK_WAIT), .PARK_MAX(PARK_MAX), .MSHRS(H_MSHRS),
                   .RAY_ID_W(SLOT_W), .AXI_ID_W(H_ID_W),
                   .AXI_DATA_W(AXI_DATA_W), .LINE_BYTES(H_LINE_BYTES), .SETS(H_SETS),
                   .WAYS(H_WAYS)) u_trav (
    .clk_i, .rst_ni,
    .cfg_method_i, .cfg_width_i, .cfg_height_i, .cfg_root_level_i, .cfg_bits16_i, .cfg_base_i,
    .cfg_root_code_i, .cfg_iter_cap_i,
    .hlt_we_i(lvt_we_i && lvt_waddr_i[LVT_ADDR_W-1 -: 2] == 2'(LVT_HEIGHT_OFF)),
    .hlt_waddr_i(lvt_waddr_i[LVL_W-1:0]), .hlt_wdata_i(lvt_wdata_i),
    .ray_valid_i(!f0_empty), .ray_ready_o(ray_ready), .ray_id_i(f0_head[F0_W-1 -: SLOT_W]),
    .ray_u0_i(f0_head[95:72]), .ray_v0_i(f0_head[71:48]), .ray_du_i(f0_head[47:24]),
    .ray_dv_i(f0_head[23:0]),
    .res_valid_o(res_valid), .res_ready_i(res_ready), .res_id_o(res_id), .res_t_o(res_t),
    .res_u_o(res_u), .res_v_o(res_v), .res_hit_o(res_hit), .res_invalid_o(res_inv),
    .res_capped_o(res_capped), .res_err_o(res_herr), .res_iters_o(res_iters),
    .m_axi_arid(m_axi_h_arid), .m_axi_araddr(m_axi_h_araddr), .m_axi_arlen(m_axi_h_arlen),
    .m_axi_arsize(m_axi_h_arsize), .m_axi_arburst(m_axi_h_arburst),
    .m_axi_arvalid(m_axi_h_arvalid), .m_axi_arready(m_axi_h_arready), .m_axi_rid(m_axi_h_rid),
    .m_axi_rdata(m_axi_h_rdata), .m_axi_rresp(m_axi_h_rresp), .m_axi_rlast(m_axi_h_rlast),
    .m_axi_rvalid(m_axi_h_rvalid), .m_axi_rready(m_axi_h_rready),
    .stat_cycles_o(t_cycles), .stat_rays_in_o(t_rays_in), .stat_rays_out_o(t_rays_out),
    .stat_iters_o(stat_iters_o), .stat_lookups_o(t_lookups), .stat_crossings_o(t_cross),
    .stat_level_ups_o(t_ups), .stat_descents_o(t_desc), .clr_stats_i,
    .stat_cache_hits_o(stat_h_hits_o), .stat_cache_misses_o(stat_h_misses_o),
    .stat_mem_bytes_o(stat_h_bytes_o), .stat_mem_lines_o(h_lines),
    .idle_o(t_idle));

  // ---- results: hits to the texture path, the rest to the miss FIFO --------------------------
  logic              miss_wr, miss_rd, miss_full, miss_empty;
  logic [SLOT_W-1:0] miss_head;
  logic [$clog2(MISS_DEPTH):0] miss_count;
  logic [REQ_CW-1:0] req_cnt;     // hits admitted whose normal-map request has not left its FIFO
  logic [OUT_CW-1:0] hit_cnt;     // hits admitted and not yet out
  logic              req_room, hit_room;
  logic              hit_adm, req_done, hit_out;

  // A hit is admitted only in the clocks where hit_ph_q, a free-running count of 4, is 0: so
  // never in the 3 clocks after one (its two lookups take 4 clocks of tex_addr), and hits are a
  // multiple of 4 clocks apart, never pipe_pkg::mip_gap or one more (1 and 2 mod 4), which
  // mip_level's shared adder forbids.  (Without the grid, with only those two distances held
  // back, a hit 5 clocks after another shifts the ones behind it off the grid, and each later
  // pair 9 or 10 apart waits: the two-ring frame of make render took 2.4% more clocks; with it,
  // 0.3%.)  dm_pipeline_assert's hit_spacing checks the first rule; the formal invariant
  // inv_spacing relates the grid to the clocks since the last hit.
  logic [1:0] hit_ph_q;   // the admission grid: a hit only where it is 0
  always_ff @(posedge clk_i) begin
    if (!rst_ni) hit_ph_q <= '0;
    else         hit_ph_q <= hit_ph_q + 2'd1;
  end
  assign res_ready = res_hit ? (req_room && hit_room && hit_ph_q == '0)
                             : !miss_full;
  assign hit_adm   = res_valid && res_ready && res_hit;
  assign miss_wr   = res_valid && res_ready && !res_hit;

  always_ff @(posedge clk_i) begin
    if (res_valid && res_ready) begin
      ctx_res_q[res_id] <= '{inv: res_inv, herr: res_herr, iters: res_iters};
    end
  end

  traverse_fifo #(.W(SLOT_W), .DEPTH(MISS_DEPTH)) u_miss (
    .clk_i, .rst_ni, .wr_i(miss_wr), .wr_data_i(res_id), .rd_i(miss_rd), .rd_data_o(miss_head),
    .full_o(miss_full), .empty_o(miss_empty), .count_o(miss_count));

  // hit -> mip_level (context read at admission: Pl0, triangle, seg).  The hit and its context
  // reach mip_level through two registers: the first (mi0_*, and the context tables' read
  // registers mi_ctx_q, mi_seg_q, which synthesis takes into the block RAMs), then mi_q, all
  // fabric, so the first stage's multiplier (t seg) always takes its operands from fabric
  // registers (a block RAM's 4.1 ns clock-to-out, 3 ns of routing and the multiplier's exponent
  // logic were once the routed top's slowest path, 17.6 ns).  (A hit is admitted every 4th clock
  // at most, so mip_level still never sees two in consecutive clocks.)
  localparam int unsigned MIP_TAG_W = SLOT_W + 48;
  typedef struct packed {
    logic [MIP_TAG_W-1:0] tag;  // {slot, u, v}
    f24_t                 t;
    f24_t                 seg;
    f24_t                 pl0;
    logic [TRI_W-1:0]     tri_id;
  } mip_in_t;
  logic    [1:0]        mi_valid_q;
  logic [MIP_TAG_W-1:0] mi0_tag_q;
  f24_t                 mi0_t_q;
  ctx_frag_t            mi_ctx_q;
  f24_t                 mi_seg_q;
  mip_in_t              mi_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) mi_valid_q <= '0;
    else         mi_valid_q <= {mi_valid_q[0], hit_adm};
    if (hit_adm) begin
      mi0_tag_q <= {res_id, res_u, res_v};
      mi0_t_q   <= res_t;
      mi_ctx_q  <= ctx_frag_q[res_id];
      mi_seg_q  <= ctx_seg_q[res_id];
    end
    if (mi_valid_q[0]) mi_q <= '{tag: mi0_tag_q, t: mi0_t_q, seg: mi_seg_q, pl0: mi_ctx_q.pl0,
                                 tri_id: mi_ctx_q.tri_id};
  end

  logic                 mip_valid, mip_tex;
  logic [MIP_TAG_W-1:0] mip_tag;
  logic [MIP_LEVEL_W-1:0] mip_lvl;

  mip_level #(.TAG_W(MIP_TAG_W), .TRIS(TRIS)) u_mip (
    .clk_i, .rst_ni, .en_i(1'b1), .cfg_mip_en_i, .cfg_levels_colour_i, .cfg_levels_normal_i,
    .tt_we_i, .tt_waddr_i, .tt_wdata_i,
    .valid_i(mi_valid_q[1]), .tag_i(mi_q.tag), .t_i(mi_q.t), .seg_i(mi_q.seg),
    .pl0_i(mi_q.pl0), .tri_i(mi_q.tri_id),
    .valid_o(mip_valid), .tag_o(mip_tag), .tex_o(mip_tex), .level_o(mip_lvl));

  // mip -> one address unit for both textures: mip_level gives a hit's colour level (texture 0)
  // and, the clock after, its normal map's (texture 1).  tex_addr (NTEX = 2) takes a lookup every
  // other clock at most (u, then v on its units), so the colour lookup goes straight in and the
  // normal map's waits a clock: only its level and valid bit are held (nl_*), since mip_level's
  // tag_o (slot, u, v) holds the hit's tag from its colour result until the next hit's colour
  // result, 4 clocks later at the earliest (asserted: nl_tag_held).  Hits are admitted at most
  // every 4th clock, so the held lookup never meets the next hit's colour lookup.  (Holding
  // the normal map's result in mip_level instead would cost one register less but give
  // mip_level's two results a clock apart; holding the tag here another 55 registers.)
  localparam int unsigned REQ_W = 4 * TEX_ADDR_W + 48;  // {fx, fy, a11, a10, a01, a00}
  logic                    ta_valid, ta_tex;
  logic [SLOT_W-1:0]       ta_slot;
  logic [REQ_W-1:0]        ta_req;
  logic [TEX_ADDR_W-1:0]   ta_a00, ta_a01, ta_a10, ta_a11;
  f24_t                    ta_fx, ta_fy;

  logic                   nl_valid_q;  // the normal map's lookup, held a clock
  logic [MIP_LEVEL_W-1:0] nl_lvl_q;
  logic                   ta_in_valid;
  logic [MIP_LEVEL_W-1:0] ta_in_lvl;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) nl_valid_q <= 1'b0;
    else         nl_valid_q <= mip_valid && mip_tex;
  end
  always_ff @(posedge clk_i) nl_lvl_q <= mip_lvl;
  assign ta_in_valid = (mip_valid && !mip_tex) || nl_valid_q;
  assign ta_in_lvl   = nl_valid_q ? nl_lvl_q : mip_lvl;

  tex_addr #(.TAG_W(SLOT_W + 1), .ADDR_W(TEX_ADDR_W), .NTEX(2)) u_addr (
    .clk_i, .rst_ni, .en_i(1'b1),
    .cfg_su_i(cfg_tex_su_i), .cfg_sv_i(cfg_tex_sv_i), .cfg_base_i(cfg_tex_base_i),
    .lvt_we_i(lvt_we_i && lvt_waddr_i[LVT_ADDR_W-1]), .lvt_waddr_i(lvt_waddr_i[LVT_ADDR_W-2:0]),
    .lvt_wdata_i,
    .valid_i(ta_in_valid), .tag_i({mip_tag[MIP_TAG_W-1 -: SLOT_W], nl_valid_q}),
    .tex_i(nl_valid_q), .u_i(mip_tag[47:24]), .v_i(mip_tag[23:0]), .level_i(ta_in_lvl),
    .valid_o(ta_valid), .tag_o({ta_slot, ta_tex}), .addr00_o(ta_a00), .addr01_o(ta_a01),
    .addr10_o(ta_a10), .addr11_o(ta_a11), .fx_o(ta_fx), .fy_o(ta_fy));
  assign ta_req = {ta_fx, ta_fy, ta_a11, ta_a10, ta_a01, ta_a00};

  // request FIFOs: colour {slot, request}, normal {request}; sent alternately, colour first
  logic              rq_c_empty, rq_n_empty, rq_c_full, rq_n_full, rq_sel_q;
  logic [SLOT_W+REQ_W-1:0] rq_c_head;
  logic [REQ_W-1:0]  rq_n_head, rq_head;
  logic [SLOT_W-1:0] rq_slot;
  logic              rq_valid, rq_ready;  // the alternating select's stream (into u_rq_skid)
  logic              rq_take;             // a request leaves its FIFO
  logic              tc_req_valid, tc_req_ready;
  logic [REQ_CW-1:0] rq_c_count, rq_n_count;

  traverse_fifo #(.W(SLOT_W + REQ_W), .DEPTH(REQ_DEPTH),
                .RAM_STYLE("block")) u_rq_c (
    .clk_i, .rst_ni, .wr_i(ta_valid && !ta_tex), .wr_data_i({ta_slot, ta_req}),
    .rd_i(rq_take && !rq_sel_q), .rd_data_o(rq_c_head), .full_o(rq_c_full),
    .empty_o(rq_c_empty), .count_o(rq_c_count));
  traverse_fifo #(.W(REQ_W), .DEPTH(REQ_DEPTH), .RAM_STYLE("block")) u_rq_n (
    .clk_i, .rst_ni, .wr_i(ta_valid && ta_tex), .wr_data_i(ta_req),
    .rd_i(rq_take && rq_sel_q), .rd_data_o(rq_n_head), .full_o(rq_n_full),
    .empty_o(rq_n_empty), .count_o(rq_n_count));

  // The slot of the pair being sent (the colour entry's, kept for the normal-map request).
  logic [SLOT_W-1:0] pair_slot_q;
  assign rq_head  = rq_sel_q ? rq_n_head : rq_c_head[REQ_W-1:0];
  assign rq_slot  = rq_sel_q ? pair_slot_q : rq_c_head[SLOT_W+REQ_W-1 -: SLOT_W];
  assign rq_valid = rq_sel_q ? !rq_n_empty : !rq_c_empty;
  assign rq_take  = rq_valid && rq_ready;

  always_ff @(posedge clk_i) begin
    if (!rst_ni)      rq_sel_q <= 1'b0;
    else if (rq_take) rq_sel_q <= !rq_sel_q;
  end
  always_ff @(posedge clk_i) begin
    if (rq_take && !rq_sel_q) pair_slot_q <= rq_slot;
  end

  // The requests reach the cache through a register slice (skid_buffer, REG_OUT 1): its
  // ready_o is a register, so the cache's req_ready_o (its front's pass queue) ends there
  // instead of running on into the request FIFOs' read pointers and block-RAM read addresses
  // (the worst path of a routed top), and the cache's front takes the request from its output
  // register instead of through the FIFO select (rq_sel_q, whose 170 loads made the next one).
  // One clock of latency, the same rate (a request a clock).  req_done, the request credit's
  // return, is a normal-map request leaving its FIFO (into the slice), which is the room the
  // credit keeps: from registers (the FIFO's empty flag, the slice's ready_o).  With the
  // cache's handshake there instead, the return waited on the cache front's pass selection
  // and ran to the count by the admission, far from the cache (once a routed top's worst
  // path, docs/synthesis.md).
  localparam int unsigned RS_W = 1 + SLOT_W + REQ_W;  // {normal?, slot, request}
  logic [RS_W-1:0] tc_req;

  skid_buffer #(.W(RS_W), .REG_OUT(1'b1)) u_rq_skid (
    .clk_i, .rst_ni, .valid_i(rq_valid), .ready_o(rq_ready), .data_i({rq_sel_q, rq_slot, rq_head}),
    .valid_o(tc_req_valid), .ready_i(tc_req_ready), .data_o(tc_req));
  assign req_done = rq_take && rq_sel_q;

  // tex_cache: tag = {slot, normal?, fx, fy}
  localparam int unsigned TC_TAG_W = SLOT_W + 1 + 48;
  logic                 tc_rsp_valid, tc_rsp_err;
  logic                 tf_ready;       // the filter takes the response at the edge
  logic [3:0][31:0]     tc_rsp_texel;
  logic [TC_TAG_W-1:0]  tc_rsp_tag;
  logic [47:0]          tc_lookups;

  tex_cache #(.ADDR_W(TEX_ADDR_W), .DATA_W(AXI_DATA_W), .LINE_BYTES(T_LINE_BYTES), .SETS(T_SETS),
              .WAYS(T_WAYS), .ID_W(T_ID_W), .TAG_W(TC_TAG_W), .WIN_WORDS(T_WIN_WORDS),
              .DIR_RAM(T_DIR_RAM)) u_tc (
    .clk_i, .rst_ni,
    .req_valid_i(tc_req_valid), .req_ready_o(tc_req_ready),
    .req_addr_i(tc_req[4*TEX_ADDR_W-1:0]),  // [0] a00, [1] a01, [2] a10, [3] a11
    .req_tag_i({tc_req[REQ_W +: SLOT_W], tc_req[RS_W-1], tc_req[REQ_W-1 -: 48]}),
    .rsp_valid_o(tc_rsp_valid), .rsp_ready_i(tf_ready), .rsp_texel_o(tc_rsp_texel),
    .rsp_err_o(tc_rsp_err), .rsp_tag_o(tc_rsp_tag),
    .m_axi_arid(m_axi_t_arid), .m_axi_araddr(m_axi_t_araddr), .m_axi_arlen(m_axi_t_arlen),
    .m_axi_arsize(m_axi_t_arsize), .m_axi_arburst(m_axi_t_arburst),
    .m_axi_arvalid(m_axi_t_arvalid), .m_axi_arready(m_axi_t_arready), .m_axi_rid(m_axi_t_rid),
    .m_axi_rdata(m_axi_t_rdata), .m_axi_rresp(m_axi_t_rresp), .m_axi_rlast(m_axi_t_rlast),
    .m_axi_rvalid(m_axi_t_rvalid), .m_axi_rready(m_axi_t_rready),
    .clr_stats_i, .stat_requests_o(stat_t_requests_o), .stat_quad_hits_o(stat_t_quad_hits_o),
    .stat_lookups_o(tc_lookups), .stat_line_misses_o(stat_t_line_misses_o),
    .stat_texel_hits_o(stat_t_texel_hits_o), .stat_bytes_o(stat_t_bytes_o));

  // tex_filter (a quad every other clock at most, at its ready_o; tag = {slot, normal?, err})
  localparam int unsigned TF_TAG_W = SLOT_W + 2;
  logic                tf_valid;
  logic [TF_TAG_W-1:0] tf_tag;
  f24_t                tf_r, tf_g, tf_b, tf_a;

  tex_filter #(.TAG_W(TF_TAG_W)) u_filter (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(tc_rsp_valid), .ready_o(tf_ready),
    .tag_i({tc_rsp_tag[TC_TAG_W-1 -: SLOT_W + 1], tc_rsp_err}),
    .t00_i(tc_rsp_texel[0]), .t01_i(tc_rsp_texel[1]), .t10_i(tc_rsp_texel[2]),
    .t11_i(tc_rsp_texel[3]), .fx_i(tc_rsp_tag[47:24]), .fy_i(tc_rsp_tag[23:0]),
    .valid_o(tf_valid), .tag_o(tf_tag), .r_o(tf_r), .g_o(tf_g), .b_o(tf_b), .a_o(tf_a));

  // pair the colour (first) and normal-map (second) results -> shade_unit
  f24_t [2:0] col_q;
  logic       col_err_q;
  logic       sh_in_valid;
  logic [SLOT_W-1:0] sh_in_slot;
  assign sh_in_valid = tf_valid && tf_tag[1];
  assign sh_in_slot  = tf_tag[TF_TAG_W-1 -: SLOT_W];
  f24_t [1:0] sh_duv_q;  // the ray's {du, dv}: ctx_duv_q's read register (block RAM)
  always_ff @(posedge clk_i) begin
    if (tf_valid && !tf_tag[1]) begin
      col_q     <= {tf_b, tf_g, tf_r};
      col_err_q <= tf_tag[0];
      sh_duv_q  <= ctx_duv_q[sh_in_slot];  // the colour result's slot = the normal map's (tf_pairs)
    end
  end

  logic              sh_valid;
  logic [SLOT_W:0]   sh_tag;
  logic [2:0][7:0]   sh_rgb;

  shade_unit #(.TAG_W(SLOT_W + 1)) u_shade (
    .clk_i, .rst_ni, .en_i(1'b1), .cfg_i(cfg_shade_i), .valid_i(sh_in_valid),
    .tag_i({sh_in_slot, col_err_q | tf_tag[0]}), .col_i(col_q), .nrm_i({tf_b, tf_g, tf_r}),
    .du_i(sh_duv_q[1]), .dv_i(sh_duv_q[0]),
    .valid_o(sh_valid), .tag_o(sh_tag), .rgb_o(sh_rgb));

  // shaded FIFO {slot, err, rgb}
  localparam int unsigned OUT_W = SLOT_W + 1 + 24;
  logic             out_rd, out_full, out_empty;
  logic [OUT_W-1:0] out_head;
  logic [OUT_CW-1:0] out_count;

  traverse_fifo #(.W(OUT_W), .DEPTH(OUT_DEPTH)) u_out (
    .clk_i, .rst_ni, .wr_i(sh_valid), .wr_data_i({sh_tag, sh_rgb}), .rd_i(out_rd),
    .rd_data_o(out_head), .full_o(out_full), .empty_o(out_empty), .count_o(out_count));

  // Credits of the back end: a hit is admitted only when both request FIFOs and the out FIFO
  // will have room for it whenever it arrives (the counts span the units in front of them).
  pipe_credit #(.LIMIT(REQ_DEPTH), .CW(REQ_CW)) u_req_credit (
    .clk_i, .rst_ni, .take_i(hit_adm), .give_i(req_done), .held_i('0), .room_o(req_room),
    .count_o(req_cnt));
  pipe_credit #(.LIMIT(OUT_DEPTH), .CW(OUT_CW)) u_out_credit (
    .clk_i, .rst_ni, .take_i(hit_adm), .give_i(hit_out), .held_i('0), .room_o(hit_room),
    .count_o(hit_cnt));

  // ---- output register: shaded pixels first, then misses -------------------------------------
  logic              o_valid_q, o_hit_q, o_err_q;
  logic [SLOT_W-1:0] o_slot_q;
  logic [2:0][7:0]   o_rgb_q;
  logic              o_load;
  logic [SLOT_W-1:0] o_slot_d;        // the slot the output register loads
  logic [PIX_W-1:0]  o_pix_q;         // its context, read as it loads (block RAM read registers)
  ctx_res_t          o_res_q;

  assign o_load  = !o_valid_q || px_ready_i;
  assign out_rd  = o_load && !out_empty;
  assign miss_rd = o_load && out_empty && !miss_empty;
  assign hit_out = out_rd;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) o_valid_q <= 1'b0;
    else if (o_load) o_valid_q <= !out_empty || !miss_empty;
  end
  assign o_slot_d = out_rd ? out_head[OUT_W-1 -: SLOT_W] : miss_head;
  always_ff @(posedge clk_i) begin
    if (out_rd || miss_rd) begin
      o_pix_q <= ctx_pix_q[o_slot_d];
      o_res_q <= ctx_res_q[o_slot_d];
    end
  end
  always_ff @(posedge clk_i) begin
    if (out_rd) begin
      o_slot_q <= out_head[OUT_W-1 -: SLOT_W];
      o_err_q  <= out_head[24];
      o_rgb_q  <= out_head[23:0];
      o_hit_q  <= 1'b1;
    end else if (miss_rd) begin
      o_slot_q <= miss_head;
      o_err_q  <= 1'b0;
      o_rgb_q  <= cfg_miss_rgb_i;
      o_hit_q  <= 1'b0;
    end
  end

  assign px_valid_o   = o_valid_q;
  assign px_id_o      = o_pix_q;
  assign px_rgb_o     = o_rgb_q;
  assign px_hit_o     = o_hit_q;
  assign px_invalid_o = o_res_q.inv;
  assign px_err_o     = o_err_q | o_res_q.herr;
  assign px_iters_o   = o_res_q.iters;

  // ---- slot free list: init after reset, then one free per pixel out -------------------------
  logic px_done;
  assign px_done = px_valid_o && px_ready_i;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      init_q     <= 1'b1;
      init_cnt_q <= '0;
    end else if (init_q) begin
      init_cnt_q <= init_cnt_q + (SLOT_W+1)'(1);
      if (init_cnt_q == (SLOT_W+1)'(SLOTS - 1)) init_q <= 1'b0;
    end
  end
  assign free_push    = init_q || px_done;
  assign free_push_id = init_q ? init_cnt_q[SLOT_W-1:0] : o_slot_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) live_q <= '0;
    else         live_q <= live_q + (SLOT_W+1)'(acc) - (SLOT_W+1)'(px_done);
  end

  // ---- statistics -----------------------------------------------------------------------------
  logic [47:0] cyc_q, pix_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni || clr_stats_i) begin
      cyc_q <= '0;
      pix_q <= '0;
    end else begin
      if (live_q != '0) cyc_q <= cyc_q + 48'd1;
      if (px_done)      pix_q <= pix_q + 48'd1;
    end
  end
  assign stat_cycles_o = cyc_q;
  assign stat_pixels_o = pix_q;
  assign idle_o        = (live_q == '0) && !init_q;

  // Unused here: the traversal's other counters (the harness reads them through hierarchy).
  logic unused;
  assign unused = ^{t_cycles, t_rays_in, t_rays_out, t_lookups, t_cross, t_ups, t_desc, t_idle,
                    res_capped, tc_lookups, free_full, rq_c_full, rq_n_full, out_full,
                    f0_full, h_lines, miss_count, vc_cnt, req_cnt, hit_cnt,
                    rq_c_count, rq_n_count, tf_a, out_count};

  // The simulation checks are in dm_pipeline_assert.sv (bound into every instance).

endmodule
