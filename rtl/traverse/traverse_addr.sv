// SPDX-License-Identifier: Apache-2.0
// traverse_addr: the byte address of a height lookup (traverse_loop stage S0), purely
// combinational.
//
// Mirrors model/traverse.py::texel_offset over the memory layout of model/heightmap.py
// (Pyramid.level_offsets, Pyramid.memory_image): levels stored one after the other from level 0
// up, level k row-major with a row pitch of N >> k = 2^(n-k) texels, one code per texel (1 byte
// for unorm8, 2 bytes little-endian for unorm16):
//   addr = base + level_off[k] + (cy * 2^(n-k) + cx) * bytes      (modulo 2^ADDR_W)
// The model's trace reads the same texel as flat[texel_offset(offs, n, k, cx, cy)].  Only cells
// of the pyramid are meaningful: k <= n and cx, cy < 2^(n-k).
module traverse_addr
  import traverse_pkg::*;
(
  input  logic [ADDR_W-1:0]                 base_i,       // byte address of the pyramid
  input  logic [MAX_LEVELS-1:0][ADDR_W-1:0] level_off_i,  // byte offset of level k from base_i
  input  logic [LVL_W-1:0]                  n_i,          // root level n (N = 2^n)
  input  logic                              bits16_i,     // 1: unorm16 (2 bytes), 0: unorm8
  input  logic [LVL_W-1:0]                  k_i,          // level of the node (k <= n)
  input  logic [CELL_W-1:0]                 cx_i,         // node column at level k
  input  logic [CELL_W-1:0]                 cy_i,         // node row at level k
  output logic [ADDR_W-1:0]                 addr_o,       // byte address of the node's code
  output logic                              wide_o        // 1: a 2-byte (unorm16) lookup
);

  logic [LVL_W:0]    row_log2;  // log2 of level k's row pitch in bytes: n - k + bits16
  logic [ADDR_W-1:0] texel;     // byte offset of the texel inside its level

  // Two independent sums, then one more (not a chain of three): the level's address and the
  // texel's offset in it, (cy << (n - k) + cx) * bytes = (cy << row_log2) + (cx << bits16).
  assign row_log2 = (LVL_W+1)'(n_i - k_i) + (LVL_W+1)'(bits16_i);
  assign texel    = (ADDR_W'(cy_i) << row_log2) + (ADDR_W'(cx_i) << bits16_i);
  assign addr_o   = (base_i + level_off_i[k_i]) + texel;
  assign wide_o     = bits16_i;

endmodule
