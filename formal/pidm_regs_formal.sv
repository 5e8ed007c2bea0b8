// SPDX-License-Identifier: Apache-2.0
// pidm_regs_formal: the generated register block pidm_regs (rtl/top/pidm_regs.sv, from
// rtl/top/pidm_regs.rdl) and pidm_cfg behind it, under SymbiYosys (formal/pidm_regs.sby).
//
// The AXI4-Lite master is free within the protocol (assumed): reset in the first clock, no VALID
// during reset, every VALID held with its payload stable until READY; its addresses are free in
// the prove task, from a set (in_set) in the bmc and cover tasks.  The hardware inputs
// (hwif_in: HWCFG, STATUS, PROGRESS, STATS, PYR.INFO, the ERROR hardware sets, the interrupt events) are
// free; INTR_STATE's inputs are wired as the system top wires them: event | INTR_TEST pulse.
//
// A request takes effect when the generated block's AXI front end hands it to the register core
// (its cpuif request, `commit` below); the wrapper keeps its own copy of every accepted AW, W and
// AR (the block holds at most one of each) and of the responses owed (at most three: the
// block's response buffer of three entries, whose pointers wrap at 3).  The block's read path
// is retimed (peakrdl-regblock --rt-read-fanin): the register core samples the read value in
// the commit clock and answers (cpuif_rd_ack) one clock later; a write is never committed in
// the clock after a read (the generated front end stalls it one clock, so that the write's
// answer, given in its commit clock, does not meet the read's).  The wrapper proves:
//   protocol  every AW+W pair and every AR is committed once, with its address and data, as a
//             whole-word write whatever its strobes (the block ignores WSTRB, scripts/flow/regs.py)
//             (wr_commit_*, rd_commit_*), in the clock it is ready unless three
//             responses are owed or, for a write, the clock before committed a read
//             (commit_when_room); a waiting write commits within three clocks with room, a
//             waiting read within three (wr_no_starve, rd_no_starve); a read is answered the
//             clock after its commit, never in the clock of a write's answer (rd_ack_next,
//             ack_one); a response is shown exactly when one is owed and answered, B only for
//             a write, R only for a read (resp_shown, b_for_write, r_for_read); B / R held
//             with stable payload until READY (b_stable, r_stable); every response OKAY (bresp_okay, rresp_okay: the block has no error
//             response; writes to read-only or unmapped addresses are ignored, answered OKAY).
//   writes    a reference copy ("shadow") of a representative set of registers (tracked below:
//             full-width and multi-field RW registers with reserved bits, f24 words, elements of
//             the write-only external tables HEIGHT.LEVEL_OFF and TEX[1].LEVEL_SIZE, TT_WRITE,
//             INTR_ENABLE, the W1C registers ERROR and INTR_STATE, the singlepulse registers CTRL
//             and INTR_TEST) updated from the committed AXI writes by the RDL rules, every write
//             a whole-word write (the strobes ignored): RW and write-only take the data on the
//             defined bits; W1C clears the written 1s and sets the hardware-set bits, a set
//             winning over a clear in the same clock (the RDL's precedence = hw: no event is
//             lost); singlepulse holds a
//             written bit one clock, then 0.  Every clock each tracked register's field values
//             (hwif_out, or the block's storage where the field has no hardware output) equal
//             their shadow (field_match): writes to the other addresses leave them alone.
//             HEIGHT.LEVEL_OFF[0], HEIGHT.LEVEL_OFF[15] and TEX[1].LEVEL_SIZE[15] are external
//             registers (HEIGHT.LEVEL_OFF, TEX[x].LEVEL_OFF / LEVEL_SIZE are not stored in the
//             block: pidm_cfg passes each write on as a write of dm_pipeline's level tables,
//             lvt_*): the "field" of each is the wrapper's model of its table entry {kind, x, k}
//             ({1, 0, 0}, {1, 0, 15}, {3, 1, 15}) that pidm_cfg's lvt_* writes build
//             (lvt_entry_q), checked against the shadow of the clock before (shadow_q): the
//             table write comes the clock after the commit, the model holds it a clock later.
//             (Compared in the clock of the table write instead, the induction took about twice
//             as long.)
//   level     the 80 external registers HEIGHT.LEVEL_OFF[k], TEX[x].LEVEL_OFF[k] /
//   tables    LEVEL_SIZE[k]: a request strobe (hwif_out .req) exactly in the clock a write to
//             one is committed, never two at once (lvt_req_one, lvt_req_commit); no external
//             access outstanding (ext_idle: they are acknowledged at once); lvt_we_o exactly the
//             clock after such a commit (lvt_we_next) with lvt_waddr_o = {kind, x, k} of the
//             address written (kind 1 HEIGHT.LEVEL_OFF, 2 TEX[x].LEVEL_OFF, 3 TEX[x].LEVEL_SIZE)
//             and lvt_wdata_o the word written (lvt_fields; the lemma lvt_addr_enc: pidm_cfg's
//             encoded address in the commit clock); every write answered by the core in its
//             commit clock, a level-table write by pidm_cfg's acknowledge (wr_ack_commit: also
//             a lemma that keeps the induction short).
//   reads     a read of a tracked readable register returns its shadow (reserved bits 0), of
//             any word of the write-only tables (HEIGHT / TEX[x] / PYR LEVEL_OFF, TEX[x].
//             LEVEL_SIZE) 0, of ID / VERSION
//             / HWCFG / STATUS / PROGRESS / a STATS word its value, of an unmapped word 0, all
//             as they were in the commit clock (the expected value is captured then; rd_value
//             checks it when the block answers, one clock later; rdata_match when R carries
//             it).
//   others    TT_WRITE's swmod strobe exactly in the clock of a write to it (tt_swmod); the interrupt line is OR(INTR_STATE & INTR_ENABLE) (intr_line); an
//             INTR_TEST pulse sets INTR_STATE unless software writes INTR_STATE in that clock
//             (test_sets_state).  Lemmas for the induction tie the wrapper's copies to the
//             block's AXI front end (front_*).
// pidm_cfg's own properties (rtl/top/pidm_cfg_assert.sv, bound) are proven with the block
// driving it.
module pidm_regs_formal (
  input  logic              clk_i,
  input  logic              rst_ni,
  // AXI4-Lite master (free, constrained by the assumptions below)
  input  logic              awvalid_i,
  input  logic [11:0]       awaddr_i,
  input  logic [2:0]        awprot_i,
  input  logic              wvalid_i,
  input  logic [31:0]       wdata_i,
  input  logic [3:0]        wstrb_i,
  input  logic              bready_i,
  input  logic              arvalid_i,
  input  logic [11:0]       araddr_i,
  input  logic [2:0]        arprot_i,
  input  logic              rready_i,
  // hardware inputs of the block (free)
  input  logic [31:0]       hwcfg_i,
  input  logic              busy_i,
  input  logic              idle_i,
  input  logic [8:0]        error_set_i,
  input  logic [31:0]       progress_i,
  input  logic [2:0]        intr_event_i,
  input  logic              pyr_busy_i,     // STATUS.pyr_busy, pyr_done, pyr_err_code
  input  logic              pyr_done_i,
  input  logic [3:0]        pyr_err_i,
  input  logic              pyr_present_i,  // PYR.INFO.present, max_lg
  input  logic [3:0]        pyr_max_lg_i,
  input  logic [10:0][47:0] stats_i
);

  // ---------------------------------------------------------------------------------------
  // The block and pidm_cfg
  // ---------------------------------------------------------------------------------------
  logic        awready, wready, arready, bvalid, rvalid;
  logic [1:0]  bresp, rresp;
  logic [31:0] rdata;
  pidm_regs_pkg::pidm_regs__in_t  hwif_in;
  pidm_regs_pkg::pidm_regs__out_t hwif_out;
  pidm_regs_pkg::pidm_regs__HEIGHT__in_t hwif_in_height;  // from pidm_cfg, as in pidm_top
  pidm_regs_pkg::pidm_regs__TEXx__in_t hwif_in_tex [2];

  pidm_regs u_dut (
    .clk(clk_i), .rst_n(rst_ni),
    .s_axil_awready(awready), .s_axil_awvalid(awvalid_i), .s_axil_awaddr(awaddr_i),
    .s_axil_awprot(awprot_i), .s_axil_wready(wready), .s_axil_wvalid(wvalid_i),
    .s_axil_wdata(wdata_i), .s_axil_wstrb(wstrb_i), .s_axil_bready(bready_i),
    .s_axil_bvalid(bvalid), .s_axil_bresp(bresp), .s_axil_arready(arready),
    .s_axil_arvalid(arvalid_i), .s_axil_araddr(araddr_i), .s_axil_arprot(arprot_i),
    .s_axil_rready(rready_i), .s_axil_rvalid(rvalid), .s_axil_rdata(rdata),
    .s_axil_rresp(rresp), .hwif_in, .hwif_out);

  always_comb begin
    hwif_in.HWCFG.pix_w.next      = hwcfg_i[7:0];
    hwif_in.HWCFG.tris.next       = hwcfg_i[15:8];
    hwif_in.HWCFG.addr_w.next     = hwcfg_i[23:16];
    hwif_in.HWCFG.data_bytes.next = hwcfg_i[31:24];
    hwif_in.STATUS.busy.next      = busy_i;
    hwif_in.STATUS.idle.next      = idle_i;
    hwif_in.ERROR.h_axi.hwset      = error_set_i[0];
    hwif_in.ERROR.t_axi.hwset      = error_set_i[1];
    hwif_in.ERROR.frag_dma.hwset   = error_set_i[2];
    hwif_in.ERROR.fb_write.hwset   = error_set_i[3];
    hwif_in.ERROR.bad_config.hwset = error_set_i[4];
    hwif_in.ERROR.pyr_read.hwset   = error_set_i[5];
    hwif_in.ERROR.pyr_write.hwset  = error_set_i[6];
    hwif_in.ERROR.pyr_config.hwset = error_set_i[7];
    hwif_in.ERROR.start_refused.hwset = error_set_i[8];
    hwif_in.STATUS.pyr_busy.next     = pyr_busy_i;
    hwif_in.STATUS.pyr_done.next     = pyr_done_i;
    hwif_in.STATUS.pyr_err_code.next = pyr_err_i;
    hwif_in.PYR.INFO.present.next    = pyr_present_i;
    hwif_in.PYR.INFO.max_lg.next     = pyr_max_lg_i;
    hwif_in.PROGRESS.pixels.next   = progress_i;
    hwif_in.INTR_STATE.frame_done.next = intr_event_i[0] | hwif_out.INTR_TEST.frame_done.value;
    hwif_in.INTR_STATE.axi_error.next  = intr_event_i[1] | hwif_out.INTR_TEST.axi_error.value;
    hwif_in.INTR_STATE.pyr_done.next   = intr_event_i[2] | hwif_out.INTR_TEST.pyr_done.value;
    hwif_in.STATS.cycles.LO.val.next        = stats_i[0][31:0];
    hwif_in.STATS.cycles.HI.val.next        = stats_i[0][47:32];
    hwif_in.STATS.pixels.LO.val.next        = stats_i[1][31:0];
    hwif_in.STATS.pixels.HI.val.next        = stats_i[1][47:32];
    hwif_in.STATS.iters.LO.val.next         = stats_i[2][31:0];
    hwif_in.STATS.iters.HI.val.next         = stats_i[2][47:32];
    hwif_in.STATS.h_hits.LO.val.next        = stats_i[3][31:0];
    hwif_in.STATS.h_hits.HI.val.next        = stats_i[3][47:32];
    hwif_in.STATS.h_misses.LO.val.next      = stats_i[4][31:0];
    hwif_in.STATS.h_misses.HI.val.next      = stats_i[4][47:32];
    hwif_in.STATS.h_bytes.LO.val.next       = stats_i[5][31:0];
    hwif_in.STATS.h_bytes.HI.val.next       = stats_i[5][47:32];
    hwif_in.STATS.t_requests.LO.val.next    = stats_i[6][31:0];
    hwif_in.STATS.t_requests.HI.val.next    = stats_i[6][47:32];
    hwif_in.STATS.t_quad_hits.LO.val.next   = stats_i[7][31:0];
    hwif_in.STATS.t_quad_hits.HI.val.next   = stats_i[7][47:32];
    hwif_in.STATS.t_line_misses.LO.val.next = stats_i[8][31:0];
    hwif_in.STATS.t_line_misses.HI.val.next = stats_i[8][47:32];
    hwif_in.STATS.t_texel_hits.LO.val.next  = stats_i[9][31:0];
    hwif_in.STATS.t_texel_hits.HI.val.next  = stats_i[9][47:32];
    hwif_in.STATS.t_bytes.LO.val.next       = stats_i[10][31:0];
    hwif_in.STATS.t_bytes.HI.val.next       = stats_i[10][47:32];
    hwif_in.HEIGHT = hwif_in_height;
    for (int x = 0; x < 2; x++) hwif_in.TEX[x] = hwif_in_tex[x];
  end

  // pidm_cfg as the system top wires it (its triangle-table outputs are checked by its bound
  // properties, its level-table outputs below)
  logic                              lvt_we;
  logic [pipe_pkg::LVT_ADDR_W-1:0]   lvt_waddr;
  logic [31:0]                       lvt_wdata;
  /* verilator lint_off PINCONNECTEMPTY */
  pidm_cfg #(.TRIS(16)) u_cfg (
    .clk_i, .rst_ni, .hwif_i(hwif_out), .cfg_method_o(), .cfg_width_o(), .cfg_height_o(),
    .cfg_root_level_o(), .cfg_bits16_o(), .cfg_base_o(), .cfg_root_code_o(),
    .cfg_iter_cap_o(), .cfg_depth_o(), .cfg_mip_en_o(), .cfg_levels_colour_o(),
    .cfg_levels_normal_o(), .cfg_shade_o(), .cfg_miss_rgb_o(), .cfg_tex_su_o(), .cfg_tex_sv_o(),
    .cfg_tex_base_o(), .tt_we_o(), .tt_waddr_o(), .tt_wdata_o(), .lvt_we_o(lvt_we),
    .lvt_waddr_o(lvt_waddr), .lvt_wdata_o(lvt_wdata), .hwif_height_o(hwif_in_height),
    .hwif_tex_o(hwif_in_tex));
  /* verilator lint_on PINCONNECTEMPTY */

  // ---------------------------------------------------------------------------------------
  // The master: AXI4-Lite rules (assumed)
  // ---------------------------------------------------------------------------------------
  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  logic        rst_q;        // rst_ni one clock earlier
  logic        aw_wait_q, w_wait_q, ar_wait_q;
  logic [11:0] awaddr_q, araddr_q;
  logic [31:0] wdata_q;
  logic [3:0]  wstrb_q;
  always_ff @(posedge clk_i) begin
    rst_q     <= rst_ni;
    aw_wait_q <= rst_ni && awvalid_i && !awready;
    w_wait_q  <= rst_ni && wvalid_i && !wready;
    ar_wait_q <= rst_ni && arvalid_i && !arready;
    awaddr_q  <= awaddr_i;
    wdata_q   <= wdata_i;
    wstrb_q   <= wstrb_i;
    araddr_q  <= araddr_i;
  end

  // In the bmc and cover tasks (PIDM_REGS_ADDR_SET) the master's addresses (any low two bits)
  // come from a set: the tracked registers, the read-only registers whose values are checked,
  // an untracked RW register and a sample of unmapped words around and between the register
  // groups.  (With all 4 KiB free the solver takes minutes per BMC step beyond the third: the
  // block's read multiplexer over every register.)  The prove task (k-induction) has every
  // address free.
  function automatic logic in_set(logic [11:0] a);
    case ({a[11:2], 2'b00})
      12'h040, 12'h060, 12'h200, 12'h204, 12'h240, 12'h27C, 12'h300, 12'h304, 12'h33C, 12'h400,
      12'h508, 12'h5BC, 12'h100, 12'h024, 12'h018, 12'h020, 12'h010, 12'h028,
      12'h608, 12'h604,                                                           // tracked
      12'h000, 12'h004, 12'h008, 12'h014, 12'h01C, 12'h080, 12'h0D4, 12'h600,     // read-only
      12'h208, 12'h440, 12'h67C,                                 // untracked (write-only: 0)
      12'h00C, 12'h02C, 12'h064, 12'h0D8, 12'h104, 12'h214, 12'h308, 12'h340,
      12'h4C0, 12'h60C, 12'h680, 12'hFFC:                                         // unmapped
        return 1'b1;
      default: return 1'b0;
    endcase
  endfunction

  always_comb begin
`ifdef PIDM_REGS_ADDR_SET
    assume (in_set(awaddr_i) && in_set(araddr_i));
`endif
    if (!rst_ni) assume (!awvalid_i && !wvalid_i && !arvalid_i);
    if (rst_ni && aw_wait_q) assume (awvalid_i && awaddr_i == awaddr_q);
    if (rst_ni && w_wait_q)  assume (wvalid_i && wdata_i == wdata_q && wstrb_i == wstrb_q);
    if (rst_ni && ar_wait_q) assume (arvalid_i && araddr_i == araddr_q);
  end

  // ---------------------------------------------------------------------------------------
  // The wrapper's copies: accepted requests not yet committed, responses owed
  // ---------------------------------------------------------------------------------------
  logic aw_hs, w_hs, ar_hs, b_hs, r_hs;
  assign aw_hs = rst_ni && awvalid_i && awready;
  assign w_hs  = rst_ni && wvalid_i && wready;
  assign ar_hs = rst_ni && arvalid_i && arready;
  assign b_hs  = rst_ni && bvalid && bready_i;
  assign r_hs  = rst_ni && rvalid && rready_i;

  // The commit: the block's AXI front end hands a request to its register core.
  logic wr_commit, rd_commit;
  assign wr_commit = rst_ni && u_dut.cpuif_req_masked && u_dut.cpuif_req_is_wr;
  assign rd_commit = rst_ni && u_dut.cpuif_req_masked && !u_dut.cpuif_req_is_wr;

  logic        aw_p, w_p, ar_p;           // an accepted AW / W / AR not yet committed
  logic [11:0] aw_addr, ar_addr;
  logic [31:0] w_data;
  logic [3:0]  w_strb;
  logic [31:0] w_biten;                   // the bits a write writes: all (WSTRB is ignored)
  assign w_biten = '1;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      aw_p <= 1'b0;
      w_p  <= 1'b0;
      ar_p <= 1'b0;
    end else begin
      if (wr_commit) begin
        aw_p <= 1'b0;
        w_p  <= 1'b0;
      end
      if (rd_commit) ar_p <= 1'b0;
      if (aw_hs) begin
        aw_p    <= 1'b1;
        aw_addr <= awaddr_i;
      end
      if (w_hs) begin
        w_p    <= 1'b1;
        w_data <= wdata_i;
        w_strb <= wstrb_i;
      end
      if (ar_hs) begin
        ar_p    <= 1'b1;
        ar_addr <= araddr_i;
      end
    end
  end

  // Responses owed, oldest first: a write's B or a read's R with the data it must carry.  Three
  // entries, indexed as the block's response buffer: 0, 1, 2, then 0 again.
  function automatic logic [1:0] idx3(logic [1:0] b, logic [2:0] k);   // (b + k) mod 3
    logic [3:0] t;
    t = 4'(b) + 4'(k);
    if (t >= 4'd6) t = t - 4'd6;
    else if (t >= 4'd3) t = t - 4'd3;
    return t[1:0];
  endfunction

  logic [2:0]  rq_cnt;                    // responses owed (committed, not yet taken by B / R)
  logic [1:0]  rq_rp;                     // the oldest entry
  logic [1:0]  rq_wp;                     // the next free entry
  logic [1:0]  rq_new;                    // the newest entry
  logic        rq_wr  [3];
  logic        rq_chk [3];                // a read whose data is known (exp)
  logic [31:0] rq_exp [3];
  logic        rq_push, rq_pop;
  logic        rq_push_chk;
  logic [31:0] rq_push_exp;
  logic        rq_head_wr;
  logic        rd_commit_q;               // a read committed in the clock before: not answered yet
  logic [2:0]  rq_ans;                    // responses owed and answered (in the block's buffer)
  assign rq_push    = wr_commit || rd_commit;
  assign rq_pop     = b_hs || r_hs;
  assign rq_wp      = idx3(rq_rp, rq_cnt);
  assign rq_new     = idx3(rq_rp, rq_cnt + 3'd2);   // rq_cnt - 1 (mod 3)
  assign rq_head_wr = rq_wr[rq_rp];
  assign rq_ans     = rq_cnt - 3'(rd_commit_q);

  always_ff @(posedge clk_i) begin
    rd_commit_q <= rd_commit;
    if (!rst_ni) begin
      rq_cnt <= '0;
      rq_rp  <= '0;
    end else begin
      if (rq_push) begin
        rq_wr[rq_wp]  <= wr_commit;
        rq_chk[rq_wp] <= rd_commit && rq_push_chk;
        rq_exp[rq_wp] <= rq_push_exp;
      end
      rq_cnt <= rq_cnt + 3'(rq_push) - 3'(rq_pop);
      if (rq_pop) rq_rp <= idx3(rq_rp, 3'd1);
    end
  end

  // ---------------------------------------------------------------------------------------
  // The tracked registers: address, defined bits, reset value, kind; their field values
  // ---------------------------------------------------------------------------------------
  localparam int unsigned NT = 20;
  localparam int unsigned K_RW = 0, K_W1C = 1, K_PULSE = 2;

  // T_* index constants used below
  localparam int unsigned T_TT = 12, T_ENABLE = 13, T_ERROR = 14, T_STATE = 15, T_CTRL = 16,
                          T_TEST = 17;

  function automatic logic [11:0] t_addr(int unsigned i);
    case (i)
      0:  return 12'h040;   // FRAME.FRAG_BASE.LO    RW 32 bits
      1:  return 12'h060;   // FRAME.FB_LAYOUT       RW xbits[4:0], status_en[8]
      2:  return 12'h200;   // HEIGHT.MODE           RW method[3:0] (reset 7), root_level, bits16
      3:  return 12'h204;   // HEIGHT.SIZE           RW width[15:0], height[31:16]
      4:  return 12'h240;   // HEIGHT.LEVEL_OFF[0]   W 32 bits (write-only: reads 0; external:
                            //   the level table entry {1, 0, 0} pidm_cfg writes)
      5:  return 12'h27C;   // HEIGHT.LEVEL_OFF[15]  (external: entry {1, 0, 15})
      6:  return 12'h300;   // SHADE.MIP             RW mip_en[0], levels_colour[13:8], levels_normal[21:16]
      7:  return 12'h304;   // SHADE.MISS_RGB        RW red, green, blue [23:0]
      8:  return 12'h33C;   // SHADE.D2              RW f24 [23:0]
      9:  return 12'h400;   // TEX[0].SU             RW f24
      10: return 12'h508;   // TEX[1].BASE           RW 32 bits
      11: return 12'h5BC;   // TEX[1].LEVEL_SIZE[15] W width, height (write-only, external:
                            //   the level table entry {3, 1, 15} pidm_cfg writes)
      12: return 12'h100;   // TT_WRITE              RW data[23:0], addr[31:24] (swmod)
      13: return 12'h024;   // INTR_ENABLE           RW [2:0] (no hardware output)
      14: return 12'h018;   // ERROR                 W1C [8:0], hardware set
      15: return 12'h020;   // INTR_STATE            W1C [2:0], hardware set (event | INTR_TEST)
      16: return 12'h010;   // CTRL                  singlepulse [3:0]
      17: return 12'h028;   // INTR_TEST             singlepulse [2:0]
      18: return 12'h608;   // PYR.SIZE              RW width[15:0], height[31:16]
      default: return 12'h604;  // PYR.FORMAT        RW bits16[0]
    endcase
  endfunction

  function automatic logic [31:0] t_mask(int unsigned i);
    case (i)
      1:  return 32'h0000_011F;
      2:  return 32'h0000_01FF;
      6:  return 32'h003F_3F01;
      7, 8, 9: return 32'h00FF_FFFF;
      13: return 32'h0000_0007;
      14: return 32'h0000_01FF;
      15: return 32'h0000_0007;
      16: return 32'h0000_000F;
      17: return 32'h0000_0007;
      19: return 32'h0000_0001;
      default: return 32'hFFFF_FFFF;
    endcase
  endfunction

  function automatic logic [31:0] t_reset(int unsigned i);
    return (i == 2) ? 32'h0000_0007 : 32'h0;
  endfunction

  // The external registers among them (their fields are modelled table entries, lvt_e).
  function automatic logic t_ext(int unsigned i);
    return i == 4 || i == 5 || i == 11;
  endfunction

  function automatic int unsigned t_kind(int unsigned i);
    case (i)
      14, 15:  return K_W1C;
      16, 17:  return K_PULSE;
      default: return K_RW;
    endcase
  endfunction

  // The level tables (external registers HEIGHT.LEVEL_OFF[k], TEX[x].LEVEL_OFF[k],
  // LEVEL_SIZE[k]): a write committed to one is lvt_waddr {kind, x, k} (lvt_idx).
  function automatic logic lvt_reg(logic [11:0] a);
    return (a[11:8] == 4'h2) ? a[7:6] == 2'b01
         : (a[11:8] == 4'h4 || a[11:8] == 4'h5) && (a[7:6] == 2'b01 || a[7:6] == 2'b10);
  endfunction
  function automatic logic [6:0] lvt_idx(logic [11:0] a);   // of an address lvt_reg accepts
    return (a[11:8] == 4'h2) ? {2'b01, 1'b0, a[5:2]}        // HEIGHT.LEVEL_OFF[k]
                             : {1'b1, a[7], a[8], a[5:2]};  // TEX[x].LEVEL_OFF / LEVEL_SIZE[k]
  endfunction
  // The modelled table entries, for the tracked registers 4, 5 and 11.
  localparam int unsigned NE = 3;
  function automatic logic [6:0] lvt_e(int unsigned e);
    case (e)
      0:       return 7'h20;   // {1, 0, 0}:  HEIGHT.LEVEL_OFF[0]
      1:       return 7'h2F;   // {1, 0, 15}: HEIGHT.LEVEL_OFF[15]
      default: return 7'h7F;   // {3, 1, 15}: TEX[1].LEVEL_SIZE[15]
    endcase
  endfunction

  logic [15:0]      height_req;           // the block's external request strobes
  logic [1:0][15:0] off_req, size_req;
  for (genvar k = 0; k < 16; k++) begin : g_hext
    assign height_req[k] = hwif_out.HEIGHT.LEVEL_OFF[k].req;
  end
  for (genvar x = 0; x < 2; x++) begin : g_ext
    for (genvar k = 0; k < 16; k++) begin : g_k
      assign off_req[x][k]  = hwif_out.TEX[x].LEVEL_OFF[k].req;
      assign size_req[x][k] = hwif_out.TEX[x].LEVEL_SIZE[k].req;
    end
  end
  logic [79:0] lvt_reqs;
  assign lvt_reqs = {height_req, off_req, size_req};

  logic        lvt_wr_q;                  // the clock before committed a level-table write
  logic [6:0]  lvt_idx_q;                 // its {kind, x, k}
  logic [31:0] lvt_data_q;                // its word
  logic [31:0] lvt_entry_q [NE];          // the model of the table entries lvt_e(e)
  logic [31:0] lvt_entry   [NE];          // ... with this clock's write to them
  always_ff @(posedge clk_i) begin
    lvt_wr_q   <= rst_ni && wr_commit && lvt_reg(aw_addr);
    lvt_idx_q  <= lvt_idx(aw_addr);
    lvt_data_q <= w_data;
    for (int unsigned e = 0; e < NE; e++) begin
      if (!rst_ni) lvt_entry_q[e] <= '0;
      else         lvt_entry_q[e] <= lvt_entry[e];
    end
  end
  always_comb
    for (int unsigned e = 0; e < NE; e++)
      lvt_entry[e] = (lvt_we && lvt_waddr == lvt_e(e)) ? lvt_wdata : lvt_entry_q[e];

  // Each tracked register's fields at their RDL bit positions (0 elsewhere).
  logic [31:0] view  [NT];
  logic [31:0] hwset [NT];   // bits the hardware sets (W1C registers)
  always_comb begin
    view[0]  = hwif_out.FRAME.FRAG_BASE.LO.val.value;
    view[1]  = {23'b0, hwif_out.FRAME.FB_LAYOUT.status_en.value, 3'b0,
                hwif_out.FRAME.FB_LAYOUT.xbits.value};
    view[2]  = {23'b0, hwif_out.HEIGHT.MODE.bits16.value, hwif_out.HEIGHT.MODE.root_level.value,
                hwif_out.HEIGHT.MODE.method.value};
    view[3]  = {hwif_out.HEIGHT.SIZE.height.value, hwif_out.HEIGHT.SIZE.width.value};
    view[4]  = lvt_entry_q[0];   // external: checked against the shadow a clock late
    view[5]  = lvt_entry_q[1];
    view[6]  = {10'b0, hwif_out.SHADE.MIP.levels_normal.value, 2'b0,
                hwif_out.SHADE.MIP.levels_colour.value, 7'b0, hwif_out.SHADE.MIP.mip_en.value};
    view[7]  = {8'b0, hwif_out.SHADE.MISS_RGB.blue.value, hwif_out.SHADE.MISS_RGB.green.value,
                hwif_out.SHADE.MISS_RGB.red.value};
    view[8]  = {8'b0, hwif_out.SHADE.D2.val.value};
    view[9]  = {8'b0, hwif_out.TEX[0].SU.val.value};
    view[10] = hwif_out.TEX[1].BASE.val.value;
    view[11] = lvt_entry_q[2];
    view[12] = {hwif_out.TT_WRITE.addr.value, hwif_out.TT_WRITE.data.value};
    // INTR_ENABLE and INTR_STATE have no hardware outputs but the interrupt line: their storage
    view[13] = {29'b0, u_dut.field_storage.INTR_ENABLE.pyr_done.value,
                u_dut.field_storage.INTR_ENABLE.axi_error.value,
                u_dut.field_storage.INTR_ENABLE.frame_done.value};
    view[14] = {23'b0, hwif_out.ERROR.start_refused.value, hwif_out.ERROR.pyr_config.value,
                hwif_out.ERROR.pyr_write.value, hwif_out.ERROR.pyr_read.value,
                hwif_out.ERROR.bad_config.value, hwif_out.ERROR.fb_write.value,
                hwif_out.ERROR.frag_dma.value, hwif_out.ERROR.t_axi.value,
                hwif_out.ERROR.h_axi.value};
    view[15] = {29'b0, u_dut.field_storage.INTR_STATE.pyr_done.value,
                u_dut.field_storage.INTR_STATE.axi_error.value,
                u_dut.field_storage.INTR_STATE.frame_done.value};
    view[16] = {28'b0, hwif_out.CTRL.pyr_start.value, hwif_out.CTRL.clear_stats.value,
                hwif_out.CTRL.soft_reset.value, hwif_out.CTRL.start.value};
    view[17] = {29'b0, hwif_out.INTR_TEST.pyr_done.value, hwif_out.INTR_TEST.axi_error.value,
                hwif_out.INTR_TEST.frame_done.value};
    view[18] = {hwif_out.PYR.SIZE.height.value, hwif_out.PYR.SIZE.width.value};
    view[19] = {31'b0, hwif_out.PYR.FORMAT.bits16.value};
    for (int unsigned i = 0; i < NT; i++) hwset[i] = '0;
    hwset[T_ERROR] = {23'b0, error_set_i};
    hwset[T_STATE] = {29'b0, intr_event_i | view[T_TEST][2:0]};
  end

  // The shadows: the register values the RDL prescribes for the committed writes.
  logic [31:0] shadow [NT];
  logic [NT-1:0] wr_sel;     // this clock commits a write to tracked register i
  always_comb
    for (int unsigned i = 0; i < NT; i++) wr_sel[i] = wr_commit && aw_addr[11:2] == t_addr(i)[11:2];

  always_ff @(posedge clk_i) begin
    for (int unsigned i = 0; i < NT; i++) begin
      if (!rst_ni) shadow[i] <= t_reset(i);
      else case (t_kind(i))
        K_RW:    if (wr_sel[i]) shadow[i] <= ((shadow[i] & ~w_biten) | (w_data & w_biten)) & t_mask(i);
        K_W1C:   shadow[i] <= wr_sel[i] ? ((shadow[i] & ~(w_data & w_biten)) | hwset[i]) & t_mask(i)
                                        : (shadow[i] | hwset[i]) & t_mask(i);
        default: shadow[i] <= wr_sel[i] ? ((shadow[i] & ~w_biten) | (w_data & w_biten)) & t_mask(i)
                                        : '0;
      endcase
    end
  end

  // The shadows of the clock before (for the external registers: pidm_cfg writes the table the
  // clock after the commit, lvt_entry_q holds the word one clock later still).
  logic [31:0] shadow_q [NT];
  always_ff @(posedge clk_i)
    for (int unsigned i = 0; i < NT; i++) shadow_q[i] <= rst_ni ? shadow[i] : t_reset(i);

  // What a read of the committed address returns (rq_push_chk: known for this address).
  function automatic logic mapped(logic [11:0] a);
    logic [11:0] t;
    t = {a[11:2], 2'b00};
    if (t <= 12'h008 || (t >= 12'h010 && t <= 12'h028)) return 1'b1;
    if (t >= 12'h040 && t <= 12'h060) return 1'b1;
    if (t >= 12'h080 && t <= 12'h0D4) return 1'b1;
    if (t == 12'h100) return 1'b1;
    if ((t >= 12'h200 && t <= 12'h210) || (t >= 12'h240 && t <= 12'h27C)) return 1'b1;
    if (t == 12'h300 || t == 12'h304 || (t >= 12'h320 && t <= 12'h33C)) return 1'b1;
    if (t >= 12'h400 && t < 12'h600 && (t[7:0] <= 8'h08 || (t[7:0] >= 8'h40 && t[7:0] <= 8'hBC)))
      return 1'b1;
    if ((t >= 12'h600 && t <= 12'h608) || (t >= 12'h610 && t <= 12'h624)
        || (t >= 12'h640 && t <= 12'h67C)) return 1'b1;
    return 1'b0;
  endfunction

  // The write-only tables: HEIGHT.LEVEL_OFF, TEX[x].LEVEL_OFF and LEVEL_SIZE, PYR.LEVEL_OFF.
  function automatic logic write_only(logic [11:0] a);
    return (a[11:8] == 4'h2 || a[11:8] == 4'h6) ? a[7:6] == 2'b01
         : (a[11:8] == 4'h4 || a[11:8] == 4'h5) && (a[7:6] == 2'b01 || a[7:6] == 2'b10);
  endfunction

  always_comb begin
    rq_push_chk = 1'b1;
    rq_push_exp = '0;                                        // unmapped, write-only: 0
    case ({ar_addr[11:2], 2'b00})
      12'h000: rq_push_exp = 32'h5049_444D;                  // ID
      12'h004: rq_push_exp = 32'h0001_0002;                  // VERSION 1.2
      12'h008: rq_push_exp = hwcfg_i;                        // HWCFG
      12'h014: rq_push_exp = {24'b0, pyr_err_i, pyr_done_i, pyr_busy_i, idle_i, busy_i}; // STATUS
      12'h600: rq_push_exp = {24'b0, pyr_max_lg_i, 3'b0, pyr_present_i};  // PYR.INFO
      12'h01C: rq_push_exp = progress_i;                     // PROGRESS
      12'h080: rq_push_exp = stats_i[0][31:0];               // STATS.cycles.LO
      12'h0D4: rq_push_exp = {16'b0, stats_i[10][47:32]};    // STATS.t_bytes.HI
      default: begin
        rq_push_chk = !mapped(ar_addr) || write_only(ar_addr);
        for (int unsigned i = 0; i < NT; i++)
          if (ar_addr[11:2] == t_addr(i)[11:2] && !write_only(ar_addr)) begin
            rq_push_chk = 1'b1;
            rq_push_exp = shadow[i];
          end
      end
    endcase
  end

  // INTR_TEST pulses that must show in INTR_STATE the clock after (no INTR_STATE write then).
  logic [2:0] test_q;
  always_ff @(posedge clk_i)
    test_q <= (rst_ni && !wr_sel[T_STATE]) ? view[T_TEST][2:0] : 3'b000;

  // Waiting requests (for the no-starvation properties).
  logic [1:0] wr_wait_q, rd_wait_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      wr_wait_q <= '0;
      rd_wait_q <= '0;
    end else begin
      wr_wait_q <= (aw_p && w_p && rq_cnt < 3'd3 && !wr_commit) ? wr_wait_q + 2'(wr_wait_q != 2'd3) : '0;
      rd_wait_q <= (ar_p && rq_cnt < 3'd3 && !rd_commit) ? rd_wait_q + 2'(rd_wait_q != 2'd3) : '0;
    end
  end

  // ---------------------------------------------------------------------------------------
  // Properties
  // ---------------------------------------------------------------------------------------
  logic        b_wait_q, r_wait_q;
  logic [1:0]  bresp_q, rresp_q;
  logic [31:0] rdata_q;
  always_ff @(posedge clk_i) begin
    b_wait_q <= rst_ni && bvalid && !bready_i;
    r_wait_q <= rst_ni && rvalid && !rready_i;
    bresp_q  <= bresp;
    rresp_q  <= rresp;
    rdata_q  <= rdata;
  end

  // Responses in the block's buffer: its pointers are {lap, index 0..2}.
  logic [2:0] dut_pending;
  assign dut_pending = (u_dut.axil_resp_wptr[2] == u_dut.axil_resp_rptr[2])
                       ? 3'(u_dut.axil_resp_wptr[1:0]) - 3'(u_dut.axil_resp_rptr[1:0])
                       : 3'd3 + 3'(u_dut.axil_resp_wptr[1:0]) - 3'(u_dut.axil_resp_rptr[1:0]);

  // The answered entries of the wrapper's queue are the block's buffer entries.
  logic entries_match;
  always_comb begin
    entries_match = 1'b1;
    for (int unsigned k = 0; k < 3; k++) begin
      logic [1:0] e;
      e = idx3(rq_rp, 3'(k));
      if (3'(k) < rq_ans
          && !(u_dut.axil_resp_buffer_is_wr[e] == rq_wr[e] && !u_dut.axil_resp_buffer_err[e]
               && (!rq_chk[e] || (!rq_wr[e] && u_dut.axil_resp_buffer_rdata[e] == rq_exp[e]))))
        entries_match = 1'b0;
    end
  end

  logic wr_commit_q, intr_q, lvt_we_q;   // for the covers
  always_ff @(posedge clk_i) begin
    wr_commit_q <= wr_commit;
    lvt_we_q    <= rst_ni && lvt_we;
    intr_q      <= rst_ni && hwif_out.INTR_STATE.intr;
  end

  // Immediate checks of this clock's values (combinational: a clocked check would report one
  // step later and need a deeper BMC).
  always_comb begin
    if (rst_ni && started_q) begin
      // --- protocol ---
      aw_one:        assert (!(aw_hs && aw_p && !wr_commit));
      w_one:         assert (!(w_hs && w_p && !wr_commit));
      ar_one:        assert (!(ar_hs && ar_p && !rd_commit));
      wr_commit_req: assert (!wr_commit || (aw_p && w_p && rq_cnt < 3'd3 && !rd_commit_q));
      wr_commit_fields: assert (!wr_commit || (u_dut.cpuif_addr == {aw_addr[11:2], 2'b00}
                                && u_dut.cpuif_wr_data == w_data && u_dut.cpuif_wr_biten == w_biten));
      rd_commit_req: assert (!rd_commit || (ar_p && rq_cnt < 3'd3));
      rd_commit_addr: assert (!rd_commit || u_dut.cpuif_addr == {ar_addr[11:2], 2'b00});
      // with room, a clock without a commit is only a complete write's stall after a read
      commit_when_room: assert (!((ar_p || (aw_p && w_p)) && rq_cnt < 3'd3)
                                || wr_commit || rd_commit || (aw_p && w_p && rd_commit_q));
      // a write passed over by a read, then stalled one clock, commits in the third clock
      wr_no_starve:  assert (wr_wait_q == 2'd0 || (wr_wait_q == 2'd1 && u_dut.axil_prev_was_rd)
                             || (wr_wait_q == 2'd2 && u_dut.axil_prev_was_rd && !rd_commit_q));
      // a read passed over by a stalled write, then by the write, commits in the third clock
      rd_no_starve:  assert (rd_wait_q == 2'd0
                             || (rd_wait_q == 2'd1 && (!u_dut.axil_prev_was_rd || (aw_p && w_p)))
                             || (rd_wait_q == 2'd2 && !u_dut.axil_prev_was_rd));
      rd_ack_next:   assert (u_dut.cpuif_rd_ack == rd_commit_q);
      ack_one:       assert (!(u_dut.cpuif_rd_ack && u_dut.cpuif_wr_ack));
      resp_bound:    assert (rq_cnt <= 3'd3);
      resp_shown:    assert ((bvalid || rvalid) == (rq_ans != 3'd0));
      b_for_write:   assert (!bvalid || (rq_ans != 3'd0 && rq_head_wr));
      r_for_read:    assert (!rvalid || (rq_ans != 3'd0 && !rq_head_wr));
      b_stable:      assert (!b_wait_q || (bvalid && bresp == bresp_q));
      r_stable:      assert (!r_wait_q || (rvalid && rdata == rdata_q && rresp == rresp_q));
      bresp_okay:    assert (!bvalid || bresp == 2'b00);
      rresp_okay:    assert (!rvalid || rresp == 2'b00);
      // the value expected at the commit, checked when the block answers (one clock later)
      rd_value:      assert (!u_dut.cpuif_rd_ack || !rq_chk[rq_new] || u_dut.cpuif_rd_data == rq_exp[rq_new]);
      rdata_match:   assert (!rvalid || !rq_chk[rq_rp] || rdata == rq_exp[rq_rp]);
      // --- the front end's state is the wrapper's copy (induction lemmas) ---
      front_aw:      assert (u_dut.axil_awvalid == aw_p && (!aw_p || u_dut.axil_awaddr == aw_addr));
      front_w:       assert (u_dut.axil_wvalid == w_p && (!w_p || u_dut.axil_wdata == w_data));
      front_ar:      assert (u_dut.axil_arvalid == ar_p && (!ar_p || u_dut.axil_araddr == ar_addr));
      front_count:   assert (3'(u_dut.axil_n_in_flight) == rq_cnt && dut_pending == rq_ans
                             && u_dut.axil_resp_rptr[1:0] == rq_rp && rq_rp != 2'd3
                             && u_dut.axil_resp_wptr[1:0] != 2'd3
                             && u_dut.readback_done_rt == rd_commit_q
                             && u_dut.cpuif_req_stall_sr[0] == rd_commit_q
                             && (!rd_commit_q || (rq_cnt != 3'd0 && !rq_wr[rq_new])));
      front_entries: assert (entries_match);
      // --- registers ---
      tt_swmod:      assert (hwif_out.TT_WRITE.data.swmod == wr_sel[T_TT]);
      // --- the level tables (external registers, pidm_cfg's lvt_* port) ---
      lvt_req_one:    assert ($onehot0(lvt_reqs));
      lvt_req_commit: assert ((|lvt_reqs) == (wr_commit && lvt_reg(aw_addr)));
      ext_idle:       assert (!u_dut.external_pending && !u_dut.readback_external_rd_ack);
      // a write is answered in its commit clock (an external one by pidm_cfg's acknowledge)
      wr_ack_commit:  assert (u_dut.cpuif_wr_ack == wr_commit
                              && u_dut.external_wr_ack == (wr_commit && lvt_reg(aw_addr)));
      // pidm_cfg's encoded address in the commit clock (a lemma for lvt_fields)
      lvt_addr_enc:   assert (!(|lvt_reqs) || u_cfg.lvt_addr == lvt_idx(aw_addr));
      lvt_we_next:    assert (lvt_we == lvt_wr_q);
      lvt_fields:     assert (!lvt_we || (lvt_waddr == lvt_idx_q && lvt_wdata == lvt_data_q));
      intr_line:     assert (hwif_out.INTR_STATE.intr
                             == |(shadow[T_STATE][2:0] & shadow[T_ENABLE][2:0]));
      test_sets_state: assert ((view[T_STATE][2:0] & test_q) == test_q);
      // --- reachability ---
      c_write:         cover (b_hs);
      c_read:          cover (r_hs && rq_chk[rq_rp] && rdata != '0);
      c_unmapped_read: cover (rd_commit && !mapped(ar_addr));
      c_back_to_back:  cover (wr_commit && wr_commit_q);
      c_partial_write: cover (wr_sel[3] && w_strb == 4'b0100);
      c_w1c_clear:     cover (wr_sel[T_ERROR] && |(shadow[T_ERROR] & w_data & w_biten)
                              && |(shadow[T_ERROR] & ~(w_data & w_biten)));
      c_pulse:         cover (hwif_out.CTRL.start.value);
      c_intr_test:     cover (|test_q);
      c_interrupt:     cover (hwif_out.INTR_STATE.intr && !intr_q);
      c_hw_wins:       cover (wr_sel[T_ERROR] && error_set_i[0] && shadow[T_ERROR][0] && w_data[0]);
      c_wo_read:       cover (rd_commit && write_only(ar_addr));
      c_lvt_write:     cover (lvt_we && lvt_waddr == 7'h7F && lvt_wdata != '0);
      c_lvt_height:    cover (lvt_we && lvt_waddr == 7'h2F && lvt_wdata != '0);
      c_lvt_back_to_back: cover (lvt_we && lvt_we_q);
    end
  end

  // Every tracked register's fields equal its shadow.
  for (genvar i = 0; i < NT; i++) begin : g_t
    always_comb begin
      if (rst_ni && started_q) begin
        field_match: assert (view[i] == (t_ext(i) ? shadow_q[i] : shadow[i]));
      end
    end
  end

endmodule
