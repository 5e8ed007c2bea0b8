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
//   flush_drained   dm_pipeline is reset (FLUSH) only while it holds no pixel and no DMA
//                   engine is busy (no AXI transaction of its own outstanding).
`ifndef SYNTHESIS
module pidm_top_assert #(
  parameter int unsigned CNT_W = 32
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic [1:0]       state_i,      // pidm_top's state_q (S_IDLE = 0, S_RUN = 1, ...)
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
  input logic [31:0]      frag_count_i
);

  localparam logic [1:0] IDLE = 2'd0, STOP = 2'd2, FLUSH = 2'd3;

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
      flush_drained: assert (state_i != FLUSH || (dm_idle_i && !frag_busy_i && pix_idle_i))
        else $error("pidm_top: dm_pipeline reset with work inside");
      c_stop: cover (state_i == STOP);
    end
  end

endmodule

bind pidm_top pidm_top_assert #(.CNT_W(CNT_W)) u_assert (
  .clk_i, .rst_ni, .state_i(state_q), .go_i(go), .bad_cfg_i(bad_cfg), .frame_end_i(frame_end),
  .err_seen_i(err_seen_q), .any_err_i(any_err), .frag_busy_i(frag_busy), .pix_idle_i(pix_idle),
  .dm_idle_i(dm_idle), .frag_sent_i(frag_sent), .pix_taken_i(pix_taken),
  .pix_written_i(pix_written), .frag_count_i(frag_count));
`endif
