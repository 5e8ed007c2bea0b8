// SPDX-License-Identifier: Apache-2.0
// circ_queue_tb: circ_queue in every configuration tb/circ_queue checks, side by side in one
// build: g_case[i] holds circ_queue with the parameters of row i of the table below and its own
// copy of the unit's ports (named as the ports), so the cocotb test drives and checks each
// through the hierarchy (dut.g_case[i].push_i, ...), with its own reset; only the clock is
// shared.  The table is the test's CASES (the test reads the parameters back and stops if they
// differ).
module circ_queue_tb (
  input logic clk_i
);

  localparam int unsigned NCASE = 9;
  // the AR queues (tex_cache: 4 lanes, height_cache: 1), the free list of MSHRs, the request
  // FIFO, the output buffer, and odd depths
  localparam int unsigned WIDTH_OF    [NCASE] = '{4, 2, 4, 37, 13, 5, 3, 6, 9};
  localparam int unsigned DEPTH_OF    [NCASE] = '{16, 4, 16, 8, 4, 5, 1, 7, 3};
  localparam int unsigned NPUSH_OF    [NCASE] = '{4, 1, 1, 1, 1, 3, 1, 1, 1};
  localparam int unsigned NPOP_OF     [NCASE] = '{1, 1, 4, 1, 1, 2, 1, 3, 1};
  localparam bit          INIT_SEQ_OF [NCASE] = '{0, 0, 1, 0, 0, 0, 0, 1, 0};
  localparam bit          ASYNC_RD_OF [NCASE] = '{1, 1, 1, 0, 1, 1, 1, 1, 1};
  localparam int unsigned PEEK_OF     [NCASE] = '{0, 0, 0, 2, 0, 0, 0, 1, 2};

  for (genvar i = 0; i < NCASE; i++) begin : g_case
    localparam int unsigned WIDTH    = WIDTH_OF[i];
    localparam int unsigned DEPTH    = DEPTH_OF[i];
    localparam int unsigned NPUSH    = NPUSH_OF[i];
    localparam int unsigned NPOP     = NPOP_OF[i];
    localparam bit          INIT_SEQ = INIT_SEQ_OF[i];
    localparam bit          ASYNC_RD = ASYNC_RD_OF[i];
    localparam int unsigned PEEK     = PEEK_OF[i];

    logic                        rst_ni;
    logic [NPUSH-1:0]            push_i, wr_i;
    logic [NPUSH-1:0][WIDTH-1:0] wdata_i;
    logic [$clog2(NPOP + 1)-1:0] pop_n_i;
    logic [NPOP-1:0][WIDTH-1:0]  rdata_o;
    logic [WIDTH-1:0]            peek_o;
    logic [$clog2(DEPTH + 1)-1:0] count_o;

    circ_queue #(
      .WIDTH(WIDTH), .DEPTH(DEPTH), .NPUSH(NPUSH), .NPOP(NPOP), .INIT_SEQ(INIT_SEQ),
      .ASYNC_RD(ASYNC_RD), .PEEK(PEEK)
    ) u_dut (
      .clk_i, .rst_ni, .push_i, .wr_i, .wdata_i, .pop_n_i, .rdata_o, .peek_o, .count_o);
  end

endmodule
