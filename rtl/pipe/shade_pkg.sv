// SPDX-License-Identifier: Apache-2.0
// shade_pkg: the colour-calculation unit's latency, configuration record and fixed constants
// (rtl/pipe/shade_unit.sv; specification model/shade.py shade(), the f24 engine).
//
// SHADE_LAT counts enabled clocks (edges with en_i = 1), like the float units of rtl/fp/: a pixel
// presented on an enabled edge with valid_i = 1 shows at valid_o / tag_o / rgb_o after SHADE_LAT
// enabled edges and holds while en_i is 0.  shade_unit.sv's header derives it stage by stage.
// (To be merged into pipe_pkg later.)
package shade_pkg;

  import f24_pkg::f24_t;

  // Each user reads only the constants it needs.
  /* verilator lint_off UNUSEDPARAM */

  // Critical path (a shared unit's operation starts a clock after the result it takes, which
  // its operand register holds): view vector (mul 1, add 1 + 2, add 1 + 2, rsqrt 1 + 3,
  // mul 1 + 1), half vector (add 1 + 2, mul 1 + 1, add 1 + 2, add 1 + 2, rsqrt 1 + 3, mul 1 + 1),
  // n.h (mul 1 + 1, add 1 + 2, the wait for dot(n, l) 1, add 1 + 2), max 1, four squarings 4,
  // KS mul 1, the wait for a 1, colour add 1 + 2, clamp 1, x255 mul 1, +0.5 add 2, floor 1, two
  // clocks more for G and B, which follow R on one lane a clock apart each, and three for the
  // alignment (a pixel enters the core on phase 0 mod 4, up to 3 clocks late; the others wait
  // at the output).  shade_unit.sv's header has the stage schedule.
  // rsqrt: f24_rsqrt #(.LAT(3)) (pipe_pkg::F24_RSQRT_LAT).
  localparam int unsigned SHADE_LAT = 59;

  // Per-frame configuration: every field is the f24 pattern of the model's const(...) of that
  // quantity (model.f24.from_float of the float64 value; the driver precomputes them), static
  // while the unit is busy.  Packed, light_x is the most significant field (bits 191:168).
  typedef struct packed {
    f24_t light_x;  // unit light vector l = Material.light_unit(), rounded per component
    f24_t light_y;
    f24_t light_z;
    f24_t ambient;  // Material.ambient (AMBIENT)
    f24_t kd;       // Material.kd (KD)
    f24_t ks;       // Material.ks (KS)
    f24_t d;        // D, the depth scale in texels
    f24_t d2;       // mul(D, D) in the f24 engine (model.f24.mul(d, d))
  } shade_cfg_t;

  // Constants of shade() that are not per frame (model.shade: EPS, and the literals 2, 1, 0, 255
  // and 0.5), hard-wired; tb/shade_unit checks these patterns against model.f24.from_float.
  localparam f24_t SHADE_EPS  = 24'h170000;  // EPS = 2^-40
  localparam f24_t SHADE_TWO  = 24'h400000;  // 2.0 (the decode's mul(M, 2), done as an exact
                                             // doubling, see shade_unit)
  localparam f24_t SHADE_ONE  = 24'h3f0000;  // 1.0
  localparam f24_t SHADE_ZERO = 24'h000000;  // +0
  localparam f24_t SHADE_255  = 24'h46fe00;  // 255.0
  localparam f24_t SHADE_HALF = 24'h3e0000;  // 0.5

  /* verilator lint_on UNUSEDPARAM */

endpackage
