// SPDX-License-Identifier: Apache-2.0
// pyr_build: the max-mipmap pyramid builder.  Reads level 0 of a height map over an AXI4 read
// master and writes levels 1..n over an AXI4 write master, each texel the maximum of its 2 x 2
// children, bit for bit the pyramid and the memory layout of model/heightmap.py
// (docs/memory-layout.md, docs/pyramid.md).
//
// Layout (the model's): a W x H map, W, H in 1 .. 2^MAX_LG, is padded with height 0 to the square
// N = 2^n >= max(W, H); level k is (N >> k) x (N >> k) codes, row-major with a pitch of N >> k
// codes (1 byte each for unorm8, 2 little-endian for unorm16).  Level 0 is read at cfg_src_base_i
// (pitch N; only its W x H texels are read, the padding is taken as zero whatever the memory
// holds); level k >= 1 is written at cfg_pyr_base_i + cfg_level_off_i[k] (Pyramid.level_offsets(),
// every offset and both bases multiples of AXI_DATA_W / 8), padding included: the whole of
// every level 1..n.  A 1 x 1 map has no level to write (n = 0).
//
// Full rebuild (the dirty rectangle is the whole map, x0 = y0 = 0, x1 = W - 1, y1 = H - 1): one
// pass.  Level 0 is read once, row by row (bursts of up to BURST beats), into a chain of n
// pyr_stage units: stage j turns the words of level j into those of level j + 1, keeping one row
// of half maxima in its line buffer (block RAM), and feeds stage j + 1 and its slot of the writer;
// the writer writes each level's rows as they complete, and the zero padding around them.
// Clocks: about max(bytes read, bytes written) / (AXI_DATA_W / 8), plus the latency of the chain
// (model/pyramid_bus.py gives the bound; docs/pyramid.md the measured figures).
// Dirty rebuild (any other rectangle x0..x1, y0..y1 of level 0, bounds inclusive): only the
// ancestors of the rectangle, level by level: pass s (s = 0 .. n - 1) reads the rectangle's
// footprint at level s (its parents' children, widened to whole bus-word pairs and clipped to the
// map) from memory, level s + 1 of the pyramid being already up to date outside it, and writes
// the parents' rows (whole bus words) at level s + 1; pass s + 1 starts when every write of pass s
// has its B response.  The words written outside the rectangle's ancestors get the values they
// already hold, so the result equals a full rebuild provided the pyramid in memory was the
// pyramid of level 0 outside the rectangle.
//
// Control: start_i (one clock, in idle) samples every cfg_* and dirty_* input; busy_o is 1 from
// the next clock until done_o (one clock).  err_o and err_code_o are valid from done_o until the
// next start_i: err_code_o[0] an AXI read error (an rresp other than OKAY), [1] an AXI write error
// (a bresp other than OKAY), [2] a configuration error (a size outside 1 .. 2^MAX_LG, a rectangle
// outside the map or empty, a base or offset not a multiple of AXI_DATA_W / 8: nothing is read or
// written), [3] 0.  An AXI error does not stop the build: it runs to its end (the data of an
// errored beat is used as it came), so it never hangs and the next build starts clean.
// Reset (rst_ni low, synchronous) stops a build at any point; the AXI slave must be reset with it
// (bursts under way are abandoned), as AXI requires.
module pyr_build #(
  parameter int unsigned ADDR_W     = 32,   // AXI address width
  parameter int unsigned AXI_DATA_W = 64,   // AXI data width (a power of two, 32 .. 512)
  parameter int unsigned ID_W       = 1,    // AXI ID width (IDs are 0)
  parameter int unsigned MAX_LG     = 10,   // largest map side 2^MAX_LG (1024)
  parameter int unsigned BURST      = 16,   // beats per burst at most (power of two, 2 .. 256)
  parameter int unsigned MAX_RD     = 4,    // read bursts outstanding at most
  parameter logic [3:0]  AXI_CACHE  = 4'b0011,  // arcache / awcache (normal, non-cacheable, bufferable)
  parameter logic [2:0]  AXI_PROT   = 3'b000,   // arprot / awprot (unprivileged, secure, data)
  // derived (not to be overridden)
  parameter int unsigned SZ_W       = MAX_LG + 1,  // width of a size (1 .. 2^MAX_LG)
  parameter int unsigned XY_W       = MAX_LG       // width of a coordinate
) (
  input  logic                           clk_i,
  input  logic                           rst_ni,
  // configuration (sampled at start_i)
  input  logic [ADDR_W-1:0]              cfg_src_base_i,   // level 0 (pitch N codes)
  input  logic [ADDR_W-1:0]              cfg_pyr_base_i,   // levels 1..n at + cfg_level_off_i[k]
  input  logic [MAX_LG:0][ADDR_W-1:0]    cfg_level_off_i,  // Pyramid.level_offsets() (entry 0 unused)
  input  logic [SZ_W-1:0]                cfg_width_i,      // W
  input  logic [SZ_W-1:0]                cfg_height_i,     // H
  input  logic                           cfg_bits16_i,     // 1: unorm16, 0: unorm8
  input  logic [XY_W-1:0]                dirty_x0_i,       // changed rectangle of level 0,
  input  logic [XY_W-1:0]                dirty_y0_i,       // bounds inclusive (the whole map:
  input  logic [XY_W-1:0]                dirty_x1_i,       // a full rebuild)
  input  logic [XY_W-1:0]                dirty_y1_i,
  // control and status
  input  logic                           start_i,
  output logic                           busy_o,
  output logic                           done_o,
  output logic                           err_o,
  output logic [3:0]                     err_code_o,
  // AXI4 read master
  output logic [ID_W-1:0]                m_axi_arid,
  output logic [ADDR_W-1:0]              m_axi_araddr,
  output logic [7:0]                     m_axi_arlen,
  output logic [2:0]                     m_axi_arsize,
  output logic [1:0]                     m_axi_arburst,
  output logic [3:0]                     m_axi_arcache,
  output logic [2:0]                     m_axi_arprot,
  output logic                           m_axi_arvalid,
  input  logic                           m_axi_arready,
  input  logic [ID_W-1:0]                m_axi_rid,
  input  logic [AXI_DATA_W-1:0]          m_axi_rdata,
  input  logic [1:0]                     m_axi_rresp,
  input  logic                           m_axi_rlast,
  input  logic                           m_axi_rvalid,
  output logic                           m_axi_rready,
  // AXI4 write master
  output logic [ID_W-1:0]                m_axi_awid,
  output logic [ADDR_W-1:0]              m_axi_awaddr,
  output logic [7:0]                     m_axi_awlen,
  output logic [2:0]                     m_axi_awsize,
  output logic [1:0]                     m_axi_awburst,
  output logic [3:0]                     m_axi_awcache,
  output logic [2:0]                     m_axi_awprot,
  output logic                           m_axi_awvalid,
  input  logic                           m_axi_awready,
  output logic [AXI_DATA_W-1:0]          m_axi_wdata,
  output logic [AXI_DATA_W/8-1:0]        m_axi_wstrb,
  output logic                           m_axi_wlast,
  output logic                           m_axi_wvalid,
  input  logic                           m_axi_wready,
  input  logic [ID_W-1:0]                m_axi_bid,
  input  logic [1:0]                     m_axi_bresp,
  input  logic                           m_axi_bvalid,
  output logic                           m_axi_bready
);

  localparam int unsigned D   = AXI_DATA_W;
  localparam int unsigned BB  = D / 8;
  localparam int unsigned LGB = $clog2(BB);
  localparam int unsigned NS  = MAX_LG;           // stages and writer slots (levels 1..MAX_LG)
  localparam int unsigned SW  = $clog2(NS + 1);
  localparam int unsigned RW  = MAX_LG;           // row index width
  localparam int unsigned WW  = MAX_LG + 1;       // word index width
  localparam int unsigned LBW = MAX_LG + 2;       // bytes of a row

  if (D < 32 || D > 512 || (1 << LGB) != BB || MAX_LG < 1 || MAX_LG > 15
      || SZ_W != MAX_LG + 1 || XY_W != MAX_LG) begin : g_check
    $error("pyr_build: AXI_DATA_W a power of two in 32..512, MAX_LG in 1..15, SZ_W/XY_W derived");
  end

  // Line buffer words of stage j: the most output words in a row (level j + 1, or any level for
  // stage 0, which also serves the dirty passes), at least 2.
  function automatic int unsigned lb_depth(input int unsigned j);
    int unsigned words;
    words = ((1 << MAX_LG) >> j) / BB;
    return (words < 2) ? 2 : words;
  endfunction

  // ---- configuration, sampled at start_i ----
  logic [ADDR_W-1:0]           src_base_q, pyr_base_q;
  logic [MAX_LG:0][ADDR_W-1:0] off_q;
  logic [SZ_W-1:0]             w_q, h_q;
  logic                        b16_q;
  logic [XY_W-1:0]             x0_q, y0_q, x1_q, y1_q;

  typedef enum logic [2:0] {C_IDLE, C_CHECK, C_CHECK2, C_CHECK3, C_SETUP, C_RUN, C_DONE} cstate_e;
  cstate_e        state_q;
  logic [4:0]     n_q;           // root level
  logic           full_q;        // full rebuild
  logic [4:0]     s_q;           // pass: source level
  logic [SW-1:0]  j_q;           // slot being loaded
  logic [SW-1:0]  m_q;           // slots (stages) of the pass
  logic [2:0]     err_q;
  logic           rd_start;

  logic [XY_W-1:0] wm1, hm1;     // W - 1, H - 1 (registered in C_CHECK)
  logic [4:0]      n_c;
  logic            cfg_bad, full_c;
  logic [LGB-1:0]  align_or;


  always_comb begin
    n_c = '0;
    for (int i = 0; i < XY_W; i++) begin
      if (((wm1 | hm1) >> i) != '0) n_c = 5'(i + 1);
    end
    align_or = src_base_q[LGB-1:0] | pyr_base_q[LGB-1:0];
    for (int k = 1; k <= MAX_LG; k++) begin
      if (k <= 32'(n_q)) align_or = align_or | off_q[k][LGB-1:0];
    end
    cfg_bad = (w_q == '0) || (h_q == '0) || (w_q > SZ_W'(1 << MAX_LG)) || (h_q > SZ_W'(1 << MAX_LG))
              || (x0_q > x1_q) || (y0_q > y1_q) || (SZ_W'(x1_q) >= w_q) || (SZ_W'(y1_q) >= h_q)
              || (align_or != '0);
    full_c  = (x0_q == '0) && (y0_q == '0) && (x1_q == wm1) && (y1_q == hm1);
  end

  // ---- pass set-up, pipelined (registers only between the steps) ----
  // C_SETUP prepares the slots 0 .. m - 1 of the pass one after the other, five clocks each
  // (ph_q 0..4): ph 0 the level k = s + j + 1, ph 1 its side and shifts, ph 2 the shifted sizes,
  // ph 3 the slot's rectangle, ph 4 the rectangle into the writer.  The reader's rectangle is
  // ready after ph 2 of slot 0 and is started with the last slot's ph 4.
  logic [LGB-1:0]    lgt;       // log2 of texels per word
  assign lgt = LGB'(LGB) - LGB'(b16_q);

  // the reader (level s)
  logic [4:0]        rs_c, rs1_c;                 // s + lgt, s + 1 + lgt
  logic [RW-1:0]     ra_hl, ra_y0, ra_y1;         // (H-1) >> s, y0 >> (s+1), y1 >> (s+1)
  logic [WW-1:0]     ra_wl, ra_x0, ra_x1;         // (W-1) >> (s+lgt), x0, x1 >> (s+1+lgt)
  logic [LBW-1:0]    ra_live;                     // (W-1) >> s
  logic [ADDR_W-1:0] r_base;
  logic [4:0]        r_pitch_lg;
  logic [RW-1:0]     r_row0, r_row1;
  logic [WW-1:0]     r_w0, r_w1;
  logic [LBW-1:0]    r_live;

  // the slot (level k)
  logic [4:0]        k_q, side_lg_q, lw_sh_q;
  logic [ADDR_W-1:0] l_base, l_off, r_off;
  logic [RW:0]       la_hk, la_y0, la_y1;        // (H-1) >> k, y0 >> k, y1 >> k
  logic [WW:0]       la_wl, la_x0, la_x1, la_rw; // (W-1), x0, x1 >> (k+lgt); row words
  logic [4:0]        l_pitch_lg;
  logic [RW-1:0]     l_row0, l_side_mask;
  logic [RW:0]       l_nrows, l_live_lim, l_side;
  logic [WW-1:0]     l_w0;
  logic [WW:0]       l_lw, l_zw, l_rw;
  logic [2:0]        ph_q;

  // Shared shifters and offset pick: the reader's values (j = 0) and the slot's come at
  // different phases, so one shifter per source serves both (amounts picked by the phase).
  logic [4:0]        sh_h, sh_y, sh_w, sh_x;      // shift amounts of hm1, y0/y1, wm1, x0/x1
  logic [XY_W-1:0]   hs_h, hs_y0, hs_y1, hs_w, hs_x0, hs_x1;
  logic [ADDR_W-1:0] off_pick;
  always_comb begin
    sh_h = (ph_q == 3'd1) ? s_q : k_q;
    sh_y = (ph_q == 3'd1) ? s_q + 5'd1 : k_q;
    sh_w = (ph_q == 3'd0) ? s_q : (ph_q == 3'd1) ? rs_c : lw_sh_q;
    sh_x = (ph_q == 3'd1) ? rs1_c : lw_sh_q;
    hs_h  = hm1 >> sh_h;
    hs_y0 = y0_q >> sh_y;
    hs_y1 = y1_q >> sh_y;
    hs_w  = wm1 >> sh_w;
    hs_x0 = x0_q >> sh_x;
    hs_x1 = x1_q >> sh_x;
    off_pick = off_q[(ph_q == 3'd0) ? s_q : k_q];
  end

  always_ff @(posedge clk_i) begin
    if (state_q == C_SETUP) begin
      case (ph_q)
        3'd0: begin
          k_q   <= s_q + 5'(j_q) + 5'd1;
          rs_c  <= s_q + 5'(lgt);
          rs1_c <= s_q + 5'd1 + 5'(lgt);
          if (j_q == '0) begin
            r_off   <= off_pick;
            ra_live <= LBW'(hs_w);
          end
        end
        3'd1: begin
          side_lg_q <= n_q - k_q;
          lw_sh_q   <= k_q + 5'(lgt);
          l_off     <= off_pick;
          if (j_q == '0) begin
            r_pitch_lg <= n_q - s_q + 5'(b16_q);
            ra_hl      <= RW'(hs_h);
            ra_y0      <= RW'(hs_y0);
            ra_y1      <= RW'(hs_y1);
            ra_wl      <= WW'(hs_w);
            ra_x0      <= WW'(hs_x0);
            ra_x1      <= WW'(hs_x1);
          end
        end
        3'd2: begin
          la_hk       <= (RW+1)'(hs_h);
          la_y0       <= (RW+1)'(hs_y0);
          la_y1       <= (RW+1)'(hs_y1);
          la_wl       <= (WW+1)'(hs_w);
          la_x0       <= (WW+1)'(hs_x0);
          la_x1       <= (WW+1)'(hs_x1);
          la_rw       <= (side_lg_q >= 5'(lgt)) ? (WW+1)'(1) << (side_lg_q - 5'(lgt)) : (WW+1)'(1);
          l_side      <= (RW+1)'(1) << side_lg_q;
          l_side_mask <= RW'(((RW+1)'(1) << side_lg_q) - (RW+1)'(1));
          l_pitch_lg  <= side_lg_q + 5'(b16_q);
          l_base      <= pyr_base_q + l_off;
          if (j_q == '0) begin
            r_base <= (s_q == '0) ? src_base_q : pyr_base_q + r_off;
            r_live <= LBW'((ra_live + LBW'(1)) << b16_q);
            if (full_q) begin
              r_row0 <= '0;
              r_row1 <= hm1;
              r_w0   <= '0;
              r_w1   <= ra_wl;
            end else begin
              r_row0 <= ra_y0 << 1;
              r_row1 <= (((ra_y1 << 1) | RW'(1)) > ra_hl) ? ra_hl : ((ra_y1 << 1) | RW'(1));
              r_w0   <= ra_x0 << 1;
              r_w1   <= (((ra_x1 << 1) | WW'(1)) > ra_wl) ? ra_wl : ((ra_x1 << 1) | WW'(1));
            end
          end
        end
        3'd3: begin
          // the slot's rectangle
          if (full_q) begin
            l_row0     <= RW'(la_hk + (RW+1)'(1)) & l_side_mask;
            l_nrows    <= l_side;
            l_live_lim <= la_hk + (RW+1)'(1);
            l_w0       <= '0;
            l_lw       <= la_wl + (WW+1)'(1);
            l_zw       <= la_rw - la_wl - (WW+1)'(1);
            l_rw       <= la_rw;
          end else begin
            l_row0     <= RW'(la_y0);
            l_nrows    <= la_y1 - la_y0 + (RW+1)'(1);
            l_live_lim <= l_side;
            l_w0       <= WW'(la_x0);
            l_lw       <= la_x1 - la_x0 + (WW+1)'(1);
            l_zw       <= '0;
            l_rw       <= la_x1 - la_x0 + (WW+1)'(1);
          end
        end
        default: ;
      endcase
    end
  end

  // ---- control ----
  logic rd_idle, rd_err, wr_idle, wr_err;
  /* verilator lint_off UNUSEDSIGNAL */  // read by the bound checker (pyr_build_assert)
  logic wr_empty;
  /* verilator lint_on UNUSEDSIGNAL */
  logic slot_ld, slot_last;

  assign slot_ld   = (state_q == C_SETUP) && (ph_q == 3'd4);
  assign slot_last = j_q + SW'(1) == m_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      state_q <= C_IDLE;
      err_q   <= '0;
      done_o  <= 1'b0;
    end else begin
      done_o <= 1'b0;
      case (state_q)
        C_IDLE: if (start_i) begin
          state_q <= C_CHECK;
          err_q   <= '0;
        end
        C_CHECK: begin
          wm1     <= XY_W'(w_q - SZ_W'(1));
          hm1     <= XY_W'(h_q - SZ_W'(1));
          state_q <= C_CHECK2;
        end
        C_CHECK2: begin
          n_q     <= n_c;
          full_q  <= full_c;
          state_q <= C_CHECK3;
        end
        C_CHECK3: begin
          s_q  <= '0;
          j_q  <= '0;
          ph_q <= '0;
          m_q  <= full_q ? SW'(n_q) : SW'(1);
          if (cfg_bad) begin
            err_q[2] <= 1'b1;
            state_q  <= C_DONE;
          end else if (n_q == '0) begin
            state_q  <= C_DONE;
          end else begin
            state_q  <= C_SETUP;
          end
        end
        C_SETUP: begin
          ph_q <= ph_q + 3'd1;
          if (ph_q == 3'd4) begin
            ph_q <= '0;
            j_q  <= j_q + SW'(1);
            if (slot_last) state_q <= C_RUN;
          end
        end
        C_RUN: begin
          err_q[0] <= err_q[0] | rd_err;
          err_q[1] <= err_q[1] | wr_err;
          if (rd_idle && wr_idle) begin
            if (full_q || (s_q + 5'd1 == n_q)) begin
              state_q <= C_DONE;
            end else begin
              s_q     <= s_q + 5'd1;
              j_q     <= '0;
              ph_q    <= '0;
              state_q <= C_SETUP;
            end
          end
        end
        C_DONE: begin
          done_o  <= 1'b1;
          state_q <= C_IDLE;
        end
        default: state_q <= C_IDLE;
      endcase
    end
  end

  always_ff @(posedge clk_i) begin
    if (state_q == C_IDLE && start_i) begin
      src_base_q <= cfg_src_base_i;
      pyr_base_q <= cfg_pyr_base_i;
      off_q      <= cfg_level_off_i;
      w_q        <= cfg_width_i;
      h_q        <= cfg_height_i;
      b16_q      <= cfg_bits16_i;
      x0_q       <= dirty_x0_i;
      y0_q       <= dirty_y0_i;
      x1_q       <= dirty_x1_i;
      y1_q       <= dirty_y1_i;
    end
  end

  assign rd_start   = slot_ld && slot_last;
  assign busy_o     = state_q != C_IDLE;
  assign err_o      = err_q != '0;
  assign err_code_o = {1'b0, err_q};

  // ---- datapath ----
  logic              rd_valid, rd_eol, rd_lrow, rd_ready;
  logic [D-1:0]      rd_data;
  logic [NS-1:0]         st_in_valid, st_in_eol, st_in_lrow, st_in_ready;
  logic [NS-1:0][D-1:0]  st_in_data;
  logic [NS-1:0]         st_out_valid, st_out_ready;
  /* verilator lint_off UNUSEDSIGNAL */  // the last stage's flags and sk_room[0] are not needed
  logic [NS-1:0]         st_out_eol, st_out_lrow;
  logic [NS-1:0]         sk_room;     // stage j's input queue has room (j >= 1)
  /* verilator lint_on UNUSEDSIGNAL */
  logic [NS-1:0][D-1:0]  st_out_data;
  logic [NS-1:0]         wr_push, wr_full;

  pyr_reader #(
    .ADDR_W(ADDR_W), .DATA_W(D), .ID_W(ID_W), .BURST(BURST), .MAX_RD(MAX_RD),
    .RW(RW), .WW(WW), .LBW(LBW), .CACHE(AXI_CACHE), .PROT(AXI_PROT)
  ) u_reader (
    .clk_i, .rst_ni,
    .start_i     (rd_start),
    .base_i      (r_base),
    .pitch_lg_i  (r_pitch_lg),
    .row0_i      (r_row0),
    .row1_i      (r_row1),
    .w0_i        (r_w0),
    .w1_i        (r_w1),
    .live_bytes_i(r_live),
    .idle_o      (rd_idle),
    .err_o       (rd_err),
    .out_valid_o (rd_valid),
    .out_data_o  (rd_data),
    .out_eol_o   (rd_eol),
    .out_lrow_o  (rd_lrow),
    .out_ready_i (rd_ready),
    .m_axi_arid, .m_axi_araddr, .m_axi_arlen, .m_axi_arsize, .m_axi_arburst, .m_axi_arcache,
    .m_axi_arprot, .m_axi_arvalid, .m_axi_arready, .m_axi_rid, .m_axi_rlast, .m_axi_rdata,
    .m_axi_rresp, .m_axi_rvalid, .m_axi_rready
  );

  for (genvar j = 0; j < NS; j++) begin : g_stage
    if (j == 0) begin : g_first
      assign st_in_valid[j] = rd_valid;
      assign st_in_data[j]  = rd_data;
      assign st_in_eol[j]   = rd_eol;
      assign st_in_lrow[j]  = rd_lrow;
      assign rd_ready       = st_in_ready[j];
      assign sk_room[j]     = 1'b1;
    end else begin : g_next
      // A two-word queue between stages: its registered count is the previous stage's ready, so
      // no combinational ready runs along the chain.
      logic [1:0]     cnt;
      logic [D+1:0]   head;
      logic           push;
      assign push = st_out_valid[j-1] && st_out_ready[j-1] && (SW'(j) < m_q);
      circ_queue #(.WIDTH(D + 2), .DEPTH(2)) u_sk (
        .clk_i, .rst_ni,
        .push_i (push),
        .wr_i   (push),
        .wdata_i({st_out_eol[j-1], st_out_lrow[j-1], st_out_data[j-1]}),
        .pop_n_i(st_in_valid[j] && st_in_ready[j]),
        .rdata_o(head),
        .peek_o (),
        .count_o(cnt)
      );
      assign sk_room[j]     = cnt != 2'd2;
      assign st_in_valid[j] = cnt != 2'd0;
      assign {st_in_eol[j], st_in_lrow[j], st_in_data[j]} = head;
    end

    if (j + 1 < NS) begin : g_ready
      assign st_out_ready[j] = !wr_full[j] && (!(SW'(j + 1) < m_q) || sk_room[j+1]);
    end else begin : g_ready_last
      assign st_out_ready[j] = !wr_full[j];
    end
    assign wr_push[j] = st_out_valid[j] && st_out_ready[j];

    pyr_stage #(.DATA_W(D), .LB_DEPTH(lb_depth(j))) u_stage (
      .clk_i, .rst_ni,
      .b16_i      (b16_q),
      .in_valid_i (st_in_valid[j]),
      .in_data_i  (st_in_data[j]),
      .in_eol_i   (st_in_eol[j]),
      .in_lrow_i  (st_in_lrow[j]),
      .in_ready_o (st_in_ready[j]),
      .out_valid_o(st_out_valid[j]),
      .out_data_o (st_out_data[j]),
      .out_eol_o  (st_out_eol[j]),
      .out_lrow_o (st_out_lrow[j]),
      .out_ready_i(st_out_ready[j])
    );
  end

  pyr_writer #(
    .ADDR_W(ADDR_W), .DATA_W(D), .ID_W(ID_W), .BURST(BURST), .NS(NS), .MAX_LG(MAX_LG),
    .RW(RW), .WW(WW), .SW(SW), .CACHE(AXI_CACHE), .PROT(AXI_PROT)
  ) u_writer (
    .clk_i, .rst_ni,
    .clr_i         ((state_q == C_SETUP) && (j_q == '0) && (ph_q == 3'd0)),
    .ld_i          (slot_ld),
    .ld_slot_i     (j_q),
    .ld_base_i     (l_base),
    .ld_pitch_lg_i (l_pitch_lg),
    .ld_row0_i     (l_row0),
    .ld_nrows_i    (l_nrows),
    .ld_live_lim_i (l_live_lim),
    .ld_side_mask_i(l_side_mask),
    .ld_w0_i       (l_w0),
    .ld_lw_i       (l_lw),
    .ld_zw_i       (l_zw),
    .ld_rw_i       (l_rw),
    .push_i        (wr_push),
    .data_i        (st_out_data),
    .full_o        (wr_full),
    .idle_o        (wr_idle),
    .empty_o       (wr_empty),
    .err_o         (wr_err),
    .m_axi_awid, .m_axi_awaddr, .m_axi_awlen, .m_axi_awsize, .m_axi_awburst, .m_axi_awcache,
    .m_axi_awprot, .m_axi_awvalid, .m_axi_awready, .m_axi_wdata, .m_axi_wstrb, .m_axi_wlast,
    .m_axi_wvalid, .m_axi_wready, .m_axi_bid, .m_axi_bresp, .m_axi_bvalid, .m_axi_bready
  );

endmodule
