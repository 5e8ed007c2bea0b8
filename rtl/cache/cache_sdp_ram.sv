// cache_sdp_ram: simple dual-port RAM (one write port, one read port, one clock), synchronous
// read: rdata_o shows mem[raddr_i] from the clock after re_i (and holds while re_i is 0).
// A read of the address written in the same clock returns the old word in simulation; real RAMs
// may differ, so the height cache never relies on it (it discards such reads).
module cache_sdp_ram #(
  parameter int unsigned DEPTH = 64,  // >= 2
  parameter int unsigned WIDTH = 32,
  parameter int unsigned AW    = $clog2(DEPTH)
) (
  input  logic             clk_i,
  input  logic             we_i,
  input  logic [AW-1:0]    waddr_i,
  input  logic [WIDTH-1:0] wdata_i,
  input  logic             re_i,
  input  logic [AW-1:0]    raddr_i,
  output logic [WIDTH-1:0] rdata_o
);

  if (DEPTH < 2 || AW != $clog2(DEPTH)) begin : g_check
    $error("cache_sdp_ram: DEPTH must be >= 2 and AW = $clog2(DEPTH)");
  end

  logic [WIDTH-1:0] mem_q [DEPTH];
  logic [WIDTH-1:0] rdata_q;

  always_ff @(posedge clk_i) begin
    if (we_i) mem_q[waddr_i] <= wdata_i;
    if (re_i) rdata_q <= mem_q[raddr_i];
  end

  assign rdata_o = rdata_q;

endmodule
