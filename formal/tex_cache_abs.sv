// SPDX-License-Identifier: Apache-2.0
// tex_cache (formal model only; the pairs tasks of formal/dm_pipeline.sby read this file instead
// of rtl/cache/tex_cache.sv): the texture cache abstracted to what dm_pipeline's pairing of
// colour and normal-map results relies on: responses in request order, each with its request's
// tag (the real cache's rsp_tag_order, proven in formal/tex_cache.sby).  It holds up to CAP
// requests (their tags), takes a request whenever it has room and a free choice says so, and
// offers the oldest one's response whenever a free choice says so; the texels and the error bit
// are free values.  The AXI port is idle, the statistics zero.
module tex_cache
  import cache_pkg::*;
#(
  parameter int unsigned ADDR_W     = 32,  // the real cache's parameters (only TAG_W used)
  parameter int unsigned DATA_W     = 64,
  parameter int unsigned LINE_BYTES = 32,
  parameter int unsigned SETS       = 32,
  parameter int unsigned WAYS       = 4,
  parameter int unsigned MSHRS      = 16,
  parameter int unsigned FIFO_DEPTH = 64,
  parameter int unsigned ID_W       = 6,
  parameter int unsigned TAG_W      = 8,
  parameter int unsigned WIN_WORDS  = 2,
  parameter string       DIR_RAM    = "auto",
  parameter int unsigned CAP        = 3    // requests held (>= 2)
) (
  input  logic                     clk_i,
  input  logic                     rst_ni,
  input  logic                     req_valid_i,
  output logic                     req_ready_o,
  input  logic [3:0][ADDR_W-1:0]   req_addr_i,
  input  logic [TAG_W-1:0]         req_tag_i,
  output logic                     rsp_valid_o,
  input  logic                     rsp_ready_i,
  output logic [3:0][31:0]         rsp_texel_o,
  output logic                     rsp_err_o,
  output logic [TAG_W-1:0]         rsp_tag_o,
  output logic [ID_W-1:0]          m_axi_arid,
  output logic [ADDR_W-1:0]        m_axi_araddr,
  output logic [7:0]               m_axi_arlen,
  output logic [2:0]               m_axi_arsize,
  output logic [1:0]               m_axi_arburst,
  output logic                     m_axi_arvalid,
  input  logic                     m_axi_arready,
  input  logic [ID_W-1:0]          m_axi_rid,
  input  logic [DATA_W-1:0]        m_axi_rdata,
  input  logic [1:0]               m_axi_rresp,
  input  logic                     m_axi_rlast,
  input  logic                     m_axi_rvalid,
  output logic                     m_axi_rready,
  input  logic                     clr_stats_i,
  output logic [47:0]              stat_requests_o,
  output logic [47:0]              stat_quad_hits_o,
  output logic [47:0]              stat_lookups_o,
  output logic [47:0]              stat_line_misses_o,
  output logic [47:0]              stat_texel_hits_o,
  output logic [47:0]              stat_bytes_o
);

  localparam int unsigned PW = $clog2(CAP);
  localparam int unsigned CW = $clog2(CAP + 1);

  // Free choices: undriven nets, which SymbiYosys makes free inputs every clock (nets, not
  // variables: see formal/traverse_system_abs.sv).
  wire              take_en;   // a request is taken if there is room
  wire              show_en;   // the oldest request's response is offered
  wire [3:0][31:0]  texel;
  wire              err;

  logic [TAG_W-1:0] q_tag_q [CAP];   // the requests held, oldest at rp_q
  logic [PW-1:0]    rp_q, wp_q;
  logic [CW-1:0]    cnt_q;
  logic             push, pop;

  assign req_ready_o = take_en && cnt_q != CW'(CAP);
  assign rsp_valid_o = show_en && cnt_q != '0;
  assign rsp_tag_o   = q_tag_q[rp_q];
  assign rsp_texel_o = texel;
  assign rsp_err_o   = err;
  assign push = req_valid_i && req_ready_o;
  assign pop  = rsp_valid_o && rsp_ready_i;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      rp_q  <= '0;
      wp_q  <= '0;
      cnt_q <= '0;
    end else begin
      if (push) wp_q <= (wp_q == PW'(CAP - 1)) ? '0 : wp_q + PW'(1);
      if (pop)  rp_q <= (rp_q == PW'(CAP - 1)) ? '0 : rp_q + PW'(1);
      cnt_q <= cnt_q + CW'(push) - CW'(pop);
    end
    if (push) q_tag_q[wp_q] <= req_tag_i;
  end

  assign {m_axi_arid, m_axi_araddr, m_axi_arlen, m_axi_arsize, m_axi_arburst} = '0;
  assign m_axi_arvalid = 1'b0;
  assign m_axi_rready  = 1'b1;
  assign {stat_requests_o, stat_quad_hits_o, stat_lookups_o, stat_line_misses_o,
          stat_texel_hits_o, stat_bytes_o} = '0;

  logic unused;
  assign unused = ^{req_addr_i, m_axi_arready, m_axi_rid, m_axi_rdata, m_axi_rresp, m_axi_rlast,
                    m_axi_rvalid, clr_stats_i};

endmodule
