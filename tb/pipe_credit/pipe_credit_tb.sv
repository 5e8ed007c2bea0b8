// SPDX-License-Identifier: Apache-2.0
// pipe_credit_tb: the credit controller in the place dm_pipeline uses it: an admission port in
// front of a LAT-clock unit that cannot stall (pipe_valid_tag), and a DEPTH-entry FIFO behind it
// whose fill counts against the same limit (the view_calc -> FIFO #0 arrangement).
module pipe_credit_tb #(
  parameter int unsigned DEPTH = 16,  // FIFO depth = credit limit (power of two)
  parameter int unsigned LAT   = 8    // latency of the unit that cannot stall
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic                       in_valid_i,
  output logic                       in_ready_o,
  input  logic [15:0]                in_data_i,
  output logic                       out_valid_o,
  input  logic                       out_ready_i,
  output logic [15:0]                out_data_o,
  output logic [$clog2(DEPTH):0]     count_o,      // items inside the unit
  output logic [$clog2(DEPTH):0]     fifo_count_o  // items in the FIFO
);

  logic        take, room, lat_valid, empty, full;
  logic [15:0] lat_data;

  assign take       = in_valid_i && room;
  assign in_ready_o = room;

  pipe_valid_tag #(.TAG_W(16), .DEPTH(LAT)) u_unit (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(take), .tag_i(in_data_i), .valid_o(lat_valid),
    .tag_o(lat_data));

  pipe_credit #(.LIMIT(DEPTH)) u_credit (
    .clk_i, .rst_ni, .take_i(take), .give_i(lat_valid), .held_i(fifo_count_o), .room_o(room),
    .count_o);

  traverse_fifo #(.W(16), .DEPTH(DEPTH)) u_fifo (
    .clk_i, .rst_ni, .wr_i(lat_valid), .wr_data_i(lat_data), .rd_i(out_valid_o && out_ready_i),
    .rd_data_o(out_data_o), .full_o(full), .empty_o(empty), .count_o(fifo_count_o));

  assign out_valid_o = !empty;

  logic unused;
  assign unused = full;

endmodule
