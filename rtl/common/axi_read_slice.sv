// SPDX-License-Identifier: Apache-2.0
// axi_read_slice: a register slice on both channels of an AXI4 read port (AR: id, address, len,
// size, burst; R: id, data, resp, last), one skid_buffer with REG_OUT 1 per channel.  Every
// output of either side comes from a flip-flop (valid, payload and ready), so no combinational
// path crosses the slice; each channel passes a beat a clock and adds one clock of latency (a
// read's data arrives two clocks later than without the slice).  s_*: the master's side (the
// slave port the master drives), m_*: the memory's side.  The order and the payloads of the
// beats are unchanged (skid_buffer's proofs, formal/skid_buffer.sby).
module axi_read_slice #(
  parameter int unsigned ID_W   = 4,   // AXI ID width
  parameter int unsigned ADDR_W = 32,  // address width
  parameter int unsigned DATA_W = 64   // R data width
) (
  input  logic              clk_i,
  input  logic              rst_ni,     // synchronous, active low: empties both slices
  // the master's side
  input  logic [ID_W-1:0]   s_arid,
  input  logic [ADDR_W-1:0] s_araddr,
  input  logic [7:0]        s_arlen,
  input  logic [2:0]        s_arsize,
  input  logic [1:0]        s_arburst,
  input  logic              s_arvalid,
  output logic              s_arready,
  output logic [ID_W-1:0]   s_rid,
  output logic [DATA_W-1:0] s_rdata,
  output logic [1:0]        s_rresp,
  output logic              s_rlast,
  output logic              s_rvalid,
  input  logic              s_rready,
  // the memory's side
  output logic [ID_W-1:0]   m_arid,
  output logic [ADDR_W-1:0] m_araddr,
  output logic [7:0]        m_arlen,
  output logic [2:0]        m_arsize,
  output logic [1:0]        m_arburst,
  output logic              m_arvalid,
  input  logic              m_arready,
  input  logic [ID_W-1:0]   m_rid,
  input  logic [DATA_W-1:0] m_rdata,
  input  logic [1:0]        m_rresp,
  input  logic              m_rlast,
  input  logic              m_rvalid,
  output logic              m_rready
);

  localparam int unsigned AR_W = ID_W + ADDR_W + 8 + 3 + 2;  // id, address, len, size, burst
  localparam int unsigned R_W  = ID_W + DATA_W + 2 + 1;      // id, data, resp, last

  skid_buffer #(.W(AR_W), .REG_OUT(1'b1)) u_ar (
    .clk_i, .rst_ni,
    .valid_i(s_arvalid), .ready_o(s_arready),
    .data_i({s_arid, s_araddr, s_arlen, s_arsize, s_arburst}),
    .valid_o(m_arvalid), .ready_i(m_arready),
    .data_o({m_arid, m_araddr, m_arlen, m_arsize, m_arburst}));

  skid_buffer #(.W(R_W), .REG_OUT(1'b1)) u_r (
    .clk_i, .rst_ni,
    .valid_i(m_rvalid), .ready_o(m_rready),
    .data_i({m_rid, m_rdata, m_rresp, m_rlast}),
    .valid_o(s_rvalid), .ready_i(s_rready),
    .data_o({s_rid, s_rdata, s_rresp, s_rlast}));

endmodule
