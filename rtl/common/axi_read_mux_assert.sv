// SPDX-License-Identifier: Apache-2.0
// axi_read_mux_assert: the properties of axi_read_mux, bound into every instance (the `bind` at
// the end of this file) and checked by simulation (Verilator --assert).  Immediate assertions.
//
//   ar_one      at most one master sees arready;
//   ar_keep,    the port's arvalid, once up and not accepted, stays up and keeps its fields (the
//   ar_hold     grant is held; the masters keep their own, their AXI4 obligation);
//   r_one       at most one master sees rvalid, and only the one rid names.
`ifndef SYNTHESIS
module axi_read_mux_assert #(
  parameter int unsigned N      = 2,
  parameter int unsigned ADDR_W = 32,
  parameter int unsigned OID_W  = 4
) (
  input logic                   clk_i,
  input logic                   rst_ni,
  input logic [N-1:0]           s_arready_i,   // axi_read_mux's s_arready_o
  input logic [N-1:0]           s_rvalid_i,    // axi_read_mux's s_rvalid_o
  input logic [OID_W-1:0]       m_arid_i,      // the port's fields (axi_read_mux's m_ar*_o)
  input logic [ADDR_W-1:0]      m_araddr_i,
  input logic                   m_arvalid_i,
  input logic                   m_arready_i
);

  logic              pend_q;   // the port's address was valid and not accepted last clock
  logic [OID_W-1:0]  id_q;
  logic [ADDR_W-1:0] addr_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) pend_q <= 1'b0;
    else         pend_q <= m_arvalid_i && !m_arready_i;
    id_q   <= m_arid_i;
    addr_q <= m_araddr_i;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      ar_one:  assert ($onehot0(s_arready_i))
        else $error("axi_read_mux: arready to more than one master (%b)", s_arready_i);
      ar_hold: assert (!pend_q || !m_arvalid_i || (m_arid_i == id_q && m_araddr_i == addr_q))
        else $error("axi_read_mux: the port's address changed before its handshake");
      ar_keep: assert (!pend_q || m_arvalid_i)
        else $error("axi_read_mux: arvalid dropped before its handshake (grant moved or a master dropped it)");
      r_one:   assert ($onehot0(s_rvalid_i))
        else $error("axi_read_mux: rvalid to more than one master (%b)", s_rvalid_i);
    end
  end

endmodule

bind axi_read_mux axi_read_mux_assert #(.N(N), .ADDR_W(ADDR_W), .OID_W(OID_W))
  u_assert (
  .clk_i, .rst_ni, .s_arready_i(s_arready_o), .s_rvalid_i(s_rvalid_o),
  .m_arid_i(m_arid_o), .m_araddr_i(m_araddr_o), .m_arvalid_i(m_arvalid_o),
  .m_arready_i);
`endif
