// SPDX-License-Identifier: Apache-2.0
// pix_dma_tb: pix_dma in every configuration tb/pix_dma checks, side by side in one build:
// g_case[i] holds pix_dma with DATA_W = DATA_W_OF[i], MAX_OUTST = MAX_OUTST_OF[i] (AWCACHE and
// AWPROT as the test sets them) and its own copy of the unit's ports (named as the ports, the
// AXI write master's m_axi_* too), so the cocotb test drives and checks each through the
// hierarchy (dut.g_case[i].px_valid_i, ...) and puts its own cocotbext-axi memory on each
// instance's m_axi_* signals, with its own reset; only the clock is shared.  The table is the
// test's CASES (the test reads the parameters back and stops if they differ).
module pix_dma_tb
  import pidm_pkg::*;
(
  input logic clk_i
);

  localparam int unsigned NCASE   = 3;
  localparam int unsigned ADDR_W  = 32;                // AXI address width (pix_dma's default)
  localparam int unsigned ID_W    = 4;                 // AXI ID width (pix_dma's default)
  localparam int unsigned PIX_W   = FRAG_ID_BITS;      // pixel id width (pix_dma's default)
  localparam int unsigned PITCH_W = 16;                // pitch width (pix_dma's default)
  localparam int unsigned ITER_W  = 16;                // iteration count width (the default)
  localparam int unsigned CNT_W   = 24;                // pixel counter width (the default)
  localparam int unsigned AWCACHE = 4'b0111;           // not the default: seen on the bus
  localparam int unsigned AWPROT  = 3'b001;            // not the default: seen on the bus
  // the default, the narrowest bus with the fewest writes in flight, a wide bus
  localparam int unsigned DATA_W_OF    [NCASE] = '{64, 32, 128};  // AXI data width
  localparam int unsigned MAX_OUTST_OF [NCASE] = '{8, 2, 4};      // writes awaiting B

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned DATA_W    = DATA_W_OF[i];
    localparam int unsigned MAX_OUTST = MAX_OUTST_OF[i];

    // the unit's ports
    logic                 rst_ni;
    logic                 start_i, abort_i;
    logic [ADDR_W-1:0]    fb_base_i, st_base_i;
    logic [PITCH_W-1:0]   pitch_i;
    logic                 st_en_i;
    logic [4:0]           xbits_i;
    logic                 idle_o, err_o;
    logic [CNT_W-1:0]     pixels_o, written_o;
    logic                 px_valid_i, px_ready_o;
    logic [PIX_W-1:0]     px_id_i;
    logic [2:0][7:0]      px_rgb_i;
    logic                 px_hit_i, px_invalid_i, px_err_i;
    logic [ITER_W-1:0]    px_iters_i;
    logic [ID_W-1:0]      m_axi_awid;
    logic [ADDR_W-1:0]    m_axi_awaddr;
    logic [7:0]           m_axi_awlen;
    logic [2:0]           m_axi_awsize;
    logic [1:0]           m_axi_awburst;
    logic                 m_axi_awlock;
    logic [3:0]           m_axi_awcache;
    logic [2:0]           m_axi_awprot;
    logic [3:0]           m_axi_awqos;
    logic                 m_axi_awvalid, m_axi_awready;
    logic [DATA_W-1:0]    m_axi_wdata;
    logic [DATA_W/8-1:0]  m_axi_wstrb;
    logic                 m_axi_wlast, m_axi_wvalid, m_axi_wready;
    logic [ID_W-1:0]      m_axi_bid;
    logic [1:0]           m_axi_bresp;
    logic                 m_axi_bvalid, m_axi_bready;

    pix_dma #(
      .ADDR_W(ADDR_W), .DATA_W(DATA_W), .ID_W(ID_W), .AWCACHE(AWCACHE), .AWPROT(AWPROT),
      .MAX_OUTST(MAX_OUTST), .PIX_W(PIX_W), .PITCH_W(PITCH_W), .ITER_W(ITER_W), .CNT_W(CNT_W)
    ) u_dut (
      .clk_i, .rst_ni, .start_i, .abort_i, .fb_base_i, .st_base_i, .pitch_i, .st_en_i, .xbits_i,
      .idle_o, .err_o, .pixels_o, .written_o,
      .px_valid_i, .px_ready_o, .px_id_i, .px_rgb_i, .px_hit_i, .px_invalid_i, .px_err_i,
      .px_iters_i,
      .m_axi_awid, .m_axi_awaddr, .m_axi_awlen, .m_axi_awsize, .m_axi_awburst, .m_axi_awlock,
      .m_axi_awcache, .m_axi_awprot, .m_axi_awqos, .m_axi_awvalid, .m_axi_awready,
      .m_axi_wdata, .m_axi_wstrb, .m_axi_wlast, .m_axi_wvalid, .m_axi_wready,
      .m_axi_bid, .m_axi_bresp, .m_axi_bvalid, .m_axi_bready
    );
  end

endmodule
