// SPDX-License-Identifier: Apache-2.0
// pyr_build_assert: the pyramid builder's simulation checks, bound into every pyr_build (the bind
// at the end of this file; not in synthesis).  Immediate assertions in a clocked block on the
// state before the clock edge (registers of the previous clock kept here for the "held" checks).
//   AXI: AR, AW and W payloads held while valid and not ready; bursts INCR, word-aligned, at most
//   BURST beats, never across a 4 KiB boundary; arsize / awsize the bus width.
//   Streams: every stage output held while not taken; no push into a full writer queue.
//   Passes: when a pass ends (reader and writer idle) no word is left in the chain or the queues
//   (the stages produced exactly the words the writer wrote).
//   Control: done_o for one clock, busy_o low with it; err_code_o[3] is 0.
module pyr_build_assert #(
  parameter int unsigned ADDR_W     = 32,
  parameter int unsigned AXI_DATA_W = 64,
  parameter int unsigned BURST      = 16,
  parameter int unsigned NS         = 10
) (
  input logic                          clk_i,
  input logic                          rst_ni,
  input logic                          busy_o,
  input logic                          done_o,
  input logic                          err_code3,   // err_code_o[3]
  input logic [ADDR_W-1:0]             m_axi_araddr,
  input logic [7:0]                    m_axi_arlen,
  input logic [2:0]                    m_axi_arsize,
  input logic [1:0]                    m_axi_arburst,
  input logic                          m_axi_arvalid,
  input logic                          m_axi_arready,
  input logic [ADDR_W-1:0]             m_axi_awaddr,
  input logic [7:0]                    m_axi_awlen,
  input logic [2:0]                    m_axi_awsize,
  input logic [1:0]                    m_axi_awburst,
  input logic                          m_axi_awvalid,
  input logic                          m_axi_awready,
  input logic [AXI_DATA_W-1:0]         m_axi_wdata,
  input logic [AXI_DATA_W/8-1:0]       m_axi_wstrb,
  input logic                          m_axi_wlast,
  input logic                          m_axi_wvalid,
  input logic                          m_axi_wready,
  input logic [NS-1:0]                 st_out_valid,
  input logic [NS-1:0]                 st_out_ready,
  input logic [NS-1:0][AXI_DATA_W-1:0] st_out_data,
  input logic [NS-1:0]                 st_in_valid,
  input logic [NS-1:0]                 wr_push,
  input logic [NS-1:0]                 wr_full,
  input logic                          rd_valid,
  input logic                          rd_idle,
  input logic                          wr_idle,
  input logic                          wr_empty,
  input logic                          pass_end     // the controller ends a pass this clock
);

  localparam int unsigned BB  = AXI_DATA_W / 8;
  localparam int unsigned LGB = $clog2(BB);

  logic                          arv_q, awv_q, wv_q, done_q;
  logic [ADDR_W-1:0]             araddr_q, awaddr_q;
  logic [7:0]                    arlen_q, awlen_q;
  logic [AXI_DATA_W-1:0]         wdata_q;
  logic [AXI_DATA_W/8-1:0]       wstrb_q;
  logic                          wlast_q;
  logic [NS-1:0]                 sv_q;
  logic [NS-1:0][AXI_DATA_W-1:0] sd_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      arv_q  <= 1'b0;
      awv_q  <= 1'b0;
      wv_q   <= 1'b0;
      sv_q   <= '0;
      done_q <= 1'b0;
    end else begin
      arv_q  <= m_axi_arvalid && !m_axi_arready;
      awv_q  <= m_axi_awvalid && !m_axi_awready;
      wv_q   <= m_axi_wvalid && !m_axi_wready;
      sv_q   <= st_out_valid & ~st_out_ready;
      done_q <= done_o;
    end
    araddr_q <= m_axi_araddr;
    arlen_q  <= m_axi_arlen;
    awaddr_q <= m_axi_awaddr;
    awlen_q  <= m_axi_awlen;
    wdata_q  <= m_axi_wdata;
    wstrb_q  <= m_axi_wstrb;
    wlast_q  <= m_axi_wlast;
    sd_q     <= st_out_data;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      ar_held: assert (!arv_q || (m_axi_arvalid && m_axi_araddr == araddr_q
                                  && m_axi_arlen == arlen_q))
        else $error("pyr_build: AR dropped or changed before arready");
      aw_held: assert (!awv_q || (m_axi_awvalid && m_axi_awaddr == awaddr_q
                                  && m_axi_awlen == awlen_q))
        else $error("pyr_build: AW dropped or changed before awready");
      w_held: assert (!wv_q || (m_axi_wvalid && m_axi_wdata == wdata_q && m_axi_wstrb == wstrb_q
                                && m_axi_wlast == wlast_q))
        else $error("pyr_build: W dropped or changed before wready");
      ar_burst: assert (!m_axi_arvalid
                        || (m_axi_arburst == 2'b01 && m_axi_arsize == 3'(LGB)
                            && m_axi_araddr[LGB-1:0] == '0 && 32'(m_axi_arlen) < BURST
                            && 32'(m_axi_araddr[11:0]) + (32'(m_axi_arlen) + 1) * BB <= 4096))
        else $error("pyr_build: read burst unaligned, too long or across 4 KiB");
      aw_burst: assert (!m_axi_awvalid
                        || (m_axi_awburst == 2'b01 && m_axi_awsize == 3'(LGB)
                            && m_axi_awaddr[LGB-1:0] == '0 && 32'(m_axi_awlen) < BURST
                            && 32'(m_axi_awaddr[11:0]) + (32'(m_axi_awlen) + 1) * BB <= 4096))
        else $error("pyr_build: write burst unaligned, too long or across 4 KiB");
      w_strobe: assert (!m_axi_wvalid || m_axi_wstrb != '0)
        else $error("pyr_build: a write beat with no byte enabled");
      for (int j = 0; j < NS; j++) begin
        // stage_held
        assert (!sv_q[j] || (st_out_valid[j] && st_out_data[j] == sd_q[j]))
          else $error("pyr_build: stage %0d output dropped or changed before taken", j);
        // no_overflow
        assert (!(wr_push[j] && wr_full[j]))
          else $error("pyr_build: push into writer queue %0d while full", j);
      end
      pass_drained: assert (!pass_end || (rd_idle && wr_idle && wr_empty && !rd_valid
                                          && st_out_valid == '0 && st_in_valid == '0))
        else $error("pyr_build: words left in the chain or the writer's queues at a pass's end");
      done_pulse: assert (!(done_o && done_q))
        else $error("pyr_build: done_o longer than one clock");
      done_busy: assert (!(done_o && busy_o))
        else $error("pyr_build: done_o while busy_o");
      err_code_bit3: assert (err_code3 == 1'b0)
        else $error("pyr_build: err_code_o[3] set");
    end
  end

endmodule

`ifndef SYNTHESIS
bind pyr_build pyr_build_assert #(
  .ADDR_W(ADDR_W), .AXI_DATA_W(AXI_DATA_W), .BURST(BURST), .NS(NS)
) u_assert (.*, .pass_end((state_q == C_RUN) && rd_idle && wr_idle),
                 .err_code3(err_code_o[3]));
`endif
