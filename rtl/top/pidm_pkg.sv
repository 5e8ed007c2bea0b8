// SPDX-License-Identifier: Apache-2.0
// pidm_pkg: the memory formats of the system top pidm_top, written once here for the RTL and the
// Python (tb/harness/sv_params.py reads these localparams; scripts/pack_frame.py packs to them).
// docs/system.md describes them; the register map is rtl/top/pidm_regs.rdl.
//
// Fragment record (the fragment buffer at FRAME.FRAG_BASE, FRAME.FRAG_COUNT records one after the
// other): FRAG_BYTES bytes, FRAG_WORDS little-endian 32-bit words; word k at byte 4 k.  The f24
// words carry the 24-bit pattern in bits 23:0 (bits 31:24 zero).  dm_pipeline's fragment port:
//   word FRAG_U0_WORD    frag_u0_i            word FRAG_V0_WORD  frag_v0_i
//   word FRAG_PL0_WORD   frag_pl0_i
//   word FRAG_TRI_WORD   bits FRAG_TRI_LSB +: FRAG_TRI_BITS  frag_tri_i (triangle id)
//                        bits FRAG_ID_LSB  +: FRAG_ID_BITS   frag_id_i  (pixel id {y, x}: x in the
//                        low FRAME.FB_LAYOUT.xbits bits)
//   words FRAG_TBN_WORD  .. + 8   frag_tbn_i[0..8] (T 0..2, B 3..5, N 6..8)
//   words FRAG_VIEW_WORD .. + 2   frag_view_i[0..2]
// Framebuffer pixel (32 bits at FB_BASE + y * FB_PITCH + 4 x): R in bits 7:0, G 15:8, B 23:16,
// A (PIX_ALPHA) 31:24.  Status word (same offset from STATUS_BASE, FB_LAYOUT.status_en): the
// pixel's iterations in bits STW_ITERS_LSB +: STW_ITERS_BITS, hit, invalid and AXI-error flags at
// STW_HIT_BIT, STW_INVALID_BIT, STW_ERR_BIT; other bits zero.
package pidm_pkg;
  /* verilator lint_off UNUSEDPARAM */
  // ---- fragment record ------------------------------------------------------------------------
  localparam int unsigned FRAG_BYTES     = 64;  // one record (a multiple of the AXI data width)
  localparam int unsigned FRAG_WORDS     = 16;  // 32-bit words per record
  localparam int unsigned FRAG_U0_WORD   = 0;
  localparam int unsigned FRAG_V0_WORD   = 1;
  localparam int unsigned FRAG_PL0_WORD  = 2;
  localparam int unsigned FRAG_TRI_WORD  = 3;
  localparam int unsigned FRAG_TRI_LSB   = 0;
  localparam int unsigned FRAG_TRI_BITS  = 8;   // triangle ids 0 .. 255 (dm_pipeline TRIS)
  localparam int unsigned FRAG_ID_WORD   = 3;
  localparam int unsigned FRAG_ID_LSB    = 8;
  localparam int unsigned FRAG_ID_BITS   = 24;  // pixel id: PIX_W <= 24
  localparam int unsigned FRAG_TBN_WORD  = 4;   // 9 words
  localparam int unsigned FRAG_VIEW_WORD = 13;  // 3 words
  localparam int unsigned F24_BITS       = 24;  // an f24 word's pattern in bits 23:0

  // ---- framebuffer pixel and status word -------------------------------------------------------
  localparam int unsigned PIX_BYTES       = 4;
  localparam int unsigned PIX_ALPHA       = 255;  // A of every pixel written
  localparam int unsigned STW_ITERS_LSB   = 0;
  localparam int unsigned STW_ITERS_BITS  = 16;   // traverse_pkg::ITER_W
  localparam int unsigned STW_HIT_BIT     = 16;
  localparam int unsigned STW_INVALID_BIT = 17;
  localparam int unsigned STW_ERR_BIT     = 18;

  // ---- identification (rtl/top/pidm_regs.rdl ID, VERSION reset values) -------------------------
  localparam int unsigned PIDM_ID         = 32'h5049_444D;  // "PIDM"
  localparam int unsigned PIDM_VERSION    = 32'h0001_0000;  // major 1, minor 0
  /* verilator lint_on UNUSEDPARAM */
endpackage
