// SPDX-License-Identifier: Apache-2.0
// pipe_credit_tb: the credit controller in the place dm_pipeline uses it: an admission port in
// front of a LAT-clock unit that cannot stall (pipe_valid_tag), and a DEPTH-entry FIFO behind it
// whose fill counts against the same limit (the view_calc -> FIFO #0 arrangement).  Every
// (DEPTH, LAT) tb/pipe_credit checks is built side by side in one build: g_case[i] holds the
// arrangement with DEPTH = DEPTH_OF[i], LAT = LAT_OF[i] and its own ports (signals named as
// ports), so the cocotb test drives and checks each through the hierarchy
// (dut.g_case[i].in_valid_i, ...), with its own reset; only the clock is shared.  The table is
// the test's CASES (the test reads DEPTH and LAT back and stops if they differ).
module pipe_credit_tb (
  input logic clk_i
);

  localparam int unsigned NCASE = 3;
  // dm_pipeline's FIFO #0 depth (F0_DEPTH = 16) behind a shorter latency; a FIFO shallower than
  // the latency (the credit throttles, as for FIFO #0 behind view_calc, pipe_pkg::VIEW_CALC_LAT
  // = 21); the smallest case
  localparam int unsigned DEPTH_OF [NCASE] = '{16, 4, 2};  // FIFO depth = credit limit (2^k)
  localparam int unsigned LAT_OF   [NCASE] = '{14, 11, 1}; // latency of the unit (no stall)

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned DEPTH = DEPTH_OF[i];
    localparam int unsigned LAT   = LAT_OF[i];

    // the arrangement's ports
    logic                   rst_ni;
    logic                   in_valid_i, in_ready_o, out_valid_o, out_ready_i;
    logic [15:0]            in_data_i, out_data_o;
    logic [$clog2(DEPTH):0] count_o;       // items inside the unit
    logic [$clog2(DEPTH):0] fifo_count_o;  // items in the FIFO

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
  end

endmodule
