// SPDX-License-Identifier: Apache-2.0
// traverse_system (formal model only; formal/traverse_rings.sby reads this file instead of
// rtl/traverse/traverse_system.sv): a ring abstracted to what traverse_rings relies on for its
// ray ids.  It holds up to CAP rays (their ids), takes a ray whenever it has room and a free
// choice says so, and offers any ray it holds as its result, at any time, in any order; a result
// shown stays with its id until it is taken (the result FIFO's head: traverse_unit_assert's
// res_out_stable).  So every ray taken comes back exactly once, the guarantee of the real ring
// (traverse_loop's id proof, the FIFOs' data-order proofs; docs/formal.md).  The AXI port is
// idle, the statistics zero, the result fields other than the id free.
module traverse_system
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned RAY_ID_W         = 16,
  parameter int unsigned SETUP_FIFO_DEPTH = 32,  // (unused: the real ring's parameters)
  parameter int unsigned RES_FIFO_DEPTH   = 16,
  parameter int unsigned UNIT_CNT_W       = 48,
  parameter int unsigned LINE_BYTES       = 32,
  parameter int unsigned SETS             = 256,
  parameter int unsigned WAYS             = 4,
  parameter int unsigned MSHRS            = 4,
  parameter int unsigned AXI_ID_W         = 4,
  parameter int unsigned AXI_DATA_W       = 64,
  parameter bit          PARK             = 1'b0, // (unused: the real ring's park queue)
  parameter int unsigned PARK_DEPTH       = PARK_DEPTH_DEF,  // (unused)
  parameter int unsigned PARK_WAIT        = 16,  // (unused)
  parameter int unsigned PARK_MAX         = 4 * LOOP_DEPTH,  // (unused)
  parameter int unsigned CAP              = 2    // rays held
) (
  input  logic                              clk_i,
  input  logic                              rst_ni,
  input  logic [3:0]                        cfg_method_i,
  input  logic [DIM_W-1:0]                  cfg_width_i,
  input  logic [DIM_W-1:0]                  cfg_height_i,
  input  logic [LVL_W-1:0]                  cfg_root_level_i,
  input  logic                              cfg_bits16_i,
  input  logic [ADDR_W-1:0]                 cfg_base_i,
  input  logic [CODE_W-1:0]                 cfg_root_code_i,
  input  logic [ITER_W-1:0]                 cfg_iter_cap_i,
  input  logic                              hlt_we_i,
  input  logic [LVL_W-1:0]                  hlt_waddr_i,
  input  logic [ADDR_W-1:0]                 hlt_wdata_i,
  input  logic                              ray_valid_i,
  output logic                              ray_ready_o,
  input  logic [RAY_ID_W-1:0]               ray_id_i,
  input  f24_t                              ray_u0_i,
  input  f24_t                              ray_v0_i,
  input  f24_t                              ray_du_i,
  input  f24_t                              ray_dv_i,
  output logic                              res_valid_o,
  input  logic                              res_ready_i,
  output logic [RAY_ID_W-1:0]               res_id_o,
  output f24_t                              res_t_o,
  output f24_t                              res_u_o,
  output f24_t                              res_v_o,
  output logic                              res_hit_o,
  output logic                              res_invalid_o,
  output logic                              res_capped_o,
  output logic                              res_err_o,
  output logic [ITER_W-1:0]                 res_iters_o,
  output logic [AXI_ID_W-1:0]               m_axi_arid,
  output logic [ADDR_W-1:0]                 m_axi_araddr,
  output logic [7:0]                        m_axi_arlen,
  output logic [2:0]                        m_axi_arsize,
  output logic [1:0]                        m_axi_arburst,
  output logic                              m_axi_arvalid,
  input  logic                              m_axi_arready,
  input  logic [AXI_ID_W-1:0]               m_axi_rid,
  input  logic [AXI_DATA_W-1:0]             m_axi_rdata,
  input  logic [1:0]                        m_axi_rresp,
  input  logic                              m_axi_rlast,
  input  logic                              m_axi_rvalid,
  output logic                              m_axi_rready,
  output logic [UNIT_CNT_W-1:0]             stat_cycles_o,
  output logic [UNIT_CNT_W-1:0]             stat_rays_in_o,
  output logic [UNIT_CNT_W-1:0]             stat_rays_out_o,
  output logic [UNIT_CNT_W-1:0]             stat_iters_o,
  output logic [UNIT_CNT_W-1:0]             stat_lookups_o,
  output logic [UNIT_CNT_W-1:0]             stat_crossings_o,
  output logic [UNIT_CNT_W-1:0]             stat_level_ups_o,
  output logic [UNIT_CNT_W-1:0]             stat_descents_o,
  input  logic                              clr_stats_i,
  output logic [47:0]                       stat_cache_hits_o,
  output logic [47:0]                       stat_cache_misses_o,
  output logic [47:0]                       stat_mem_bytes_o,
  output logic [47:0]                       stat_mem_lines_o,
  output logic                              idle_o
);

  localparam int unsigned CW = $clog2(CAP + 1);

  // Free choices: undriven nets, which SymbiYosys makes free inputs every clock (declared as
  // nets: read_slang gives an undriven variable the constant x, which optimisation may resolve
  // differently at each use).
  wire                    take_en;   // the ring takes a ray if it has room
  wire                    show_en;   // a result is offered
  wire [$clog2(CAP)-1:0]  pick;      // which held ray

  logic [CAP-1:0]               h_v_q;    // slot k holds a ray
  logic [CAP-1:0][RAY_ID_W-1:0] h_id_q;
  logic                         o_v_q;    // a result is shown: held slot o_k_q
  logic [$clog2(CAP)-1:0]       o_k_q;

  // the first free slot
  logic             room;
  logic [$clog2(CAP)-1:0] fk;
  always_comb begin
    room = 1'b0;
    fk   = '0;
    for (int k = CAP - 1; k >= 0; k--) begin
      if (!h_v_q[k]) begin
        room = 1'b1;
        fk   = ($clog2(CAP))'(k);
      end
    end
  end

  assign ray_ready_o = room && take_en;
  assign res_valid_o = o_v_q;
  assign res_id_o    = h_id_q[o_k_q];

  logic taken;
  assign taken = o_v_q && res_ready_i;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      h_v_q <= '0;
      o_v_q <= 1'b0;
    end else begin
      if (taken) h_v_q[o_k_q] <= 1'b0;
      if (ray_valid_i && ray_ready_o) begin
        h_v_q[fk]  <= 1'b1;
        h_id_q[fk] <= ray_id_i;
      end
      // a new result: any held ray (not the one leaving now), when none is shown
      if (!o_v_q || taken) begin
        o_v_q <= show_en && 32'(pick) < CAP && h_v_q[pick] && !(taken && pick == o_k_q);
        o_k_q <= pick;
      end
    end
  end

  assign idle_o = (h_v_q == '0);
  assign {res_t_o, res_u_o, res_v_o} = '0;
  assign {res_hit_o, res_invalid_o, res_capped_o, res_err_o} = '0;
  assign res_iters_o = '0;
  assign {m_axi_arid, m_axi_araddr, m_axi_arlen, m_axi_arsize, m_axi_arburst} = '0;
  assign m_axi_arvalid = 1'b0;
  assign m_axi_rready  = 1'b1;
  assign {stat_cycles_o, stat_rays_in_o, stat_rays_out_o, stat_iters_o, stat_lookups_o,
          stat_crossings_o, stat_level_ups_o, stat_descents_o} = '0;
  assign {stat_cache_hits_o, stat_cache_misses_o, stat_mem_bytes_o, stat_mem_lines_o} = '0;

endmodule
