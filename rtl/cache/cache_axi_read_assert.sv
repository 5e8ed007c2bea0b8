// SPDX-License-Identifier: Apache-2.0
// cache_axi_read_assert: the AXI checks of every cache_axi_read (the height cache's and the texture
// cache's), bound into it (the bind at the end of this file; not in synthesis).  Immediate
// assertions in a clocked block (the state before the clock edge); "disable iff (!rst_ni)" is a
// guard on rst_ni, "a |=> b" a guard on registered copies of the clock before.
module cache_axi_read_assert #(
  parameter int unsigned ADDR_W = 32,
  parameter int unsigned ID_W   = 4
) (
  input logic              clk_i,
  input logic              rst_ni,
  input logic [ID_W-1:0]   m_axi_arid,
  input logic [ADDR_W-1:0] m_axi_araddr,
  input logic [7:0]        m_axi_arlen,
  input logic [2:0]        m_axi_arsize,
  input logic [1:0]        m_axi_arburst,
  input logic              m_axi_arvalid,
  input logic              m_axi_arready,
  input logic              m_axi_rlast,
  input logic              r_cur_o,    // rvalid, of the current epoch
  input logic              r_acc_i,    // the cache accepts the beat
  input logic              r_last_o    // the beat is its line's last by the count
);

  localparam int unsigned AR_W = ID_W + ADDR_W + 8 + 3 + 2;

  logic            p_rst_q, p_ar_wait_q;
  logic [AR_W-1:0] p_ar_q;
  always_ff @(posedge clk_i) begin
    p_rst_q     <= rst_ni;
    p_ar_wait_q <= m_axi_arvalid && !m_axi_arready;
    p_ar_q      <= {m_axi_arid, m_axi_araddr, m_axi_arlen, m_axi_arsize, m_axi_arburst};
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      // AR: the payload holds and arvalid stays up until the handshake.
      if (p_rst_q && p_ar_wait_q) begin
        ar_stable: assert (m_axi_arvalid && p_ar_q == {m_axi_arid, m_axi_araddr, m_axi_arlen,
                                                       m_axi_arsize, m_axi_arburst})
          else $error("%m: AR dropped or changed before arready");
      end
      // rlast marks exactly the last beat of each of the cache's bursts.
      rlast_on_last_beat: assert (!r_acc_i || m_axi_rlast == r_last_o)
        else $error("%m: rlast on a beat other than the last");
      // A beat carrying the current epoch belongs to an MSHR waiting for its line.
      r_beat_expected: assert (!r_cur_o || r_acc_i)
        else $error("%m: R beat for no outstanding read");
    end
  end

endmodule

`ifndef SYNTHESIS
bind cache_axi_read cache_axi_read_assert #(.ADDR_W(ADDR_W), .ID_W(ID_W)) u_assert (.*);
`endif
