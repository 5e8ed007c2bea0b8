// SPDX-License-Identifier: Apache-2.0
// cache_sdp_ram: simple dual-port RAM (one write port, one read port, one clock), synchronous
// read.  A word is LANES lanes of WIDTH / LANES bits: the write port writes whole words, the read
// port reads one lane, so rdata_o shows lane rlane_i of mem[raddr_i] from the clock after re_i
// (and holds while re_i is 0).  LANES = 1 is an ordinary RAM (rlane_i is ignored); LANES > 1 a
// RAM whose read port is narrower than its write port (the height cache writes whole lines and
// reads one 16-bit texel word): the read register holds the word, the lane is picked after it.
// A read of the address written in the same clock returns the old word in simulation; real RAMs
// may differ, so the height cache never relies on it (it discards such reads).
module cache_sdp_ram #(
  parameter int unsigned DEPTH = 64,  // >= 2
  parameter int unsigned WIDTH = 32,  // word (write port) width, a multiple of LANES
  parameter int unsigned LANES = 1,   // lanes per word (a power of two): read width WIDTH / LANES
  parameter int unsigned AW    = $clog2(DEPTH),
  parameter int unsigned LW    = WIDTH / LANES,                  // lane (read port) width
  parameter int unsigned SW    = (LANES > 1) ? $clog2(LANES) : 1  // lane index width
) (
  input  logic             clk_i,
  input  logic             we_i,
  input  logic [AW-1:0]    waddr_i,
  input  logic [WIDTH-1:0] wdata_i,
  input  logic             re_i,
  input  logic [AW-1:0]    raddr_i,
  /* verilator lint_off UNUSEDSIGNAL */  // LANES = 1: no lane to choose
  input  logic [SW-1:0]    rlane_i = '0,  // lane to read (may be left unconnected when LANES = 1)
  /* verilator lint_on UNUSEDSIGNAL */
  output logic [LW-1:0]    rdata_o
);

  if (DEPTH < 2 || AW != $clog2(DEPTH)) begin : g_check
    $error("cache_sdp_ram: DEPTH must be >= 2 and AW = $clog2(DEPTH)");
  end
  if (LANES < 1 || (1 << $clog2(LANES)) != LANES || LW * LANES != WIDTH
      || SW != ((LANES > 1) ? $clog2(LANES) : 1)) begin : g_check_lanes
    $error("cache_sdp_ram: LANES must be a power of two dividing WIDTH (LW, SW derived)");
  end

  // no_rw_check: the users never use a read of a word written in the same clock (see above), so
  // Yosys need not emulate the old-data rule around the block RAM (a copy of the written word, an
  // address compare and a multiplexer per read bit).
  (* no_rw_check *) logic [LANES-1:0][LW-1:0] mem_q [DEPTH];

  always_ff @(posedge clk_i) begin
    if (we_i) mem_q[waddr_i] <= wdata_i;
  end

  // The read register holds the whole word and the lane is chosen after it: a synchronous read
  // port straight into a register is what block RAM offers (Yosys maps it to ECP5 EBR / Xilinx
  // BRAM; with the lane multiplexer in front of the register the read port is asynchronous and
  // becomes LUT RAM).
  if (LANES > 1) begin : g_lanes
    logic [LANES-1:0][LW-1:0] word_q;
    logic [SW-1:0]            lane_q;
    always_ff @(posedge clk_i) begin
      if (re_i) begin
        word_q <= mem_q[raddr_i];
        lane_q <= rlane_i;
      end
    end
    assign rdata_o = word_q[lane_q];
  end else begin : g_word
    logic [LW-1:0] rdata_q;
    always_ff @(posedge clk_i) begin
      if (re_i) rdata_q <= mem_q[raddr_i];
    end
    assign rdata_o = rdata_q;
  end

endmodule
