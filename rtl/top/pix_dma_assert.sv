// SPDX-License-Identifier: Apache-2.0
// pix_dma_assert: the properties of pix_dma, bound into every instance (the `bind` at the end
// of this file) and checked by simulation (Verilator --assert).  Immediate assertions only.
//
//   aw_stable / w_stable  AW and W hold their payload while valid && !ready;
//   outst_bound           at most MAX_OUTST writes await their B response;
//   b_requested           a B response arrives only for an issued write (the slave's obligation);
//   lane_match            the W beat's strobes are the 4 bytes of the address's lane;
//   written_bound         written_o <= pixels_o (a pixel counts written after it was taken).
`ifndef SYNTHESIS
module pix_dma_assert #(
  parameter int unsigned ADDR_W    = 32,
  parameter int unsigned DATA_W    = 64,
  parameter int unsigned MAX_OUTST = 8,
  parameter int unsigned OUT_W     = 4,
  parameter int unsigned CNT_W     = 24
) (
  input logic                clk_i,
  input logic                rst_ni,
  input logic                awvalid_i,
  input logic                awready_i,
  input logic [ADDR_W-1:0]   awaddr_i,
  input logic                wvalid_i,
  input logic                wready_i,
  input logic [DATA_W-1:0]   wdata_i,
  input logic [DATA_W/8-1:0] wstrb_i,
  input logic                b_take_i,
  input logic [OUT_W-1:0]    outst_i,
  input logic [CNT_W-1:0]    pixels_i,
  input logic [CNT_W-1:0]    written_i
);

  localparam int unsigned LB = $clog2(DATA_W / 8);   // address bits of a byte lane

  logic              aw_hold_q, w_hold_q;
  logic [ADDR_W-1:0] awaddr_q;
  logic [DATA_W-1:0] wdata_q;
  logic [DATA_W/8-1:0] wstrb_q;
  always_ff @(posedge clk_i) begin
    aw_hold_q <= rst_ni && awvalid_i && !awready_i;
    w_hold_q  <= rst_ni && wvalid_i && !wready_i;
    awaddr_q  <= awaddr_i;
    wdata_q   <= wdata_i;
    wstrb_q   <= wstrb_i;
  end

  logic [DATA_W/8-1:0] strb_exp;
  assign strb_exp = (DATA_W / 8)'(4'hF) << awaddr_i[LB-1:0];

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      aw_stable: assert (!aw_hold_q || (awvalid_i && awaddr_i == awaddr_q))
        else $error("pix_dma: AW changed before awready");
      w_stable: assert (!w_hold_q || (wvalid_i && wdata_i == wdata_q && wstrb_i == wstrb_q))
        else $error("pix_dma: W changed before wready");
      outst_bound: assert (32'(outst_i) <= MAX_OUTST)
        else $error("pix_dma: %0d writes outstanding", outst_i);
      b_requested: assert (!(b_take_i && outst_i == '0))
        else $error("pix_dma: B response without a write");
      lane_match: assert (!(awvalid_i && wvalid_i) || wstrb_i == strb_exp)
        else $error("pix_dma: wstrb %h for address %h", wstrb_i, awaddr_i);
      written_bound: assert (written_i <= pixels_i)
        else $error("pix_dma: %0d written of %0d pixels", written_i, pixels_i);
    end
  end

endmodule

bind pix_dma pix_dma_assert #(
  .ADDR_W(ADDR_W), .DATA_W(DATA_W), .MAX_OUTST(MAX_OUTST), .OUT_W(OUT_W), .CNT_W(CNT_W)
) u_assert (
  .clk_i, .rst_ni, .awvalid_i(m_axi_awvalid), .awready_i(m_axi_awready),
  .awaddr_i(m_axi_awaddr), .wvalid_i(m_axi_wvalid), .wready_i(m_axi_wready),
  .wdata_i(m_axi_wdata), .wstrb_i(m_axi_wstrb), .b_take_i(b_take), .outst_i(outst_q),
  .pixels_i(pixels_q), .written_i(written_q));
`endif
