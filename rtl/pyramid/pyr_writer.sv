// SPDX-License-Identifier: Apache-2.0
// pyr_writer: pyr_build's AXI4 write master.  NS slots, one per pyr_stage: slot j takes stage j's
// output words into its own queue and writes a rectangle of one pyramid level from them.
//
// A slot's rectangle (loaded with ld_i): rows row0, row0 + 1, ... (nrows rows, the row index
// wrapping at side_mask + 1), and in each row the words w0 .. w0 + lw + zw - 1.  A row below
// live_lim takes its first lw words from the queue and writes zw zero words after them (the
// padding right of the map); a row at or above live_lim is all zero words (the padding below the
// map).  Word w of row r is at base + (r << pitch_lg) + w * DATA_W / 8 (base word-aligned); a row
// narrower than a word (2^pitch_lg < DATA_W / 8) is one beat at the word that holds it, the data
// shifted up to the row's byte offset and wstrb covering the row's 2^pitch_lg bytes only.
// Bursts: INCR, at most BURST beats, never across a 4 KiB boundary nor across a row, awid 0.  A
// burst of queued words is started only when the queue holds all of its words, so the W channel
// never waits for data; zero bursts need none.  Slots with a burst ready are served round robin.
// One burst at a time: pick, then four clocks to its address and length (the slot's fields and its
// next word, the row's and the word's offsets, the sum, the length), then AW and the W beats
// together.  At most 2^10 - 1 bursts wait for their B response.
// B: bready = 1; a bresp other than OKAY sets err_o (held until clr_i).  idle_o: no slot has a
// row left, no burst is under way and every B has come back; empty_o: every queue is empty.
// clr_i (one clock, between rectangles) empties every slot's rectangle; the queues keep their
// words (they are empty then when the words matched the rectangles).
module pyr_writer #(
  parameter int unsigned ADDR_W = 32,  // AXI address width
  parameter int unsigned DATA_W = 64,  // AXI data width
  parameter int unsigned ID_W   = 1,   // AXI ID width
  parameter int unsigned BURST  = 16,  // beats per burst at most (power of two, 2..256)
  parameter int unsigned NS     = 10,  // slots (levels 1 .. NS)
  parameter int unsigned MAX_LG = 10,  // log2 of the largest level 0 side
  parameter int unsigned RW     = 10,  // row index width
  parameter int unsigned WW     = 11,  // word index width
  parameter int unsigned SW     = 4,   // slot index width
  parameter logic [3:0]  CACHE  = 4'b0011,  // awcache
  parameter logic [2:0]  PROT   = 3'b000    // awprot
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  input  logic                       clr_i,
  input  logic                       ld_i,
  input  logic [SW-1:0]              ld_slot_i,
  input  logic [ADDR_W-1:0]          ld_base_i,
  input  logic [4:0]                 ld_pitch_lg_i,
  input  logic [RW-1:0]              ld_row0_i,
  input  logic [RW:0]                ld_nrows_i,
  input  logic [RW:0]                ld_live_lim_i,
  input  logic [RW-1:0]              ld_side_mask_i,
  input  logic [WW-1:0]              ld_w0_i,
  input  logic [WW:0]                ld_lw_i,
  input  logic [WW:0]                ld_zw_i,
  input  logic [WW:0]                ld_rw_i,   // lw + zw
  input  logic [NS-1:0]              push_i,
  input  logic [NS-1:0][DATA_W-1:0]  data_i,
  output logic [NS-1:0]              full_o,
  output logic                       idle_o,
  output logic                       empty_o,   // every queue is empty
  output logic                       err_o,
  // AXI4 write master
  output logic [ID_W-1:0]            m_axi_awid,
  output logic [ADDR_W-1:0]          m_axi_awaddr,
  output logic [7:0]                 m_axi_awlen,
  output logic [2:0]                 m_axi_awsize,
  output logic [1:0]                 m_axi_awburst,
  output logic [3:0]                 m_axi_awcache,
  output logic [2:0]                 m_axi_awprot,
  output logic                       m_axi_awvalid,
  input  logic                       m_axi_awready,
  output logic [DATA_W-1:0]          m_axi_wdata,
  output logic [DATA_W/8-1:0]        m_axi_wstrb,
  output logic                       m_axi_wlast,
  output logic                       m_axi_wvalid,
  input  logic                       m_axi_wready,
  /* verilator lint_off UNUSEDSIGNAL */  // one ID: bid is not needed
  input  logic [ID_W-1:0]            m_axi_bid,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic [1:0]                 m_axi_bresp,
  input  logic                       m_axi_bvalid,
  output logic                       m_axi_bready
);

  localparam int unsigned BB  = DATA_W / 8;
  localparam int unsigned LGB = $clog2(BB);
  localparam int unsigned BLW = $clog2(BURST) + 1;
  localparam int unsigned OBW = 10;              // outstanding bursts counter width

  if (DATA_W < 32 || (1 << LGB) != BB || BURST < 2 || BURST > 256
      || (1 << $clog2(BURST)) != BURST || NS < 1 || SW < $clog2(NS + 1)) begin : g_check
    $error("pyr_writer: DATA_W a power of two >= 32, BURST a power of two in 2..256, SW wide enough");
  end

  // Queue depth of slot j: twice its longest burst of queued words (a row of level j + 1, or of
  // any level for slot 0), at least 2.
  function automatic int unsigned qdepth(input int unsigned j);
    int unsigned words;
    words = ((1 << MAX_LG) >> j) / BB;
    if (words < 1) words = 1;
    if (words > BURST) words = BURST;
    return (2 * words < 2) ? 2 : 2 * words;
  endfunction

  // ---- slot rectangles and their progress ----
  logic [ADDR_W-1:0] base_q      [NS];
  logic [4:0]        pitch_lg_q  [NS];
  logic [RW:0]       live_lim_q  [NS];
  logic [RW-1:0]     side_mask_q [NS];
  logic [WW-1:0]     w0_q        [NS];
  logic [WW:0]       lw_q        [NS];
  logic [WW:0]       zw_q        [NS];
  logic [WW:0]       rw_q        [NS];  // lw + zw
  logic [RW-1:0]     row_q       [NS];  // current row
  logic [RW:0]       rows_left_q [NS];  // rows left, the current one included
  logic              zseg_q      [NS];  // in the zero words of the row
  logic [WW:0]       wleft_q     [NS];  // words left in the current segment
  // The next word from w0 is not kept: it is (zseg ? rw : lw) - wleft (the live segment starts
  // at 0, the zero segment ends at rw), worked out for the picked slot only.

  logic [NS-1:0][DATA_W-1:0] q_head;
  logic [NS-1:0]             q_pop;
  logic [NS-1:0]             ready;     // slot j has a burst it can start now
  logic [NS-1:0]             q_empty;

  for (genvar j = 0; j < NS; j++) begin : g_q
    localparam int unsigned QD = qdepth(j);
    localparam int unsigned CW = $clog2(QD + 1);
    logic [CW-1:0] cnt;
    logic [WW:0]   need;
    circ_queue #(.WIDTH(DATA_W), .DEPTH(QD)) u_q (
      .clk_i, .rst_ni,
      .push_i (push_i[j]),
      .wr_i   (push_i[j]),
      .wdata_i(data_i[j]),
      .pop_n_i(q_pop[j]),
      .rdata_o(q_head[j]),
      .peek_o (),
      .count_o(cnt)
    );
    assign full_o[j] = cnt == CW'(QD);
    assign q_empty[j] = cnt == '0;
    assign need      = (wleft_q[j] < (WW+1)'(BURST)) ? wleft_q[j] : (WW+1)'(BURST);
    assign ready[j]  = (rows_left_q[j] != '0) && (zseg_q[j] || ((WW+1)'(cnt) >= need));
  end

  // ---- the burst engine ----
  typedef enum logic [2:0] {S_PICK, S_SEL, S_SHIFT, S_ADD, S_LEN, S_DATA} state_e;
  state_e            state_q;
  logic [SW-1:0]     sel_q, last_q;
  logic [SW-1:0]     pick;
  logic              any_ready;
  logic [ADDR_W-1:0] m_base_q, m_rowoff_q, m_woff_q, b_addr_q;
  logic [RW-1:0]     m_row_q, m_next_row_q;  // the slot's row, the next one
  logic [4:0]        m_pitch_lg_q;
  logic              m_next_live_q;          // the next row is below live_lim
  logic              m_seg_end_q;            // the burst ends the segment
  logic              m_zseg_q;
  logic [WW:0]       m_lw_q, m_zw_q, m_rw_q;
  logic [WW-1:0]     m_w0_q, m_wpos_q;   // the slot's w0, its next word (from w0)
  logic [RW:0]       m_live_lim_q;
  logic [RW-1:0]     m_side_mask_q;
  logic [WW:0]       m_wleft_q;
  logic              m_partial_q;
  logic [BB-1:0]     m_mask_q;       // a sub-word row's bytes, from lane 0
  logic [12:0]       b_to4k;
  logic [BLW-1:0]    b_len;
  logic [ADDR_W-1:0] awaddr_q;
  logic [BLW-1:0]    len_q, beats_q;
  logic              awv_q, zero_q;
  logic [LGB-1:0]    shift_q;
  logic [BB-1:0]     strb_q;
  logic [OBW-1:0]    outst_q;
  logic              aw_hs, w_hs, b_hs;

  // Round robin: the first ready slot after the last one served.
  always_comb begin
    pick = '0;
    any_ready = 1'b0;
    for (int i = NS - 1; i >= 0; i--) begin
      if (ready[i] && (SW'(i) > last_q)) begin
        pick = SW'(i);
        any_ready = 1'b1;
      end
    end
    if (!any_ready) begin
      for (int i = NS - 1; i >= 0; i--) begin
        if (ready[i]) begin
          pick = SW'(i);
          any_ready = 1'b1;
        end
      end
    end
  end

  assign b_to4k = 13'((13'h1000 - {1'b0, b_addr_q[11:0]}) >> LGB);
  always_comb begin
    b_len = BLW'(BURST);
    if (m_wleft_q < (WW+1)'(b_len)) b_len = BLW'(m_wleft_q);
    if (b_to4k < 13'(b_len)) b_len = BLW'(b_to4k);
  end

  assign aw_hs = m_axi_awvalid && m_axi_awready;
  assign w_hs  = m_axi_wvalid && m_axi_wready;
  assign b_hs  = m_axi_bvalid && m_axi_bready;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      state_q <= S_PICK;
      last_q  <= '0;
      awv_q   <= 1'b0;
      outst_q <= '0;
      err_o   <= 1'b0;
      for (int j = 0; j < NS; j++) rows_left_q[j] <= '0;
    end else begin
      outst_q <= outst_q + OBW'(aw_hs) - OBW'(b_hs);
      if (b_hs && m_axi_bresp != 2'b00) err_o <= 1'b1;
      if (aw_hs) awv_q <= 1'b0;
      case (state_q)
        S_PICK: begin
          if (any_ready && !clr_i && !ld_i && (outst_q != '1)) begin
            sel_q   <= pick;
            state_q <= S_SEL;
          end
        end
        S_SEL: begin
          m_base_q    <= base_q[sel_q];
          m_row_q     <= row_q[sel_q];
          m_pitch_lg_q <= pitch_lg_q[sel_q];
          m_zseg_q    <= zseg_q[sel_q];
          m_lw_q      <= lw_q[sel_q];
          m_zw_q      <= zw_q[sel_q];
          m_rw_q      <= rw_q[sel_q];
          m_wpos_q    <= WW'((zseg_q[sel_q] ? rw_q[sel_q] : lw_q[sel_q]) - wleft_q[sel_q]);
          m_w0_q      <= w0_q[sel_q];
          m_live_lim_q <= live_lim_q[sel_q];
          m_side_mask_q <= side_mask_q[sel_q];
          m_wleft_q   <= wleft_q[sel_q];
          m_partial_q <= pitch_lg_q[sel_q] < 5'(LGB);
          m_mask_q    <= BB'((BB'(1) << (BB'(1) << pitch_lg_q[sel_q])) - BB'(1));
          zero_q      <= zseg_q[sel_q];
          state_q     <= S_SHIFT;
        end
        S_SHIFT: begin
          m_rowoff_q   <= ADDR_W'(m_row_q) << m_pitch_lg_q;
          m_woff_q     <= ADDR_W'(WW'(m_w0_q) + WW'(m_wpos_q)) << LGB;
          m_next_row_q <= (m_row_q + RW'(1)) & m_side_mask_q;
          state_q      <= S_ADD;
        end
        S_ADD: begin
          b_addr_q      <= m_base_q + m_rowoff_q + m_woff_q;
          m_next_live_q <= (RW+1)'(m_next_row_q) < m_live_lim_q;
          state_q       <= S_LEN;
        end
        S_LEN: begin
          awaddr_q <= {b_addr_q[ADDR_W-1:LGB], {LGB{1'b0}}};
          len_q    <= b_len;
          beats_q  <= b_len;
          awv_q    <= 1'b1;
          shift_q  <= b_addr_q[LGB-1:0];
          strb_q   <= m_partial_q ? m_mask_q << b_addr_q[LGB-1:0] : {BB{1'b1}};
          m_seg_end_q <= (m_wleft_q <= (WW+1)'(BURST)) && (32'(m_wleft_q) <= 32'(b_to4k));
          state_q  <= S_DATA;
        end
        S_DATA: begin
          if (w_hs) beats_q <= beats_q - BLW'(1);
          if ((beats_q == BLW'(w_hs)) && (!awv_q || aw_hs)) begin
            // the burst is done: advance the slot
            last_q  <= sel_q;
            state_q <= S_PICK;
            if (!m_seg_end_q) begin
              wleft_q[sel_q] <= m_wleft_q - (WW+1)'(len_q);
            end else if (!m_zseg_q && m_zw_q != '0) begin
              zseg_q[sel_q]  <= 1'b1;
              wleft_q[sel_q] <= m_zw_q;
            end else begin
              row_q[sel_q]       <= m_next_row_q;
              rows_left_q[sel_q] <= rows_left_q[sel_q] - (RW+1)'(1);
              if (m_next_live_q) begin
                zseg_q[sel_q]  <= 1'b0;
                wleft_q[sel_q] <= m_lw_q;
              end else begin
                zseg_q[sel_q]  <= 1'b1;
                wleft_q[sel_q] <= m_rw_q;
              end
            end
          end
        end
        default: state_q <= S_PICK;
      endcase
      if (clr_i) begin
        for (int j = 0; j < NS; j++) rows_left_q[j] <= '0;
        err_o <= 1'b0;
      end
      if (ld_i) begin
        rows_left_q[ld_slot_i] <= ld_nrows_i;
        row_q[ld_slot_i]       <= ld_row0_i;
        if ((RW+1)'(ld_row0_i) < ld_live_lim_i) begin
          zseg_q[ld_slot_i]  <= 1'b0;
          wleft_q[ld_slot_i] <= ld_lw_i;
        end else begin
          zseg_q[ld_slot_i]  <= 1'b1;
          wleft_q[ld_slot_i] <= ld_rw_i;
        end
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (ld_i) begin
      base_q[ld_slot_i]      <= ld_base_i;
      pitch_lg_q[ld_slot_i]  <= ld_pitch_lg_i;
      live_lim_q[ld_slot_i]  <= ld_live_lim_i;
      side_mask_q[ld_slot_i] <= ld_side_mask_i;
      w0_q[ld_slot_i]        <= ld_w0_i;
      lw_q[ld_slot_i]        <= ld_lw_i;
      zw_q[ld_slot_i]        <= ld_zw_i;
      rw_q[ld_slot_i]        <= ld_rw_i;
    end
  end

  always_comb begin
    q_pop = '0;
    q_pop[sel_q] = (state_q == S_DATA) && !zero_q && w_hs;
  end

  assign m_axi_awid    = '0;
  assign m_axi_awaddr  = awaddr_q;
  assign m_axi_awlen   = 8'(len_q - BLW'(1));
  assign m_axi_awsize  = 3'(LGB);
  assign m_axi_awburst = 2'b01;
  assign m_axi_awcache = CACHE;
  assign m_axi_awprot  = PROT;
  assign m_axi_awvalid = awv_q;
  assign m_axi_wvalid  = (state_q == S_DATA) && (beats_q != '0);
  assign m_axi_wdata   = zero_q ? '0 : (q_head[sel_q] << {shift_q, 3'b000});
  assign m_axi_wstrb   = strb_q;
  assign m_axi_wlast   = beats_q == BLW'(1);
  assign m_axi_bready  = 1'b1;

  assign empty_o = &q_empty;

  always_comb begin
    idle_o = (state_q == S_PICK) && (outst_q == '0);
    for (int j = 0; j < NS; j++) if (rows_left_q[j] != '0) idle_o = 1'b0;
  end

endmodule
