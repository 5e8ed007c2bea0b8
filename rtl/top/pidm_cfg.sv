// SPDX-License-Identifier: Apache-2.0
// pidm_cfg: the configuration registers of the register block pidm_regs (rtl/top/pidm_regs.rdl,
// generated rtl/top/pidm_regs.sv) as dm_pipeline's cfg_* ports, triangle-table write port and
// level table write port.
// Wiring, plus two table writes:
// - TT_WRITE's swmod strobe comes in the clock of the bus write, its stored value the clock
//   after, so tt_we_o is the strobe delayed one clock and tt_waddr_o / tt_wdata_o are the stored
//   fields (scripts/pack_frame.py writes one TT_WRITE per table word; tb/harness/pidm_frame.py
//   ports_from_writes is the same map in Python).
// - HEIGHT.LEVEL_OFF[k], TEX[x].LEVEL_OFF[k] and TEX[x].LEVEL_SIZE[k] are external registers of
//   the block (no storage there: dm_pipeline keeps them in its LUT-RAM level tables, the height
//   offsets in each traverse ring's traverse_addr, the texture entries in tex_addr).  A bus write
//   to one of the 80 is its request strobe hwif_i.HEIGHT.LEVEL_OFF[k].req /
//   hwif_i.TEX[x].LEVEL_OFF[k].req / .LEVEL_SIZE[k].req for one clock (the block hands the
//   register core one request per clock and keeps at most one external access outstanding, so
//   at most one of the 80 strobes is 1), acknowledged in the same clock (hwif_height_o.
//   LEVEL_OFF[k].wr_ack, hwif_tex_o[x].*[k].wr_ack = its req: the block answers the write at
//   once, as any other).  The block forwards no read of them (they are sw = w): a read is
//   answered inside it with 0.  lvt_we_o / lvt_waddr_o / lvt_wdata_o are that write registered
//   once (a clock after the bus write; the address {kind, x, k} encoded by ORs of the one-hot
//   strobes, the data the one bus word hwif_i.HEIGHT.LEVEL_OFF[0].wr_data that every external
//   register's wr_data carries: no multiplexer).
//
// Field -> port (registers of docs/registers.md):
//   HEIGHT.MODE method / root_level / bits16   cfg_method_o / cfg_root_level_o / cfg_bits16_o
//   HEIGHT.SIZE width / height                  cfg_width_o / cfg_height_o
//   HEIGHT.BASE                                 cfg_base_o
//   HEIGHT.ROOT root_code / iter_cap            cfg_root_code_o / cfg_iter_cap_o
//   HEIGHT.DEPTH                                cfg_depth_o
//   SHADE.MIP mip_en / levels_colour / levels_normal   cfg_mip_en_o / cfg_levels_*_o
//   SHADE.MISS_RGB red / green / blue           cfg_miss_rgb_o[0] / [1] / [2]
//   SHADE.LIGHT_X .. D2                         cfg_shade_o (shade_cfg_t fields light_x .. d2)
//   TEX[x].SU / SV / BASE                       cfg_tex_su_o[x] / cfg_tex_sv_o[x] / cfg_tex_base_o[x]
//   HEIGHT.LEVEL_OFF[k] (write)                 lvt_we_o, lvt_waddr_o = {LVT_HEIGHT_OFF, 1'b0, k}
//                                               (kind 2'd1), lvt_wdata_o = the written word
//                                               (byte offset of pyramid level k from HEIGHT.BASE)
//   TEX[x].LEVEL_OFF[k] (write)                 lvt_we_o, lvt_waddr_o = {LVT_TEX_OFF, x, k}
//                                               (kind 2'd2), lvt_wdata_o = the written word
//                                               (byte offset)
//   TEX[x].LEVEL_SIZE[k] (write)                lvt_we_o, lvt_waddr_o = {LVT_TEX_SIZE, x, k}
//                                               (kind 2'd3), lvt_wdata_o = the written word
//                                               {height, width}
//   TT_WRITE data / addr (swmod)                tt_wdata_o / tt_waddr_o (tt_we_o)
module pidm_cfg
  import f24_pkg::*;
  import traverse_pkg::*;
  import pipe_pkg::*;
  import shade_pkg::*;
