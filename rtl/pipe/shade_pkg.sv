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

  // ---- the stage schedule, a function of the float units' latencies ---------------------------
  // shade_unit's 41 shared-unit operations (a lane-0 "stream" op, x then z, counts once and takes
  // two consecutive phases), listed in their priority order: each operation, in this order, takes
  // the first core stage a at or after the stage its operands are ready in whose phase a mod 4
  // (and a + 1 mod 4 for a stream) its unit has not given to an earlier-listed operation.  An
  // operand that is another unit's result in stage b is ready for a >= b + 1 (the unit's operand
  // register is loaded by its select in a - 1); the inputs are ready in S0.  The order (the
  // critical path, view vector -> half vector -> n.h -> colour, before the normal's chain) is the
  // one design choice; at (ADD_LAT, MUL_LAT) = (2, 1) it gives the hand schedule of the paper's
  // depths (SHADE_LAT 67), at (3, 2) SHADE_LAT 90.  tb/shade_unit mirrors this in Python.
  localparam int unsigned SHADE_NOPS = 41;
  localparam int unsigned SHADE_NUNITS = 15;  // the shared units (+ the direct-fed pseudo units)
  // operations (priority order) ...
  localparam int unsigned OP_DU2 = 0, OP_NY = 1, OP_NY2 = 2, OP_DV2 = 3, OP_UV = 4, OP_VV = 5,
                          OP_RV = 6, OP_VY = 7, OP_VXZ = 8, OP_HXZ = 9, OP_HXZ2 = 10, OP_HY = 11,
                          OP_HY2 = 12, OP_HXY2 = 13, OP_HH = 14, OP_RH = 15, OP_HUY = 16,
                          OP_HUXZ = 17, OP_NXZ = 18, OP_NXY2 = 19, OP_NN = 20, OP_RN = 21,
                          OP_NUXZ = 22, OP_NHXZ = 23, OP_NUY = 24, OP_NHY = 25, OP_NHXY = 26,
                          OP_NLY = 27, OP_NLXY = 28, OP_DOTS = 29, OP_KDN = 30, OP_A = 31,
                          OP_CYA = 32, OP_S2 = 33, OP_S4 = 34, OP_S8 = 35, OP_S16 = 36,
                          OP_CAXZ = 37, OP_SP = 38, OP_CG = 39, OP_CRB = 40;
  // ... and their units
  localparam int unsigned U_UV2HY2 = 0, U_DVNC = 1, U_NC = 2, U_NUA = 3, U_NV = 4, U_NY2H = 5,
                          U_VA = 6, U_NXH = 7, U_HD = 8, U_HKD = 9, U_RVNH = 10, U_NUNH1 = 11,
                          U_HUNH1 = 12, U_CAA = 13, U_SQ = 14;

  // The unit of an operation, and whether it is a stream (x in a, z in a + 1).
  function automatic int unsigned shade_op_unit(input int unsigned op);
    case (op)
      OP_DU2, OP_HY2:                     return U_UV2HY2;
      OP_DV2, OP_NUXZ, OP_CYA:            return U_DVNC;
      OP_NXZ, OP_CRB:                     return U_NC;
      OP_NY, OP_UV, OP_A, OP_CG:          return U_NUA;
      OP_VV, OP_NN, OP_HXY2, OP_HH:       return U_NV;
      OP_NY2, OP_VY, OP_HUXZ:             return U_NY2H;
      OP_VXZ:                             return U_VA;
      OP_NXY2, OP_HXZ, OP_NLXY:           return U_NXH;
      OP_HY, OP_NHXY, OP_DOTS:            return U_HD;
      OP_HXZ2, OP_KDN:                    return U_HKD;
      OP_RV, OP_RN, OP_RH:                return U_RVNH;
      OP_NUY, OP_NHXZ:                    return U_NUNH1;
      OP_HUY, OP_NHY, OP_NLY:             return U_HUNH1;
      OP_S2, OP_S4, OP_S8, OP_S16:        return U_SQ;
      default:                            return U_CAA;  // OP_CAXZ, OP_SP
    endcase
  endfunction

  function automatic logic shade_op_stream(input int unsigned op);
    return op inside {OP_VXZ, OP_HXZ, OP_HXZ2, OP_HUXZ, OP_NXZ, OP_NUXZ, OP_NHXZ, OP_DOTS,
                      OP_CAXZ, OP_CRB};
  endfunction

  // The latency of an operation's unit.
  function automatic int unsigned shade_op_lat(input int unsigned op, input int unsigned add_lat,
                                               input int unsigned mul_lat);
    case (shade_op_unit(op))
      U_NC, U_NUA, U_NV, U_NXH, U_HD: return add_lat;
      U_RVNH:                         return pipe_pkg::F24_RSQRT_LAT;
      default:                        return mul_lat;
    endcase
  endfunction

  // The core stage of operation `op` (the stage its unit works on its operands in).
  /* verilator lint_off UNUSEDSIGNAL */  // op: an index below SHADE_NOPS
  function automatic int unsigned shade_op_stage(input int unsigned op, input int unsigned add_lat,
                                                 input int unsigned mul_lat);
    int unsigned st [SHADE_NOPS];
    int unsigned rs [SHADE_NOPS];
    logic [4*SHADE_NUNITS-1:0] used;  // unit u's phase r: bit 4 u + r
    int unsigned e, a, u, m;
    m = mul_lat;
    used = '0;
    for (int unsigned i = 0; i < SHADE_NOPS; i++) begin
      st[i] = 0;
      rs[i] = 0;
    end
    for (int unsigned i = 0; i < SHADE_NOPS; i++) begin
      // the last stage an operand becomes ready in (x of a stream; its z comes a stage later)
      case (i)
        OP_DU2, OP_NY, OP_DV2, OP_NXZ: e = 0;                              // the inputs
        OP_NY2:  e = rs[OP_NY];
        OP_UV:   e = (rs[OP_DU2] > rs[OP_DV2]) ? rs[OP_DU2] : rs[OP_DV2];
        OP_VV:   e = rs[OP_UV];
        OP_RV, OP_VY, OP_VXZ: e = rs[(i == OP_RV) ? OP_VV : OP_RV];
        OP_HXZ:  e = rs[OP_VXZ];
        OP_HXZ2: e = rs[OP_HXZ];
        OP_HY:   e = rs[OP_VY];
        OP_HY2:  e = rs[OP_HY];
        OP_HXY2: e = (rs[OP_HXZ2] > rs[OP_HY2]) ? rs[OP_HXZ2] : rs[OP_HY2];
        OP_HH:   e = (rs[OP_HXY2] > rs[OP_HXZ2] + 1) ? rs[OP_HXY2] : rs[OP_HXZ2] + 1;
        OP_RH:   e = rs[OP_HH];
        OP_HUY:  e = (rs[OP_RH] > rs[OP_HY]) ? rs[OP_RH] : rs[OP_HY];
        OP_HUXZ: e = (rs[OP_RH] > rs[OP_HXZ]) ? rs[OP_RH] : rs[OP_HXZ];
        // n_x^2, n_z^2: u_nsqa, fed directly by u_nc, in rs[OP_NXZ] + mul_lat (+ 1)
        OP_NXY2: e = (rs[OP_NXZ] + m > rs[OP_NY2]) ? rs[OP_NXZ] + m : rs[OP_NY2];
        OP_NN:   e = (rs[OP_NXY2] > rs[OP_NXZ] + m + 1) ? rs[OP_NXY2] : rs[OP_NXZ] + m + 1;
        OP_RN:   e = rs[OP_NN] + 1;                                   // max(nn, EPS): a register
        OP_NUXZ: e = (rs[OP_RN] > rs[OP_NXZ]) ? rs[OP_RN] : rs[OP_NXZ];
        OP_NHXZ: e = (rs[OP_NUXZ] > rs[OP_HUXZ]) ? rs[OP_NUXZ] : rs[OP_HUXZ];
        OP_NUY:  e = (rs[OP_RN] > rs[OP_NY]) ? rs[OP_RN] : rs[OP_NY];
        OP_NHY:  e = (rs[OP_NUY] > rs[OP_HUY]) ? rs[OP_NUY] : rs[OP_HUY];
        OP_NHXY: e = (rs[OP_NHXZ] > rs[OP_NHY]) ? rs[OP_NHXZ] : rs[OP_NHY];
        OP_NLY:  e = rs[OP_NUY];
        // n_x l_x, n_z l_z: u_nla, fed directly by u_dvnc, in rs[OP_NUXZ] + mul_lat (+ 1)
        OP_NLXY: e = (rs[OP_NUXZ] + m > rs[OP_NLY]) ? rs[OP_NUXZ] + m : rs[OP_NLY];
        // dot(n, l) in a, dot(n, h) in a + 1 (one max register for both)
        OP_DOTS: begin
          e = (rs[OP_NLXY] > rs[OP_NUXZ] + m + 1) ? rs[OP_NLXY] : rs[OP_NUXZ] + m + 1;
          if (rs[OP_NHXY] > e + 1) e = rs[OP_NHXY] - 1;
          if (rs[OP_NHXZ] > e)     e = rs[OP_NHXZ];
        end
        OP_KDN:  e = rs[OP_DOTS] + 1;                                 // ndl: the max register
        OP_A:    e = rs[OP_KDN];
        OP_CYA, OP_CAXZ: e = rs[OP_A];
        // s = ndh^2 (ndh in the max register a stage after ndl), s^4, s^8, s^16; sp = KS s^16
        OP_S2:   e = rs[OP_DOTS] + 2;
        OP_S4:   e = rs[OP_S2];
        OP_S8:   e = rs[OP_S4];
        OP_S16:  e = rs[OP_S8];
        OP_SP:   e = rs[OP_S16];
        OP_CG:   e = (rs[OP_CYA] > rs[OP_SP]) ? rs[OP_CYA] : rs[OP_SP];
        default: e = (rs[OP_CAXZ] > rs[OP_SP]) ? rs[OP_CAXZ] : rs[OP_SP];  // OP_CRB
      endcase
      u = shade_op_unit(i);
      a = e + 1;
      // (at most 8 tries: a unit left without the two consecutive phases a stream needs shows in
      // shade_unit's elaboration check)
      while ((used[4 * u + a % 4] || (shade_op_stream(i) && used[4 * u + (a + 1) % 4]))
             && a < e + 9) a++;
      used = used | ((4*SHADE_NUNITS)'(1) << (4 * u + a % 4));
      if (shade_op_stream(i)) used = used | ((4*SHADE_NUNITS)'(1) << (4 * u + (a + 1) % 4));
      st[i] = a;
      rs[i] = a + shade_op_lat(i, add_lat, mul_lat);
    end
    return st[op];
  endfunction
  /* verilator lint_on UNUSEDSIGNAL */

  // The core stage the clamp takes c_R in (c_G follows a stage later, c_B two).
  function automatic int unsigned shade_clamp_stage(input int unsigned add_lat,
                                                    input int unsigned mul_lat);
    int unsigned r, g;
    r = shade_op_stage(OP_CRB, add_lat, mul_lat) + add_lat;
    g = shade_op_stage(OP_CG, add_lat, mul_lat) + add_lat;
    return (r + 1 > g) ? r : g - 1;
  endfunction

  // The latency: the clamp (1), c 255 (mul), + 0.5 and floor (f24_round_index, in the clocks of
  // an add and F24_TO_INDEX_LAT), G and B a stage after R each (2) complete the result in core
  // stage CS; 3 more for the alignment (a pixel enters the core on phase 0 mod 4, up to 3 clocks
  // late; the others wait at the output).
  function automatic int unsigned shade_lat(input int unsigned add_lat, input int unsigned mul_lat);
    return shade_clamp_stage(add_lat, mul_lat) + 1 + mul_lat + add_lat
           + pipe_pkg::F24_TO_INDEX_LAT + 2 + 3;
  endfunction

  // At the package defaults (pipe_pkg::F24_ADD_LAT, F24_MUL_LAT); 67 at (2, 1), 90 at (3, 2).
  // rsqrt: f24_rsqrt #(.LAT(3)) (pipe_pkg::F24_RSQRT_LAT).
  localparam int unsigned SHADE_LAT = shade_lat(pipe_pkg::F24_ADD_LAT, pipe_pkg::F24_MUL_LAT);

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
  localparam f24_t SHADE_HALF = 24'h3e0000;  // 0.5 (added inside f24_round_index)

  /* verilator lint_on UNUSEDPARAM */

endpackage
