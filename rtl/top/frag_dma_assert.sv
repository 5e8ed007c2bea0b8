// SPDX-License-Identifier: Apache-2.0
// frag_dma_assert: the properties of frag_dma, bound into every instance (the `bind` at the end
// of this file) and checked by simulation (Verilator --assert).  Immediate assertions only.
//
//   fifo_no_overflow  a beat is written into the beat FIFO only while it has room (the credit
//                     of the burst requests: inflight + FIFO count <= FIFO depth);
//   credit_bound      beats requested and not yet taken plus the FIFO's fill never exceed it;
//   r_requested       an R beat arrives only for a requested burst (the slave's obligation);
//   ar_stable         AR holds its payload while arvalid && !arready;
//   ar_page           a burst never crosses a 4 KiB boundary; arlen + 1 is whole records;
//   frag_stable       the fragment holds its payload while frag_valid_o && !frag_ready_i;
//   sent_bound        sent_o never exceeds the frame's record count;
//   idle_quiet        outside a frame nothing is requested, offered or outstanding.
`ifndef SYNTHESIS
module frag_dma_assert #(
  parameter int unsigned ADDR_W     = 32,
  parameter int unsigned DATA_W     = 64,
  parameter int unsigned CNT_W      = 24,
  parameter int unsigned FB_W       = 5,
  parameter int unsigned FIFO_BEATS = 16,
  parameter int unsigned BEATS      = 8,
  parameter int unsigned REC_W      = 512
) (
  input logic              clk_i,
  input logic              rst_ni,
  input logic              busy_i,
  input logic              start_i,
  input logic [CNT_W-1:0]  count_i,
  input logic [CNT_W-1:0]  sent_i,
  input logic              f_wr_i,
  input logic              f_full_i,
  input logic [FB_W-1:0]   f_count_i,
  input logic [FB_W-1:0]   inflight_i,
  input logic              r_take_i,
  input logic              arvalid_i,
  input logic              arready_i,
  input logic [ADDR_W-1:0] araddr_i,
  input logic [7:0]        arlen_i,
  input logic              frag_valid_i,
  input logic              frag_ready_i,
  input logic [REC_W-1:0]  out_i
);

  logic              ar_hold_q, fr_hold_q;
  logic [ADDR_W-1:0] araddr_q;
  logic [7:0]        arlen_q;
  logic [REC_W-1:0]  out_q;
  logic [CNT_W-1:0]  count_q;
  always_ff @(posedge clk_i) begin
    ar_hold_q <= rst_ni && arvalid_i && !arready_i;
    fr_hold_q <= rst_ni && frag_valid_i && !frag_ready_i;
    araddr_q  <= araddr_i;
    arlen_q   <= arlen_i;
    out_q     <= out_i;
    if (start_i && !busy_i) count_q <= count_i;
  end

  logic [12:0] ar_end;   // offset in the 4 KiB page of the byte after the burst
  assign ar_end = {1'b0, araddr_i[11:0]} + 13'((32'(arlen_i) + 1) * (DATA_W / 8));

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      fifo_no_overflow: assert (!(f_wr_i && f_full_i))
        else $error("frag_dma: beat FIFO written while full");
      credit_bound: assert (32'(inflight_i) + 32'(f_count_i) <= FIFO_BEATS)
        else $error("frag_dma: %0d beats in flight + %0d in the FIFO > %0d", inflight_i,
                    f_count_i, FIFO_BEATS);
      r_requested: assert (!(r_take_i && inflight_i == '0))
        else $error("frag_dma: R beat without a burst requested");
      ar_stable: assert (!ar_hold_q || (arvalid_i && araddr_i == araddr_q && arlen_i == arlen_q))
        else $error("frag_dma: AR changed before arready");
      ar_page: assert (!arvalid_i || (ar_end <= 13'd4096 && (32'(arlen_i) + 1) % BEATS == 0))
        else $error("frag_dma: burst at %h, arlen %0d crosses 4 KiB or splits a record",
                    araddr_i, arlen_i);
      frag_stable: assert (!fr_hold_q || (frag_valid_i && out_i == out_q))
        else $error("frag_dma: fragment changed or withdrawn before ready");
      sent_bound: assert (!busy_i || sent_i <= count_q)
        else $error("frag_dma: %0d records delivered of %0d", sent_i, count_q);
      idle_quiet: assert (busy_i || (!arvalid_i && !frag_valid_i && inflight_i == '0))
        else $error("frag_dma: activity outside a frame");
    end
  end

endmodule

bind frag_dma frag_dma_assert #(
  .ADDR_W(ADDR_W), .DATA_W(DATA_W), .CNT_W(CNT_W), .FB_W(FB_W), .FIFO_BEATS(FIFO_BEATS),
  .BEATS(BEATS), .REC_W(REC_W)
) u_assert (
  .clk_i, .rst_ni, .busy_i(busy_q), .start_i, .count_i, .sent_i(sent_q), .f_wr_i(f_wr),
  .f_full_i(f_full), .f_count_i(f_count), .inflight_i(inflight_q), .r_take_i(r_take),
  .arvalid_i(m_axi_arvalid), .arready_i(m_axi_arready), .araddr_i(m_axi_araddr),
  .arlen_i(m_axi_arlen), .frag_valid_i(frag_valid_o), .frag_ready_i, .out_i(out_q));
`endif