#(
  parameter int unsigned TRIS  = 16,                            // dm_pipeline's TRIS
  parameter int unsigned TRI_W = (TRIS > 1) ? $clog2(TRIS) : 1  // triangle id width
) (
  input  logic                                 clk_i,
  input  logic                                 rst_ni,
  // the register block's outputs (only the configuration registers are read here)
  /* verilator lint_off UNUSEDSIGNAL */  // control, frame, error and interrupt fields: pidm_top's;
                                         // the external registers' req_is_wr, wr_biten (all ones:
                                         // whole-word writes) and all wr_data but one (the same)
  input  pidm_regs_pkg::pidm_regs__out_t       hwif_i,
  /* verilator lint_on UNUSEDSIGNAL */
  // dm_pipeline configuration
  output logic [3:0]                           cfg_method_o,
  output logic [DIM_W-1:0]                     cfg_width_o,
  output logic [DIM_W-1:0]                     cfg_height_o,
  output logic [LVL_W-1:0]                     cfg_root_level_o,
  output logic                                 cfg_bits16_o,
  output logic [ADDR_W-1:0]                    cfg_base_o,
  output logic [CODE_W-1:0]                    cfg_root_code_o,
  output logic [ITER_W-1:0]                    cfg_iter_cap_o,
  output f24_t                                 cfg_depth_o,
  output logic                                 cfg_mip_en_o,
  output logic [MIP_LEVEL_W:0]                 cfg_levels_colour_o,
  output logic [MIP_LEVEL_W:0]                 cfg_levels_normal_o,
  output shade_cfg_t                           cfg_shade_o,
  output logic [2:0][7:0]                      cfg_miss_rgb_o,
  output f24_t [1:0]                           cfg_tex_su_o,
  output f24_t [1:0]                           cfg_tex_sv_o,
  output logic [1:0][TEX_ADDR_W-1:0]           cfg_tex_base_o,
  // triangle-table write port
  output logic                                 tt_we_o,
  output logic [TRI_W:0]                       tt_waddr_o,
  output f24_t                                 tt_wdata_o,
  // level table write port (dm_pipeline lvt_*): {kind [1:0], texture x, level k}, the word
  output logic                                 lvt_we_o,
  output logic [LVT_ADDR_W-1:0]                lvt_waddr_o,
  output logic [31:0]                          lvt_wdata_o,
  // the register block's inputs of the external registers HEIGHT.LEVEL_OFF and TEX[x].LEVEL_OFF /
  // LEVEL_SIZE (their write acknowledges); the system top drives the block's hwif_in.HEIGHT and
  // hwif_in.TEX with them
  output pidm_regs_pkg::pidm_regs__HEIGHT__in_t hwif_height_o,
  output pidm_regs_pkg::pidm_regs__TEXx__in_t  hwif_tex_o [2]
);

  if (TRI_W + 1 > 8) begin : g_check
    $error("pidm_cfg: TT_WRITE.addr holds 8 address bits (TRIS <= 128)");
  end
  if (TEX_LEVELS != 16 || MAX_LEVELS != TEX_LEVELS || LVT_ADDR_W != 3 + TEX_LVL_W
      || (1 << TEX_LVL_W) != TEX_LEVELS) begin : g_check_lvt
    $error("pidm_cfg: the RDL's HEIGHT.LEVEL_OFF[16], TEX[x].LEVEL_OFF[16] / LEVEL_SIZE[16]",
           " are the level tables");
  end

  // ---- height pyramid and traversal --------------------------------------------------------------
  assign cfg_method_o     = hwif_i.HEIGHT.MODE.method.value;
  assign cfg_root_level_o = hwif_i.HEIGHT.MODE.root_level.value;
  assign cfg_bits16_o     = hwif_i.HEIGHT.MODE.bits16.value;
  assign cfg_width_o      = hwif_i.HEIGHT.SIZE.width.value;
  assign cfg_height_o     = hwif_i.HEIGHT.SIZE.height.value;
  assign cfg_base_o       = hwif_i.HEIGHT.BASE.val.value;
  assign cfg_root_code_o  = hwif_i.HEIGHT.ROOT.root_code.value;
  assign cfg_iter_cap_o   = hwif_i.HEIGHT.ROOT.iter_cap.value;
  assign cfg_depth_o      = hwif_i.HEIGHT.DEPTH.val.value;

  // ---- MIP, miss colour, shading -------------------------------------------------------------------
  assign cfg_mip_en_o        = hwif_i.SHADE.MIP.mip_en.value;
  assign cfg_levels_colour_o = hwif_i.SHADE.MIP.levels_colour.value;
  assign cfg_levels_normal_o = hwif_i.SHADE.MIP.levels_normal.value;
  assign cfg_miss_rgb_o[0]   = hwif_i.SHADE.MISS_RGB.red.value;
  assign cfg_miss_rgb_o[1]   = hwif_i.SHADE.MISS_RGB.green.value;
  assign cfg_miss_rgb_o[2]   = hwif_i.SHADE.MISS_RGB.blue.value;
  assign cfg_shade_o.light_x = hwif_i.SHADE.LIGHT_X.val.value;
  assign cfg_shade_o.light_y = hwif_i.SHADE.LIGHT_Y.val.value;
  assign cfg_shade_o.light_z = hwif_i.SHADE.LIGHT_Z.val.value;
  assign cfg_shade_o.ambient = hwif_i.SHADE.AMBIENT.val.value;
  assign cfg_shade_o.kd      = hwif_i.SHADE.KD.val.value;
  assign cfg_shade_o.ks      = hwif_i.SHADE.KS.val.value;
  assign cfg_shade_o.d       = hwif_i.SHADE.D.val.value;
  assign cfg_shade_o.d2      = hwif_i.SHADE.D2.val.value;

  // ---- textures -------------------------------------------------------------------------------------
  for (genvar x = 0; x < 2; x++) begin : g_tex
    assign cfg_tex_su_o[x]   = hwif_i.TEX[x].SU.val.value;
    assign cfg_tex_sv_o[x]   = hwif_i.TEX[x].SV.val.value;
    assign cfg_tex_base_o[x] = hwif_i.TEX[x].BASE.val.value;
  end

  // ---- level tables: the external registers' write strobes as one table write ---------------
  logic [TEX_LEVELS-1:0]      height_req;          // a write to HEIGHT.LEVEL_OFF[k]
  logic [1:0][TEX_LEVELS-1:0] off_req, size_req;   // a write to TEX[x] LEVEL_OFF[k] / LEVEL_SIZE[k]
  for (genvar k = 0; k < TEX_LEVELS; k++) begin : g_hlt
    assign height_req[k] = hwif_i.HEIGHT.LEVEL_OFF[k].req;
    assign hwif_height_o.LEVEL_OFF[k].wr_ack = height_req[k];   // at once, as below
  end
  for (genvar x = 0; x < 2; x++) begin : g_lvt
    for (genvar k = 0; k < TEX_LEVELS; k++) begin : g_level
      assign off_req[x][k]  = hwif_i.TEX[x].LEVEL_OFF[k].req;
      assign size_req[x][k] = hwif_i.TEX[x].LEVEL_SIZE[k].req;
      // every access the block forwards (a write: reads of these registers are not forwarded)
      // is acknowledged at once
      assign hwif_tex_o[x].LEVEL_OFF[k].wr_ack  = off_req[x][k];
      assign hwif_tex_o[x].LEVEL_SIZE[k].wr_ack = size_req[x][k];
    end
  end

  // At most one strobe is 1: the address is the OR of the addresses of the strobes that are 1
  // (kind LVT_HEIGHT_OFF 2'b01, LVT_TEX_OFF 2'b10, LVT_TEX_SIZE 2'b11: kind bit 1 a texture
  // strobe, kind bit 0 a height or a size strobe; x 1 a strobe of TEX[1]).
  logic                  lvt_req;
  logic [LVT_ADDR_W-1:0] lvt_addr;
  always_comb begin
    logic [1:0][TEX_LEVELS-1:0] tex_req;
    logic [TEX_LEVELS-1:0]      lvl_req;   // a strobe of level k, any table
    logic [TEX_LVL_W-1:0]       k_or;
    tex_req = off_req | size_req;
    lvl_req = height_req | tex_req[0] | tex_req[1];
    k_or    = '0;
    for (int unsigned k = 0; k < TEX_LEVELS; k++)
      k_or |= TEX_LVL_W'(k) & {TEX_LVL_W{lvl_req[k]}};
    lvt_req  = |lvl_req;
    lvt_addr = {|tex_req, (|height_req) | (|size_req), |tex_req[1], k_or};
  end

  logic                  lvt_we_q;
  logic [LVT_ADDR_W-1:0] lvt_waddr_q;
  logic [31:0]           lvt_wdata_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) lvt_we_q <= 1'b0;
    else         lvt_we_q <= lvt_req;
  end
  always_ff @(posedge clk_i) begin   // no reset: valid with lvt_we_q
    lvt_waddr_q <= lvt_addr;
    lvt_wdata_q <= hwif_i.HEIGHT.LEVEL_OFF[0].wr_data.val;  // the bus word (every wr_data)
  end
  assign lvt_we_o    = lvt_we_q;
  assign lvt_waddr_o = lvt_waddr_q;
  assign lvt_wdata_o = lvt_wdata_q;

  // ---- triangle table: the write strobe one clock late, with the stored fields ------------------------
  logic tt_we_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) tt_we_q <= 1'b0;
    else         tt_we_q <= hwif_i.TT_WRITE.data.swmod;
  end
  assign tt_we_o    = tt_we_q;
  assign tt_waddr_o = hwif_i.TT_WRITE.addr.value[TRI_W:0];
  assign tt_wdata_o = hwif_i.TT_WRITE.data.value;

endmodule
