// SPDX-License-Identifier: Apache-2.0
// traverse_unit: ray / height-field intersection through the max-mipmap pyramid, bit-exact with
// model.traverse.trace(pyr, rays, method, "f24") (hit, t, u, v, invalid, iterations).
//
//   ray stream -> traverse_setup (first mode, SETUP_LAT = 26 stages) -> setup FIFO
//              -> traverse_loop (second mode, ring of loop_depth(MUL_LAT) = 22 slots at
//                 MUL_LAT 2, 19 at MUL_LAT 1; one height lookup per pass)
//              -> result FIFO -> result stream (rays leave in completion order, not input order)
//
// Flow control (valid never depends on ready):
//   - ray_ready_o: a credit counter covers setup and the setup FIFO (SETUP_FIFO_DEPTH rays), so
//     the setup pipeline never stalls and its FIFO never overflows.  It is also 0 in three
//     clocks of every four (traverse_setup's in_ready_o, a free-running phase): traverse_setup
//     shares its float units over 4 clocks, so it takes a ray every 4th clock at most (above
//     what the loop finishes: a ray takes several passes of the ring, and the back end
//     takes a hit every 4th clock at most).
//   - The loop takes a new ray only into an empty slot at its entry (re-circulating rays first).
//   - Result back-pressure never loses a ray: a finished ray leaves the ring only when the result
//     FIFO has room, otherwise it keeps circulating (no lookups) and tries again a pass later; an
//     invalid / never-entering ray from setup waits at the head of the setup FIFO.  With the result
//     stream stalled, the ring fills with finished rays and stops admitting new ones.
//
// Height lookups (master; the height cache is the slave): lk_valid_o, lk_addr_o (byte address =
// base + level_off[k] + (cy * (N >> k) + cx) * bytes per texel), lk_wide_o (1: 16-bit texel);
// exactly LOOKUP_LAT = 3 clocks later rs_valid_i, rs_hit_i, rs_err_i, rs_data_i (8-bit codes in
// the low byte).  rs_hit_i = 0 (or no response): the ray goes round again unchanged and the pass
// does not count as an iteration.  rs_err_i = 1: the ray finishes with res_err_o = 1.
//
// Configuration (cfg_*): static while the unit holds rays (idle_o = 1 to change it) and stable at
// least 7 clocks before the next ray enters (one register stage, which loads while idle_o = 1,
// then traverse_setup derives the clip start time from it in 3 + ADD_LAT = 6 more at its
// package-default float depths (3, 2)).  A ray may enter in any clock after the unit turns idle:
// the start time is held until the shared units that compute it have been idle long enough.
// tb/harness/traverse_words.py packs it from a Pyramid and a method name.
module traverse_unit
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W             = 16,
  parameter int unsigned SETUP_FIFO_DEPTH = 32,  // power of two, > SETUP_LAT (26)
  parameter int unsigned RES_FIFO_DEPTH   = 16,  // power of two
  parameter int unsigned CNT_W            = 32,  // statistics counters
  parameter bit          XOR_PATH         = 1'b1, // 0: no XOR descent path (traverse_loop)
  parameter int unsigned MUL_LAT          = pipe_pkg::F24_MUL_LAT, // f24_mul latency (traverse_loop)
  parameter bit          PARK             = 1'b0, // 1: park queue for missed rays (traverse_loop)
  parameter int unsigned PARK_DEPTH       = PARK_DEPTH_DEF, // park queue entries (traverse_loop)
  parameter int unsigned PARK_WAIT        = 16,   // clocks before a parked ray beats new rays (traverse_loop)
  parameter int unsigned PARK_MAX         = 4 * loop_depth(MUL_LAT) // bound on a parked ray's wait (traverse_loop)
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  // configuration
  input  logic [3:0]                        cfg_method_i,      // model.traverse.METHOD_CODES
  input  logic [DIM_W-1:0]                  cfg_width_i,       // W
  input  logic [DIM_W-1:0]                  cfg_height_i,      // H
  input  logic [LVL_W-1:0]                  cfg_root_level_i,  // n (N = 2^n >= max(W, H))
  input  logic                              cfg_bits16_i,      // 1: unorm16 heights, 0: unorm8
  input  logic [ADDR_W-1:0]                 cfg_base_i,        // byte address of the pyramid
  input  logic [CODE_W-1:0]                 cfg_root_code_i,   // root texel code (clip)
  input  logic [ITER_W-1:0]                 cfg_iter_cap_i,    // traverse.iteration_cap(pyr)
  // the height pyramid's level-offset table (traverse_addr: LUT RAM, not reset, static while
  // busy): write hlt_wdata_i as level hlt_waddr_i's byte offset from cfg_base_i
  input  logic                              hlt_we_i,
  input  logic [LVL_W-1:0]                  hlt_waddr_i,
  input  logic [ADDR_W-1:0]                 hlt_wdata_i,
  // rays in
  input  logic                              ray_valid_i,
  output logic                              ray_ready_o,
  input  logic [ID_W-1:0]                   ray_id_i,
  input  f24_t                              ray_u0_i,
  input  f24_t                              ray_v0_i,
  input  f24_t                              ray_du_i,
  input  f24_t                              ray_dv_i,
  // results out
  output logic                              res_valid_o,
  input  logic                              res_ready_i,
  output logic [ID_W-1:0]                   res_id_o,
  output f24_t                              res_t_o,        // hit time (when res_hit_o)
  output f24_t                              res_u_o,        // hit position (when res_hit_o)
  output f24_t                              res_v_o,
  output logic                              res_hit_o,
  output logic                              res_invalid_o,
  output logic                              res_capped_o,   // stopped by the iteration cap
  output logic                              res_err_o,      // a height read returned an error
  output logic [ITER_W-1:0]                 res_iters_o,
  // height lookups
  output logic                              lk_valid_o,
  output logic [ADDR_W-1:0]                 lk_addr_o,
  output logic                              lk_wide_o,
  input  logic                              rs_valid_i,
  input  logic                              rs_hit_i,
  input  logic                              rs_err_i,
  input  logic [CODE_W-1:0]                 rs_data_i,
  // statistics (since reset, wrapping)
  output logic [CNT_W-1:0]                  stat_cycles_o,     // clocks with a ray in the unit
  output logic [CNT_W-1:0]                  stat_rays_in_o,
  output logic [CNT_W-1:0]                  stat_rays_out_o,
  output logic [CNT_W-1:0]                  stat_iters_o,      // lookups that returned data
  output logic [CNT_W-1:0]                  stat_lookups_o,
  output logic [CNT_W-1:0]                  stat_crossings_o,  // iterations that crossed
  output logic [CNT_W-1:0]                  stat_level_ups_o,  // ... and went up a level
  output logic [CNT_W-1:0]                  stat_descents_o,   // iterations that descended
  output logic                              idle_o             // no ray in the unit
);

  localparam int unsigned SF_AW = $clog2(SETUP_FIFO_DEPTH);
  localparam int unsigned RF_AW = $clog2(RES_FIFO_DEPTH);
  localparam int unsigned SF_W  = ID_W + $bits(ray_t);
  localparam int unsigned RF_W  = ID_W + $bits(result_t);

  // The configuration register (decoded): it loads while the unit is idle, the only time the
  // configuration may change, and holds otherwise.
  cfg_t cfg;
  always_ff @(posedge clk_i) begin
    if (idle_o) begin
      cfg <= '{policy: decode_method(cfg_method_i), width: cfg_width_i, height: cfg_height_i,
               n: cfg_root_level_i, bits16: cfg_bits16_i, base: cfg_base_i,
               root_code: cfg_root_code_i, iter_cap: cfg_iter_cap_i};
    end
  end

  // ---- rays in: credits for setup + setup FIFO ---------------------------------------------
  logic in_fire, out_fire;
  logic [SF_AW:0] sf_used_q;  // rays in setup and in the setup FIFO
  logic           sf_pop;
  logic           su_in_ready;  // traverse_setup's phase: one clock in four
  assign ray_ready_o = (sf_used_q < (SF_AW+1)'(SETUP_FIFO_DEPTH)) && su_in_ready;
  assign in_fire     = ray_valid_i && ray_ready_o;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      sf_used_q <= '0;
    end else begin
      sf_used_q <= sf_used_q + (SF_AW+1)'(in_fire) - (SF_AW+1)'(sf_pop);
    end
  end

  // ---- first mode ----------------------------------------------------------------------------
  logic            su_valid;
  logic [ID_W-1:0] su_id;
  ray_t            su_ray;
  logic [SETUP_BUSY_W-1:0] su_busy;
  traverse_setup #(.ID_W(ID_W)) u_setup (
    .clk_i, .rst_ni, .cfg_i(cfg), .idle_i(idle_o), .in_ready_o(su_in_ready),
    .in_valid_i(in_fire), .in_id_i(ray_id_i), .in_u0_i(ray_u0_i), .in_v0_i(ray_v0_i),
    .in_du_i(ray_du_i), .in_dv_i(ray_dv_i),
    .out_valid_o(su_valid), .out_id_o(su_id), .out_ray_o(su_ray), .busy_o(su_busy)
  );

  logic [SF_W-1:0] sf_head;
  logic            sf_full, sf_empty;
  logic [SF_AW:0]  sf_count;
  logic            unused_sf_full;
  assign unused_sf_full = sf_full;  // the credit counter keeps the setup FIFO from filling up
  traverse_fifo #(.W(SF_W), .DEPTH(SETUP_FIFO_DEPTH), .RAM_STYLE("block")) u_setup_fifo (
    .clk_i, .rst_ni, .wr_i(su_valid), .wr_data_i({su_id, su_ray}), .rd_i(sf_pop),
    .rd_data_o(sf_head), .full_o(sf_full), .empty_o(sf_empty), .count_o(sf_count)
  );

  // ---- second mode ---------------------------------------------------------------------------
  logic            rf_push, rf_full, rf_empty;
  logic [ID_W-1:0] lp_res_id;
  result_t         lp_res;
  logic [RF_W-1:0] rf_head;
  logic [RF_AW:0]  rf_count;
  logic            st_iter, st_down, st_cross, st_up;
  logic [LOOP_BUSY_W-1:0] lp_busy;
  traverse_loop #(
    .ID_W(ID_W), .MUL_LAT(MUL_LAT), .XOR_PATH(XOR_PATH), .PARK(PARK), .PARK_DEPTH(PARK_DEPTH),
    .PARK_WAIT(PARK_WAIT), .PARK_MAX(PARK_MAX)
  ) u_loop (
    .clk_i, .rst_ni, .cfg_i(cfg), .hlt_we_i, .hlt_waddr_i, .hlt_wdata_i,
    .new_valid_i(!sf_empty), .new_id_i(sf_head[SF_W-1 -: ID_W]),
    .new_ray_i(ray_t'(sf_head[$bits(ray_t)-1:0])), .new_pop_o(sf_pop),
    .res_full_i(rf_full), .res_push_o(rf_push), .res_id_o(lp_res_id), .res_o(lp_res),
    .lk_valid_o, .lk_addr_o, .lk_wide_o, .rs_valid_i, .rs_hit_i, .rs_err_i, .rs_data_i,
    .st_iter_o(st_iter), .st_down_o(st_down), .st_cross_o(st_cross), .st_up_o(st_up),
    .busy_o(lp_busy)
  );

  // ---- results out ---------------------------------------------------------------------------
  result_t rf_res;
  traverse_fifo #(.W(RF_W), .DEPTH(RES_FIFO_DEPTH), .RAM_STYLE("block")) u_res_fifo (
    .clk_i, .rst_ni, .wr_i(rf_push), .wr_data_i({lp_res_id, lp_res}), .rd_i(out_fire),
    .rd_data_o(rf_head), .full_o(rf_full), .empty_o(rf_empty), .count_o(rf_count)
  );
  assign res_valid_o   = !rf_empty;
  assign out_fire      = res_valid_o && res_ready_i;
  assign res_id_o      = rf_head[RF_W-1 -: ID_W];
  assign rf_res        = result_t'(rf_head[$bits(result_t)-1:0]);
  assign res_t_o       = rf_res.t;
  assign res_u_o       = rf_res.u;
  assign res_v_o       = rf_res.v;
  assign res_hit_o     = rf_res.hit;
  assign res_invalid_o = rf_res.invalid;
  assign res_capped_o  = rf_res.capped;
  assign res_err_o     = rf_res.err;
  assign res_iters_o   = rf_res.iters;

  // ---- statistics ----------------------------------------------------------------------------
  // Rays in the unit: in minus out.  At most SETUP_FIFO_DEPTH in setup and its FIFO (the
  // credits above), the ring's slots and park queue (busy_o < 2^LOOP_BUSY_W) and RES_FIFO_DEPTH
  // results.
  localparam int unsigned MAX_INFLIGHT = SETUP_FIFO_DEPTH + (1 << LOOP_BUSY_W) - 1
                                         + RES_FIFO_DEPTH;
  localparam int unsigned IF_W = $clog2(MAX_INFLIGHT + 1);
  logic [IF_W-1:0] inflight_q;
  assign idle_o = (inflight_q == '0);
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      inflight_q       <= '0;
      stat_cycles_o    <= '0;
      stat_rays_in_o   <= '0;
      stat_rays_out_o  <= '0;
      stat_iters_o     <= '0;
      stat_lookups_o   <= '0;
      stat_crossings_o <= '0;
      stat_level_ups_o <= '0;
      stat_descents_o  <= '0;
    end else begin
      inflight_q       <= inflight_q + IF_W'(in_fire) - IF_W'(out_fire);
      stat_cycles_o    <= stat_cycles_o + CNT_W'(!idle_o);
      stat_rays_in_o   <= stat_rays_in_o + CNT_W'(in_fire);
      stat_rays_out_o  <= stat_rays_out_o + CNT_W'(out_fire);
      stat_iters_o     <= stat_iters_o + CNT_W'(st_iter);
      stat_lookups_o   <= stat_lookups_o + CNT_W'(lk_valid_o);
      stat_crossings_o <= stat_crossings_o + CNT_W'(st_cross);
      stat_level_ups_o <= stat_level_ups_o + CNT_W'(st_up);
      stat_descents_o  <= stat_descents_o + CNT_W'(st_down);
    end
  end

  // The simulation checks are in traverse_unit_assert.sv (bound into every instance).

endmodule
