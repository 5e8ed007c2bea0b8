// SPDX-License-Identifier: Apache-2.0
// frag_dma_tb: frag_dma in every configuration tb/frag_dma checks, side by side in one build:
// g_case[i] holds frag_dma with DATA_W = DATA_W_OF[i], MAX_BURST = MAX_BURST_OF[i], FIFO_RECS =
// FIFO_RECS_OF[i] (ARCACHE and ARPROT as the test sets them) and its own copy of the unit's
// ports (named as the ports, the AXI read master's m_axi_* too), so the cocotb test drives and
// checks each through the hierarchy (dut.g_case[i].frag_ready_i, ...) and puts its own
// cocotbext-axi memory on each instance's m_axi_* signals, with its own reset; only the clock is
// shared.  The table is the test's CASES (the test reads the parameters back and stops if they
// differ).
module frag_dma_tb
  import f24_pkg::*;
  import pidm_pkg::*;
(
  input logic clk_i
);

  localparam int unsigned NCASE   = 3;
  localparam int unsigned ADDR_W  = 32;            // AXI address width (frag_dma's default)
  localparam int unsigned ID_W    = 4;             // AXI ID width (frag_dma's default)
  localparam int unsigned CNT_W   = 24;            // record count width (frag_dma's default)
  localparam int unsigned PIX_W   = FRAG_ID_BITS;  // pixel id bits (frag_dma's default)
  localparam int unsigned TRI_W   = 4;             // triangle id bits (frag_dma's default)
  localparam int unsigned ARCACHE = 4'b0010;       // not the default: seen on the bus
  localparam int unsigned ARPROT  = 3'b010;        // not the default: seen on the bus
  // the default; a narrow bus with short bursts and a small FIFO; a wide bus with long bursts
  localparam int unsigned DATA_W_OF    [NCASE] = '{64, 32, 128};  // AXI data width
  localparam int unsigned MAX_BURST_OF [NCASE] = '{4, 2, 8};      // records per burst
  localparam int unsigned FIFO_RECS_OF [NCASE] = '{8, 4, 8};      // beat FIFO, records

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned DATA_W    = DATA_W_OF[i];
    localparam int unsigned MAX_BURST = MAX_BURST_OF[i];
    localparam int unsigned FIFO_RECS = FIFO_RECS_OF[i];

    // the unit's ports
    logic                 rst_ni;
    logic                 start_i, abort_i;
    logic [ADDR_W-1:0]    base_i;
    logic [CNT_W-1:0]     count_i;
    logic                 busy_o, done_o, err_o;
    logic [CNT_W-1:0]     sent_o;
    logic                 frag_valid_o, frag_ready_i;
    logic [PIX_W-1:0]     frag_id_o;
    f24_t                 frag_u0_o, frag_v0_o, frag_pl0_o;
    logic [TRI_W-1:0]     frag_tri_o;
    f24_t [8:0]           frag_tbn_o;
    f24_t [2:0]           frag_view_o;
    logic [ID_W-1:0]      m_axi_arid;
    logic [ADDR_W-1:0]    m_axi_araddr;
    logic [7:0]           m_axi_arlen;
    logic [2:0]           m_axi_arsize;
    logic [1:0]           m_axi_arburst;
    logic                 m_axi_arlock;
    logic [3:0]           m_axi_arcache;
    logic [2:0]           m_axi_arprot;
    logic [3:0]           m_axi_arqos;
    logic                 m_axi_arvalid, m_axi_arready;
    logic [ID_W-1:0]      m_axi_rid;
    logic [DATA_W-1:0]    m_axi_rdata;
    logic [1:0]           m_axi_rresp;
    logic                 m_axi_rlast, m_axi_rvalid, m_axi_rready;

    frag_dma #(
      .ADDR_W(ADDR_W), .DATA_W(DATA_W), .ID_W(ID_W), .ARCACHE(ARCACHE), .ARPROT(ARPROT),
      .MAX_BURST(MAX_BURST), .FIFO_RECS(FIFO_RECS), .CNT_W(CNT_W), .PIX_W(PIX_W), .TRI_W(TRI_W)
    ) u_dut (
      .clk_i, .rst_ni, .start_i, .abort_i, .base_i, .count_i, .busy_o, .done_o, .err_o, .sent_o,
      .frag_valid_o, .frag_ready_i, .frag_id_o, .frag_u0_o, .frag_v0_o, .frag_pl0_o,
      .frag_tri_o, .frag_tbn_o, .frag_view_o,
      .m_axi_arid, .m_axi_araddr, .m_axi_arlen, .m_axi_arsize, .m_axi_arburst, .m_axi_arlock,
      .m_axi_arcache, .m_axi_arprot, .m_axi_arqos, .m_axi_arvalid, .m_axi_arready,
      .m_axi_rid, .m_axi_rdata, .m_axi_rresp, .m_axi_rlast, .m_axi_rvalid, .m_axi_rready
    );
  end

endmodule
