// SPDX-License-Identifier: Apache-2.0
// frag_pkg: the memory layouts the system top reads and writes (docs: README "System top").
//
// Fragment record (the fragment buffer holds FRAG_COUNT of them back to back from FRAG_BASE,
// which is REC_BYTES aligned): REC_BYTES = 64 bytes, 16 little-endian 32-bit words; an f24 word
// in bits [23:0], bits [31:24] reserved (written 0, ignored):
//   word 0  u0            word 1  v0            word 2  Pl0
//   word 3  [7:0] triangle id, [31:8] pixel id (PIXID_W bits: {y, x}, x in the low PIX_X_W)
//   words 4..12  TBN: T (4..6), B (7..9), N (10..12)  (the columns of the matrix)
//   words 13..15 view vector x, y, z
// The pixel id is the pixel's place in the framebuffer: pixel (x, y) lies at
//   FB_BASE + y * FB_PITCH + x * 4      (RGBA8: byte 0 red, 1 green, 2 blue, 3 alpha = 0xFF)
// and, when the status buffer is enabled, its status word at ST_BASE + y * FB_PITCH + x * 4:
//   [15:0] iterations, [16] hit, [17] invalid, [18] error (a height or texel read failed),
//   [31] written (always 1: a word the unit wrote).
package frag_pkg;

  // A package of constants: each user takes the ones it needs.
  /* verilator lint_off UNUSEDPARAM */

  localparam int unsigned REC_BYTES  = 64;   // one fragment record
  localparam int unsigned REC_W      = 8 * REC_BYTES;
  localparam int unsigned REC_SHIFT  = 6;    // log2(REC_BYTES)
  localparam int unsigned PAGE_SHIFT = 12;   // AXI: a burst never crosses a 4 KiB boundary

  // word indices of the record
  localparam int unsigned W_U0   = 0;
  localparam int unsigned W_V0   = 1;
  localparam int unsigned W_PL0  = 2;
  localparam int unsigned W_ID   = 3;
  localparam int unsigned W_TBN  = 4;
  localparam int unsigned W_VIEW = 13;
  localparam int unsigned TRI_BITS = 8;      // word 3 [7:0]
  localparam int unsigned PIXID_W  = 24;     // word 3 [31:8]
  localparam int unsigned PIX_X_W  = 12;     // x in the pixel id's low bits: frames up to 4096 wide
  localparam int unsigned PIX_Y_W  = PIXID_W - PIX_X_W;

  // status word
  localparam int unsigned ST_HIT     = 16;
  localparam int unsigned ST_INVALID = 17;
  localparam int unsigned ST_ERR     = 18;
  localparam int unsigned ST_WRITTEN = 31;
  /* verilator lint_on UNUSEDPARAM */

endpackage
