// SPDX-License-Identifier: Apache-2.0
// traverse_start_level: the start decision of the first mode (traverse_setup's last stages),
// latency 2 enabled clocks, one decision per clock; registers advance only while en_i is 1.
//
// Mirrors model/traverse.py::start_node (called from _trace's "first mode" block): from the level-0
// start cell c0 as locate() found it (one cell outside the padded map, -1 or N = 2^n, when the
// ray starts off it) and the floor of the end point A (f24_to_index of its position, unclipped):
//   outside = c0 is outside the map's own extent [0, W) x [0, H)    (the ray never enters)
//   c0, a   = both clipped to the padded map [0, N - 1]
//   k       = (a) ? min(bitlen(max(c0x ^ ax, c0y ^ ay)), n) : n      (XOR, leading-zero count)
//   cell    = c0 >> k                                                 (the start node)
// bitlen is the number of significant bits ("levels minus leading zeros"): the lowest level at
// which the start and end cells share a node.  Without the start-level policy the start is the
// root (the end point is then ignored).
//
// Stages (the whole decision in one clock was 16 ns on the ECP5):
//   1: N - 1, the clips, outside, the XORs ORed (bitlen(max(p, q)) = bitlen(p | q));
//   2: the leading-zero count and k;
//   out: the shift c0 >> k (straight from the stage-2 register).
// The configuration inputs (n, W, H, the policy) are sampled with the cells in stage 1, so that
// every decision uses the configuration it was presented with.
module traverse_start_level
  import traverse_pkg::*;
(
  input  logic                    clk_i,          // clock
  input  logic                    en_i,           // clock enable: the registers advance while 1
  input  logic [LVL_W-1:0]        n_i,            // root level n: the padded map is N = 2^n square
  input  logic [DIM_W-1:0]        width_i,        // map width W (level-0 texels)
  input  logic [DIM_W-1:0]        height_i,       // map height H
  input  logic                    start_level_i,  // policy (a): start level by XOR / leading zeros
  input  sidx_t                   c0x_i,          // located start cell at level 0 (-1 .. N)
  input  sidx_t                   c0y_i,
  input  logic signed [IDX_W-1:0] ex_i,           // floor of the end point's u (unclipped)
  input  logic signed [IDX_W-1:0] ey_i,           // floor of the end point's v (unclipped)
  output logic                    outside_o,      // the start cell is outside [0, W) x [0, H)
  output logic [LVL_W-1:0]        k_o,            // start level
  output logic [CELL_W-1:0]       cx_o,           // start node at level k: c0x >> k
  output logic [CELL_W-1:0]       cy_o            // c0y >> k
);

  // ---- stage 1: clips, outside, XOR -----------------------------------------------------------
  sidx_t last;                // N - 1
  sidx_t c0x, c0y;            // start cell, clipped
  sidx_t ax, ay;              // end cell, clipped
  assign last = (sidx_t'(1) <<< n_i) - sidx_t'(1);
  assign c0x  = clip_idx(c0x_i, '0, last);
  assign c0y  = clip_idx(c0y_i, '0, last);
  assign ax   = clip_idx(sidx_t'(ex_i), '0, last);
  assign ay   = clip_idx(sidx_t'(ey_i), '0, last);

  logic              outside1_q, outside2_q;
  logic              sl1_q;
  logic [LVL_W-1:0]  n1_q, k2_q;
  logic [CELL_W-1:0] c0x1_q, c0y1_q, c0x2_q, c0y2_q;  // clipped start cell (cells < 2^15)
  logic [15:0]       xo1_q;                           // (c0x ^ ax) | (c0y ^ ay)

  // ---- stage 2: leading zeros, k ----------------------------------------------------------------
  logic [4:0] kbits;          // bitlen(xo), 0 .. 16
  assign kbits = bitlen16(xo1_q);

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      outside1_q <= (c0x_i < 0) || (c0x_i >= sidx_t'(width_i)) ||
                    (c0y_i < 0) || (c0y_i >= sidx_t'(height_i));
      sl1_q      <= start_level_i;
      n1_q       <= n_i;
      c0x1_q     <= CELL_W'(c0x);
      c0y1_q     <= CELL_W'(c0y);
      xo1_q      <= 16'(c0x ^ ax) | 16'(c0y ^ ay);
      outside2_q <= outside1_q;
      k2_q       <= (sl1_q && kbits < {1'b0, n1_q}) ? LVL_W'(kbits) : n1_q;
      c0x2_q     <= c0x1_q;
      c0y2_q     <= c0y1_q;
    end
  end

  // ---- out: the start node ----------------------------------------------------------------------
  assign outside_o = outside2_q;
  assign k_o       = k2_q;
  assign cx_o      = c0x2_q >> k2_q;
  assign cy_o      = c0y2_q >> k2_q;

endmodule
