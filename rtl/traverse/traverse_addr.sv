// SPDX-License-Identifier: Apache-2.0
// traverse_addr: the byte address of a height lookup (traverse_loop stage S0), combinational
// from its inputs and the level-offset table.
//
// Mirrors model/traverse.py::texel_offset over the memory layout of model/heightmap.py
// (Pyramid.level_offsets, Pyramid.memory_image): levels stored one after the other from level 0
// up, level k row-major with a row pitch of N >> k = 2^(n-k) texels, one code per texel (1 byte
// for unorm8, 2 bytes little-endian for unorm16):
//   addr = base + level_off[k] + (cy * 2^(n-k) + cx) * bytes      (modulo 2^ADDR_W)
// The model's trace reads the same texel as flat[texel_offset(offs, n, k, cx, cy)].  Only cells
// of the pyramid are meaningful: k <= n and cx, cy < 2^(n-k).
// The client gives n - k (nk_i) besides k: the ring registers it with the node, so that the row
// pitch's shift starts at a register (n - k in front of the shifter was on the ring's slowest
// path).
// The level offsets (Pyramid.level_offsets) are a table of MAX_LEVELS words in LUT RAM, written
// through hlt_* (one word per clock with hlt_we_i = 1; not reset: every level a lookup reads must
// be written first; static while lookups run) and read asynchronously at k_i.  (A flip-flop
// array read through a 16:1 multiplexer instead took about 480 LUT4 on the ECP5.)
module traverse_addr
  import traverse_pkg::*;
(
  input  logic                              clk_i,        // the table's write clock
  input  logic                              hlt_we_i,     // write hlt_wdata_i as level
  input  logic [LVL_W-1:0]                  hlt_waddr_i,  //   hlt_waddr_i's offset
  input  logic [ADDR_W-1:0]                 hlt_wdata_i,  // byte offset of that level from base_i
  input  logic [ADDR_W-1:0]                 base_i,       // byte address of the pyramid
  input  logic                              bits16_i,     // 1: unorm16 (2 bytes), 0: unorm8
  input  logic [LVL_W-1:0]                  k_i,          // level of the node (k <= n)
  input  logic [LVL_W-1:0]                  nk_i,         // n - k (root level n, N = 2^n)
  input  logic [CELL_W-1:0]                 cx_i,         // node column at level k
  input  logic [CELL_W-1:0]                 cy_i,         // node row at level k
  output logic [ADDR_W-1:0]                 addr_o,       // byte address of the node's code
  output logic                              wide_o        // 1: a 2-byte (unorm16) lookup
);

  logic [ADDR_W-1:0] texel;     // offset of the texel inside its level, in texels
  logic [ADDR_W-1:0] off_mem [MAX_LEVELS];  // level offsets (LUT RAM)

  always_ff @(posedge clk_i) begin
    if (hlt_we_i) off_mem[hlt_waddr_i] <= hlt_wdata_i;
  end

  // Two independent sums, then one more (not a chain of three): the level's address and the
  // texel's offset in it, (cy << (n - k) + cx) * bytes = ((cy << (n - k)) + cx) << bits16
  // (modulo 2^ADDR_W alike).
  assign texel    = (ADDR_W'(cy_i) << nk_i) + ADDR_W'(cx_i);
  assign addr_o   = (base_i + off_mem[k_i]) + (texel << bits16_i);
  assign wide_o     = bits16_i;

endmodule
