// SPDX-License-Identifier: Apache-2.0
// axi_read_mux: N AXI4 read masters (AR and R channels) onto one port.  The slave port's arid is
// {master index, the master's arid}, so the R channel returns each beat to its master by the
// top bits of rid; beats of different masters may interleave, as AXI4 allows between ids.
//
// AR: round-robin among the masters' arvalid.  The grant is held while the granted arvalid is
//   up and not yet accepted (AXI4: an address, once valid, stays until its handshake), and moves
//   on after each handshake to the next requesting master.  No register in the path: arvalid
//   and the fields of the port are the granted master's.
// R: rvalid goes to the master named by rid's top bits, rready comes from it; the other masters
//   see rvalid = 0.
module axi_read_mux #(
  parameter int unsigned N      = 2,    // masters (>= 1)
  parameter int unsigned ADDR_W = 32,   // address width
  parameter int unsigned DATA_W = 64,   // data width
  parameter int unsigned ID_W   = 3,    // each master's id width
  // derived (not to be overridden)
  parameter int unsigned SEL_W  = (N > 1) ? $clog2(N) : 1,  // master index width
  parameter int unsigned OID_W  = ID_W + ((N > 1) ? $clog2(N) : 0)  // the slave port's id width
) (
  input  logic                        clk_i,
  input  logic                        rst_ni,
  // masters
  input  logic [N-1:0][ID_W-1:0]      s_arid_i,
  input  logic [N-1:0][ADDR_W-1:0]    s_araddr_i,
  input  logic [N-1:0][7:0]           s_arlen_i,
  input  logic [N-1:0][2:0]           s_arsize_i,
  input  logic [N-1:0][1:0]           s_arburst_i,
  input  logic [N-1:0]                s_arvalid_i,
  output logic [N-1:0]                s_arready_o,
  output logic [N-1:0][ID_W-1:0]      s_rid_o,
  output logic [N-1:0][DATA_W-1:0]    s_rdata_o,
  output logic [N-1:0][1:0]           s_rresp_o,
  output logic [N-1:0]                s_rlast_o,
  output logic [N-1:0]                s_rvalid_o,
  input  logic [N-1:0]                s_rready_i,
  // slave port (to memory)
  output logic [OID_W-1:0]            m_arid_o,
  output logic [ADDR_W-1:0]           m_araddr_o,
  output logic [7:0]                  m_arlen_o,
  output logic [2:0]                  m_arsize_o,
  output logic [1:0]                  m_arburst_o,
  output logic                        m_arvalid_o,
  input  logic                        m_arready_i,
  input  logic [OID_W-1:0]            m_rid_i,
  input  logic [DATA_W-1:0]           m_rdata_i,
  input  logic [1:0]                  m_rresp_i,
  input  logic                        m_rlast_i,
  input  logic                        m_rvalid_i,
  output logic                        m_rready_o
);

  if (N == 1) begin : g_one
    assign m_arid_o     = s_arid_i[0];
    assign m_araddr_o   = s_araddr_i[0];
    assign m_arlen_o    = s_arlen_i[0];
    assign m_arsize_o   = s_arsize_i[0];
    assign m_arburst_o  = s_arburst_i[0];
    assign m_arvalid_o  = s_arvalid_i[0];
    assign s_arready_o  = m_arready_i;
    assign s_rid_o[0]   = m_rid_i;
    assign s_rdata_o[0] = m_rdata_i;
    assign s_rresp_o[0] = m_rresp_i;
    assign s_rlast_o[0] = m_rlast_i;
    assign s_rvalid_o   = m_rvalid_i;
    assign m_rready_o   = s_rready_i[0];
    logic unused;
    assign unused = ^{clk_i, rst_ni};
  end else begin : g_mux
    // ---- AR: round-robin grant, held until the handshake ---------------------------------------
    logic [SEL_W-1:0] gnt;       // the granted master
    rr_hold_arb #(.N(N)) u_arb (
      .clk_i, .rst_ni, .req_i(s_arvalid_i), .ready_i(m_arready_i), .gnt_o(gnt),
      .valid_o(m_arvalid_o));

    assign m_arid_o    = {gnt, s_arid_i[gnt]};
    assign m_araddr_o  = s_araddr_i[gnt];
    assign m_arlen_o   = s_arlen_i[gnt];
    assign m_arsize_o  = s_arsize_i[gnt];
    assign m_arburst_o = s_arburst_i[gnt];
    always_comb begin
      s_arready_o      = '0;
      s_arready_o[gnt] = m_arready_i;
    end

    // ---- R: by rid's top bits ------------------------------------------------------------------
    logic [SEL_W-1:0] rsel;
    assign rsel = m_rid_i[OID_W-1 -: SEL_W];
    for (genvar m = 0; m < N; m++) begin : g_r
      assign s_rid_o[m]    = m_rid_i[ID_W-1:0];
      assign s_rdata_o[m]  = m_rdata_i;
      assign s_rresp_o[m]  = m_rresp_i;
      assign s_rlast_o[m]  = m_rlast_i;
      assign s_rvalid_o[m] = m_rvalid_i && (rsel == SEL_W'(m));
    end
    // A rid naming no master (N not a power of two) is taken and dropped, never left hanging.
    assign m_rready_o = (int'(rsel) < N) ? s_rready_i[rsel] : 1'b1;
  end

endmodule
