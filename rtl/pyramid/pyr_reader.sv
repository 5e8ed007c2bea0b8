// SPDX-License-Identifier: Apache-2.0
// pyr_reader: pyr_build's AXI4 read master.  Reads a rectangle of one pyramid level (rows
// row0_i..row1_i, bus words w0_i..w1_i of each row, bounds inclusive) as INCR bursts and hands its
// words to the first pyr_stage, row by row, flagged with eol (a row's last word) and lrow (the
// rectangle's last row).
//
// Addresses: word w of row r is at base_i + (r << pitch_lg_i) + w * DATA_W / 8 (the level's own
// row pitch, 2^pitch_lg_i bytes; base_i a multiple of DATA_W / 8).  A row narrower than a bus word
// (2^pitch_lg_i < DATA_W / 8) is one word, read from the word that holds it and shifted down to
// lane 0.  Bytes at or past live_bytes_i from the row's start (the texels past the map's own width)
// are replaced by zero: the padding rule of model/heightmap.py, whatever the memory holds there.
// Bursts: at most BURST beats (arlen = len - 1), never across a 4 KiB boundary, at most MAX_RD
// bursts outstanding; arid 0, arsize log2(DATA_W / 8), arburst INCR.
// R: rready = the output queue (two words, registered count) has room; outside a run rready is 1
// and beats are dropped.  An rresp other than OKAY on any beat sets err_o (held until start_i); the
// beat is used all the same, so the build runs to its end (never hangs).
// start_i (one clock, with the rectangle on the *_i ports, sampled then) begins a rectangle;
// idle_o is 1 when every burst of the rectangle has been issued and every beat received.
module pyr_reader #(
  parameter int unsigned ADDR_W = 32,  // AXI address width
  parameter int unsigned DATA_W = 64,  // AXI data width
  parameter int unsigned ID_W   = 1,   // AXI ID width
  parameter int unsigned BURST  = 16,  // beats per burst at most (power of two, 2..256)
  parameter int unsigned MAX_RD = 4,   // bursts outstanding at most (>= 1)
  parameter int unsigned RW     = 10,  // row index width
  parameter int unsigned WW     = 11,  // word index width
  parameter int unsigned LBW    = 12,  // live_bytes_i width
  parameter logic [3:0]  CACHE  = 4'b0011,  // arcache
  parameter logic [2:0]  PROT   = 3'b000    // arprot
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              start_i,
  input  logic [ADDR_W-1:0] base_i,
  input  logic [4:0]        pitch_lg_i,
  input  logic [RW-1:0]     row0_i,
  input  logic [RW-1:0]     row1_i,
  input  logic [WW-1:0]     w0_i,
  input  logic [WW-1:0]     w1_i,
  input  logic [LBW-1:0]    live_bytes_i,
  output logic              idle_o,
  output logic              err_o,
  // to the first stage
  output logic              out_valid_o,
  output logic [DATA_W-1:0] out_data_o,
  output logic              out_eol_o,
  output logic              out_lrow_o,
  input  logic              out_ready_i,
  // AXI4 read master
  output logic [ID_W-1:0]   m_axi_arid,
  output logic [ADDR_W-1:0] m_axi_araddr,
  output logic [7:0]        m_axi_arlen,
  output logic [2:0]        m_axi_arsize,
  output logic [1:0]        m_axi_arburst,
  output logic [3:0]        m_axi_arcache,
  output logic [2:0]        m_axi_arprot,
  output logic              m_axi_arvalid,
  input  logic              m_axi_arready,
  /* verilator lint_off UNUSEDSIGNAL */  // one ID: rid is not needed
  input  logic [ID_W-1:0]   m_axi_rid,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic              m_axi_rlast,
  input  logic [DATA_W-1:0] m_axi_rdata,
  input  logic [1:0]        m_axi_rresp,
  input  logic              m_axi_rvalid,
  output logic              m_axi_rready
);

  localparam int unsigned BB   = DATA_W / 8;       // bytes per beat
  localparam int unsigned LGB  = $clog2(BB);
  localparam int unsigned OW   = $clog2(MAX_RD + 1);
  localparam int unsigned BLW  = $clog2(BURST) + 1;  // burst length width

  if (DATA_W < 32 || (1 << LGB) != BB || BURST < 2 || BURST > 256
      || (1 << $clog2(BURST)) != BURST || MAX_RD < 1) begin : g_check
    $error("pyr_reader: DATA_W a power of two >= 32, BURST a power of two in 2..256, MAX_RD >= 1");
  end

  // The rectangle (sampled at start_i).
  logic [ADDR_W-1:0] base_q;
  logic [4:0]        pitch_lg_q;
  logic [RW-1:0]     row1_q;
  logic [WW-1:0]     w0_q, w1_q;
  logic [LBW-1:0]    live_q;

  // ---- AR: the bursts ----
  // A_INIT, A_INIT2: the first row's offset, then its address; A_ADDR: the burst's address (the row's address plus the
  // word's offset); A_LEN: its length (row end, BURST, 4 KiB boundary); A_SEND: AR.  A row's
  // address is the previous one's plus the pitch, so no clock has more than one adder in series.
  typedef enum logic [2:0] {A_IDLE, A_INIT, A_INIT2, A_ADDR, A_LEN, A_SEND} ar_state_e;
  ar_state_e         a_state_q;
  logic [RW-1:0]     a_row_q;
  logic [WW-1:0]     a_w_q;
  logic [ADDR_W-1:0] a_row_addr_q;  // address of the row's first word
  // a_addr_q[LGB-1:0] (a row's byte offset inside its first beat) is read by nothing: bursts
  // start at the beat's address.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [ADDR_W-1:0] a_addr_q;      // address of the burst's first word
  /* verilator lint_on UNUSEDSIGNAL */
  logic [12:0]       a_to4k;        // beats to the next 4 KiB boundary
  logic [WW:0]       a_left_q;      // words left in the row
  logic              a_lastrow_q;   // the rectangle's last row
  logic              a_rowend_q;    // the burst ends the row
  logic [BLW-1:0]    a_len, a_len_q;
  logic [ADDR_W-1:0] araddr_q;
  logic [OW-1:0]     outst_q;       // bursts issued, last beat not yet received
  logic              ar_hs, r_hs, r_last_beat;

  // from the burst's first beat's address (a row may start inside a beat)
  assign a_to4k = 13'((13'h1000 - {1'b0, a_addr_q[11:LGB], {LGB{1'b0}}}) >> LGB);
  always_comb begin
    a_len = BLW'(BURST);
    if (a_left_q < (WW+1)'(a_len)) a_len = BLW'(a_left_q);
    if (a_to4k < 13'(a_len)) a_len = BLW'(a_to4k);
  end

  assign ar_hs = m_axi_arvalid && m_axi_arready;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      a_state_q <= A_IDLE;
    end else begin
      case (a_state_q)
        A_IDLE: if (start_i) a_state_q <= A_INIT;
        A_INIT: a_state_q <= A_INIT2;
        A_INIT2: a_state_q <= A_ADDR;
        A_ADDR: a_state_q <= A_LEN;
        A_LEN:  a_state_q <= A_SEND;
        A_SEND: begin
          if (ar_hs) begin
            if (!a_rowend_q) begin
              a_w_q     <= a_w_q + WW'(a_len_q);
              a_state_q <= A_ADDR;
            end else if (!a_lastrow_q) begin
              a_w_q        <= w0_q;
              a_row_q      <= a_row_q + RW'(1);
              a_row_addr_q <= a_row_addr_q + (ADDR_W'(1) << pitch_lg_q);
              a_state_q    <= A_ADDR;
            end else begin
              a_state_q <= A_IDLE;
            end
          end
        end
        default: a_state_q <= A_IDLE;
      endcase
    end
    if (a_state_q == A_IDLE && start_i) begin
      a_row_q <= row0_i;
      a_w_q   <= w0_i;
    end
    if (a_state_q == A_INIT) a_row_addr_q <= ADDR_W'(a_row_q) << pitch_lg_q;
    if (a_state_q == A_INIT2) a_row_addr_q <= base_q + a_row_addr_q;
    if (a_state_q == A_ADDR) begin
      a_addr_q    <= a_row_addr_q + (ADDR_W'(a_w_q) << LGB);
      a_left_q    <= {1'b0, w1_q} - {1'b0, a_w_q} + (WW+1)'(1);
      a_lastrow_q <= a_row_q == row1_q;
    end
    if (a_state_q == A_LEN) begin
      araddr_q   <= {a_addr_q[ADDR_W-1:LGB], {LGB{1'b0}}};
      a_len_q    <= a_len;
      a_rowend_q <= (a_left_q <= (WW+1)'(BURST)) && (32'(a_left_q) <= 32'(a_to4k));
    end
  end

  always_ff @(posedge clk_i) begin
    if (start_i) begin
      base_q     <= base_i;
      pitch_lg_q <= pitch_lg_i;
      row1_q     <= row1_i;
      w0_q       <= w0_i;
      w1_q       <= w1_i;
      live_q     <= live_bytes_i;
    end
  end

  assign m_axi_arid    = '0;
  assign m_axi_araddr  = araddr_q;
  assign m_axi_arlen   = 8'(a_len_q - BLW'(1));
  assign m_axi_arsize  = 3'(LGB);
  assign m_axi_arburst = 2'b01;
  assign m_axi_arcache = CACHE;
  assign m_axi_arprot  = PROT;
  assign m_axi_arvalid = (a_state_q == A_SEND) && (outst_q < OW'(MAX_RD));

  // ---- R: the beats, in the order of the bursts ----
  logic          r_run_q;          // beats of the rectangle still to come
  logic [RW-1:0] r_row_q;
  logic [WW-1:0] r_w_q;
  logic [1:0]    q_cnt;
  logic [DATA_W+1:0] q_wdata, q_rdata;
  logic [LGB-1:0]    r_shift;      // byte offset of a sub-word row in its word
  logic [LBW+1:0]    r_rem;        // live bytes left from this word on (may be negative)
  logic [DATA_W-1:0] r_data;
  logic              q_pop;

  assign m_axi_rready = !r_run_q || (q_cnt < 2'd2);
  assign r_hs         = m_axi_rvalid && m_axi_rready && r_run_q;
  assign r_last_beat  = (r_w_q == w1_q) && (r_row_q == row1_q);

  // A row narrower than a word: its offset in the word (base_q is word-aligned).
  assign r_shift = (pitch_lg_q < 5'(LGB)) ? LGB'(ADDR_W'(r_row_q) << pitch_lg_q) : '0;
  assign r_rem   = (LBW+2)'(live_q) - ((LBW+2)'(r_w_q) << LGB);
  always_comb begin
    r_data = m_axi_rdata >> {r_shift, 3'b000};
    for (int b = 0; b < BB; b++) begin
      if ($signed(r_rem) <= $signed((LBW+2)'(b))) r_data[8*b +: 8] = 8'h00;
    end
  end
  assign q_wdata = {r_w_q == w1_q, r_row_q == row1_q, r_data};

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      r_run_q <= 1'b0;
      outst_q <= '0;
      err_o   <= 1'b0;
    end else begin
      outst_q <= outst_q + OW'(ar_hs) - OW'(r_hs && m_axi_rlast);
      if (start_i) begin
        r_run_q <= 1'b1;
        r_row_q <= row0_i;
        r_w_q   <= w0_i;
        err_o   <= 1'b0;
      end else if (r_hs) begin
        if (m_axi_rresp != 2'b00) err_o <= 1'b1;
        if (r_last_beat) r_run_q <= 1'b0;
        if (r_w_q == w1_q) begin
          r_w_q   <= w0_q;
          r_row_q <= r_row_q + RW'(1);
        end else begin
          r_w_q <= r_w_q + WW'(1);
        end
      end
    end
  end

  circ_queue #(.WIDTH(DATA_W + 2), .DEPTH(2)) u_q (
    .clk_i, .rst_ni,
    .push_i (r_hs),
    .wr_i   (r_hs),
    .wdata_i(q_wdata),
    .pop_n_i(q_pop),
    .rdata_o(q_rdata),
    .peek_o (),
    .count_o(q_cnt)
  );

  assign out_valid_o = q_cnt != 2'd0;
  assign {out_eol_o, out_lrow_o, out_data_o} = q_rdata;
  assign q_pop = out_valid_o && out_ready_i;

  assign idle_o = (a_state_q == A_IDLE) && !r_run_q;

endmodule
