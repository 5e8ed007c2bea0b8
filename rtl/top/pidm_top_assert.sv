// SPDX-License-Identifier: Apache-2.0
// pidm_top_assert: the properties of pidm_top, bound into every instance (the `bind` at the end
// of this file) and checked by simulation (Verilator --assert).  Immediate assertions only.
//
//   idle_quiet      in IDLE the DMA engines hold no frame (frag_dma not busy, pix_dma idle);
//   px_le_frag      pixels taken by pix_dma never exceed the fragments frag_dma delivered;
//   frame_complete  a frame that ends without an error (frame_done from RUN) delivered every
//                   fragment of FRAG_COUNT, and pix_dma took and wrote (B response back) one
//                   pixel for each of them;
//   start_in_idle   a frame starts only from IDLE, and never with a bad configuration;
//   flush_drained   dm_pipeline is reset (FLUSH, BFLUSH) only while it holds no pixel and no
//                   DMA engine is busy (no AXI transaction of its own outstanding);
//   own_switch      the owner of m_axi_h and m_axi_w (the builder in BUILD, else dm_pipeline
//                   and pix_dma) changes only when neither port has a transaction outstanding:
//                   no read burst without its last beat, no write without its B response, no
//                   W beat waiting for or ahead of its AW (counted here on the ports);
//   own_quiet       the side that does not own a port offers nothing on it (no arvalid,
//                   awvalid or wvalid), and the builder is busy only in BUILD;
//   build_clean     a build starts only from IDLE with both DMA engines idle, and never
//                   together with a frame start (dm_pipeline holds no pixel in IDLE, though it
//                   may still be refilling its slot list after a reset: no AXI traffic; the
//                   port counters of own_switch check that no height read is outstanding).
`ifndef SYNTHESIS
module pidm_top_assert #(
  parameter int unsigned CNT_W = 32
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic [2:0]       state_i,      // pidm_top's state_q (S_IDLE = 0, S_RUN = 1, ...)
  input logic             go_i,
  input logic             bad_cfg_i,
  input logic             frame_end_i,
  input logic             err_seen_i,
  input logic             any_err_i,
  input logic             frag_busy_i,
  input logic             pix_idle_i,
  input logic             dm_idle_i,
  input logic [CNT_W-1:0] frag_sent_i,
  input logic [CNT_W-1:0] pix_taken_i,
  input logic [CNT_W-1:0] pix_written_i,
  input logic [31:0]      frag_count_i,
  // the owner mux of m_axi_h / m_axi_w
  input logic             own_b_i,      // the builder owns both ports
  input logic             pyr_go_i,     // builder start
  input logic             b_busy_i,     // pyr_build busy_o
  input logic             p_h_arvalid_i, // dm_pipeline's arvalid (before the mux)
  input logic             b_arvalid_i,  // the builder's arvalid
  input logic             p_w_awvalid_i, // pix_dma's awvalid / wvalid
  input logic             p_w_wvalid_i,
  input logic             b_awvalid_i,  // the builder's awvalid / wvalid
  input logic             b_wvalid_i,
  // the ports
  input logic             h_arvalid_i,
  input logic             h_arready_i,
  input logic             h_rvalid_i,
  input logic             h_rready_i,
  input logic             h_rlast_i,
  input logic             w_awvalid_i,
  input logic             w_awready_i,
  input logic             w_wvalid_i,
  input logic             w_wready_i,
  input logic             w_wlast_i,
  input logic             w_bvalid_i,
  input logic             w_bready_i
);

  localparam logic [2:0] IDLE = 3'd0, STOP = 3'd2, FLUSH = 3'd3, BUILD = 3'd4, BFLUSH = 3'd5;

  // transactions outstanding on the two shared ports
  int h_out, aw_out, wl_out;   // read bursts; AWs and W bursts without their B response
  logic own_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      h_out  <= 0;
      aw_out <= 0;
      wl_out <= 0;
      own_q  <= 1'b0;
    end else begin
      h_out  <= h_out + int'(h_arvalid_i && h_arready_i) - int'(h_rvalid_i && h_rready_i && h_rlast_i);
      aw_out <= aw_out + int'(w_awvalid_i && w_awready_i) - int'(w_bvalid_i && w_bready_i);
      wl_out <= wl_out + int'(w_wvalid_i && w_wready_i && w_wlast_i) - int'(w_bvalid_i && w_bready_i);
      own_q  <= own_b_i;
    end
  end

  logic [31:0] count_q;   // FRAG_COUNT of the running frame
  always_ff @(posedge clk_i) begin
    if (go_i) count_q <= frag_count_i;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      idle_quiet: assert (state_i != IDLE || (!frag_busy_i && pix_idle_i))
        else $error("pidm_top: a DMA engine busy in IDLE");
      px_le_frag: assert (pix_taken_i <= frag_sent_i)
        else $error("pidm_top: %0d pixels taken for %0d fragments", pix_taken_i, frag_sent_i);
      frame_complete: assert (!(frame_end_i && !err_seen_i && !any_err_i) ||
                              (32'(frag_sent_i) == count_q && 32'(pix_taken_i) == count_q &&
                               32'(pix_written_i) == count_q))
        else $error("pidm_top: frame ended with %0d fragments, %0d pixels taken, %0d written of %0d",
                    frag_sent_i, pix_taken_i, pix_written_i, count_q);
      start_in_idle: assert (!go_i || (state_i == IDLE && !bad_cfg_i))
        else $error("pidm_top: frame started outside IDLE or with a bad configuration");
      flush_drained: assert (!(state_i == FLUSH || state_i == BFLUSH)
                             || (dm_idle_i && !frag_busy_i && pix_idle_i))
        else $error("pidm_top: dm_pipeline reset with work inside");
      own_switch: assert (own_q == own_b_i || (h_out == 0 && aw_out == 0 && wl_out == 0))
        else $error("pidm_top: port owner changed with %0d reads, %0d AWs, %0d W bursts outstanding",
                    h_out, aw_out, wl_out);
      own_quiet: assert ((own_b_i || (!b_arvalid_i && !b_awvalid_i && !b_wvalid_i && !b_busy_i))
                         && (!own_b_i || (!p_h_arvalid_i && !p_w_awvalid_i && !p_w_wvalid_i)))
        else $error("pidm_top: the side that does not own the ports offers a request");
      build_clean: assert (!pyr_go_i || (state_i == IDLE && !go_i && !frag_busy_i && pix_idle_i))
        else $error("pidm_top: a build started outside IDLE or with a DMA engine busy (state %0d, frame start %0d, frag_dma busy %0d, pix_dma idle %0d)",
                    state_i, go_i, frag_busy_i, pix_idle_i);
      c_build: cover (state_i == BUILD);
      c_stop: cover (state_i == STOP);
    end
  end

endmodule

bind pidm_top pidm_top_assert #(.CNT_W(CNT_W)) u_assert (
  .clk_i, .rst_ni, .state_i(state_q), .go_i(go), .bad_cfg_i(bad_cfg), .frame_end_i(frame_end),
  .err_seen_i(err_seen_q), .any_err_i(any_err), .frag_busy_i(frag_busy), .pix_idle_i(pix_idle),
  .dm_idle_i(dm_idle), .frag_sent_i(frag_sent), .pix_taken_i(pix_taken),
  .pix_written_i(pix_written), .frag_count_i(frag_count),
  .own_b_i(own_b), .pyr_go_i(pyr_go), .b_busy_i(b_busy), .p_h_arvalid_i(p_h_arvalid),
  .b_arvalid_i(b_arvalid), .p_w_awvalid_i(p_w_awvalid), .p_w_wvalid_i(p_w_wvalid),
  .b_awvalid_i(b_awvalid), .b_wvalid_i(b_wvalid),
  .h_arvalid_i(m_axi_h_arvalid), .h_arready_i(m_axi_h_arready), .h_rvalid_i(m_axi_h_rvalid),
  .h_rready_i(m_axi_h_rready), .h_rlast_i(m_axi_h_rlast), .w_awvalid_i(m_axi_w_awvalid),
  .w_awready_i(m_axi_w_awready), .w_wvalid_i(m_axi_w_wvalid), .w_wready_i(m_axi_w_wready),
  .w_wlast_i(m_axi_w_wlast), .w_bvalid_i(m_axi_w_bvalid), .w_bready_i(m_axi_w_bready));
`endif
