// SPDX-License-Identifier: Apache-2.0
// skid_buffer_tb: skid_buffer in both modes side by side in one build: g_case[i] holds a
// skid_buffer with REG_OUT = i and its own copy of the unit's ports (named as the ports), so the
// cocotb test drives and checks each through the hierarchy (dut.g_case[i].valid_i, ...), with its
// own reset; only the clock is shared.
module skid_buffer_tb #(
  parameter int unsigned W = 16  // payload bits of both
) (
  input logic clk_i
);

  for (genvar i = 0; i < 2; i++) begin : g_case
    localparam bit REG_OUT = i[0];  // the test reads it back (its table: REG_OUTS)

    logic         rst_ni, valid_i, ready_o, valid_o, ready_i;
    logic [W-1:0] data_i, data_o;

    skid_buffer #(.W(W), .REG_OUT(REG_OUT)) u_dut (
      .clk_i, .rst_ni, .valid_i, .ready_o, .data_i, .valid_o, .ready_i, .data_o);
  end

endmodule
