// SPDX-License-Identifier: Apache-2.0
// pyr_stage: one level of the max-mipmap reduction (pyr_build).  Takes the words of a rectangle of
// level k, row by row, and gives the words of level k + 1 over the parents of that rectangle:
// each output texel the maximum of its 2 x 2 children.
//
// A word is DATA_W bits of texels (DATA_W / 8 unorm8 or DATA_W / 16 unorm16 codes, b16_i), lane 0
// in the low bits, as on the AXI bus.  Input rows are sequences of words flagged by in_eol_i (the
// row's last word) and in_lrow_i (every word of the rectangle's last row); the first input row of
// a rectangle is an even row and its first word an even word (pyr_build aligns the rectangle).
// Texels past the map's own width are zero in the input, so they are zero in the output: the
// padding rule of model/heightmap.py (pad with height 0).
//   Horizontal: the codes of a word pair up (lanes 2t, 2t + 1) into half a word; an even word gives
//   the low half of an output word, the next (odd) word its high half; a row's last word when even
//   gives the low half with a zero high half.
//   Vertical: an even row's half-maxima go to the line buffer (cache_sdp_ram, synchronous read,
//   one word per output word of the row); the odd row's are combined with the buffer lane by lane
//   and leave.  An even row that is the rectangle's last (an odd number of rows) leaves directly
//   (its missing partner is the zero padding).
// Output flags: out_eol_o on an output row's last word, out_lrow_o on every word of the last
// output row.  Three register stages (p1: the combined word, its line-buffer read issued; p2: the
// line buffer's word copied beside it, so the block RAM's clock-to-out is not in series with the
// compare; out: the vertical maximum), all held by out_ready_i = 0 (in_ready_o = !out_valid_o ||
// out_ready_i: combinational only through out_ready_i).  At most one output word per two input
// words.
// Reset (rst_ni low, synchronous) empties the stage; the row and word parity also return to even
// after the last word of a rectangle, so consecutive rectangles need no clear.
module pyr_stage #(
  parameter int unsigned DATA_W   = 64,  // word width (AXI data width), a power of two >= 32
  parameter int unsigned LB_DEPTH = 128, // line buffer words: the most output words in a row (>= 2)
  parameter int unsigned LB_AW    = $clog2(LB_DEPTH)  // derived
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              b16_i,       // 1: unorm16 codes, 0: unorm8
  input  logic              in_valid_i,
  input  logic [DATA_W-1:0] in_data_i,
  input  logic              in_eol_i,
  input  logic              in_lrow_i,
  output logic              in_ready_o,
  output logic              out_valid_o,
  output logic [DATA_W-1:0] out_data_o,
  output logic              out_eol_o,
  output logic              out_lrow_o,
  input  logic              out_ready_i
);

  localparam int unsigned HW = DATA_W / 2;   // half a word

  if (DATA_W < 32 || (1 << $clog2(DATA_W)) != DATA_W || LB_DEPTH < 2
      || LB_AW != $clog2(LB_DEPTH)) begin : g_check
    $error("pyr_stage: DATA_W a power of two >= 32, LB_DEPTH >= 2, LB_AW derived");
  end

  // Pair maxima of one word: half a word.
  function automatic logic [HW-1:0] pair_max(input logic [DATA_W-1:0] w, input logic wide);
    logic [HW-1:0] r;
    r = '0;
    if (wide) begin
      for (int t = 0; t < DATA_W / 32; t++) begin
        r[16*t +: 16] = (w[32*t +: 16] > w[32*t+16 +: 16]) ? w[32*t +: 16] : w[32*t+16 +: 16];
      end
    end else begin
      for (int t = 0; t < DATA_W / 16; t++) begin
        r[8*t +: 8] = (w[16*t +: 8] > w[16*t+8 +: 8]) ? w[16*t +: 8] : w[16*t+8 +: 8];
      end
    end
    return r;
  endfunction

  // Lane-wise maximum of two words, as byte selects: bit i set where byte i of the maximum is
  // b's (b's lane greater; equal lanes are equal either way).  One carry chain per 16-bit lane
  // serves both widths: d = {a_hi, m, a_lo} - {b_hi, 0, b_lo} with m = !wide.  d[8] is
  // m ^ (a_lo < b_lo); with m = 1 no borrow crosses bit 8, so the top borrow d[17] is
  // a_hi < b_hi, and with m = 0 it is the 16-bit a < b.
  function automatic logic [DATA_W/8-1:0] lane_sel(input logic [DATA_W-1:0] a,
                                                   input logic [DATA_W-1:0] b, input logic wide);
    logic [DATA_W/8-1:0] s;
    /* verilator lint_off UNUSEDSIGNAL */  // only the borrows d[8] and d[17] are read
    logic [17:0]         d;
    /* verilator lint_on UNUSEDSIGNAL */
    for (int t = 0; t < DATA_W / 16; t++) begin
      d = {1'b0, a[16*t+8 +: 8], !wide, a[16*t +: 8]} - {1'b0, b[16*t+8 +: 8], 1'b0, b[16*t +: 8]};
      s[2*t]   = wide ? d[17] : !d[8];
      s[2*t+1] = d[17];
    end
    return s;
  endfunction

  logic              adv;          // the pipeline moves
  logic              acc;          // an input word is taken
  logic              completes;    // ... and completes an output word
  logic [HW-1:0]     pm;
  logic [DATA_W-1:0] word_c;       // the completed word (before the vertical maximum)
  logic              wpar_q, rpar_q;   // odd word, odd row
  logic [HW-1:0]     acc_q;            // an even word's half maxima
  logic [LB_AW-1:0]  oidx_q;           // output word within the row
  logic              p1_v_q, p1_lb_q, p1_eol_q, p1_lrow_q;
  logic [DATA_W-1:0] p1_word_q;
  logic              p2_v_q, p2_lb_q, p2_eol_q, p2_lrow_q;
  logic [DATA_W-1:0] p2_word_q, p2_buf_q;
  logic              out_v_q, out_eol_q, out_lrow_q;
  logic [DATA_W-1:0] out_word_q;
  logic [DATA_W-1:0] lb_rdata;
  logic [DATA_W/8-1:0] vsel;       // the vertical maximum's byte selects (1: the line buffer's)

  assign adv        = !out_v_q || out_ready_i;
  assign in_ready_o = adv;
  assign acc        = in_valid_i && adv;
  assign completes  = wpar_q || in_eol_i;
  assign pm         = pair_max(in_data_i, b16_i);
  assign word_c     = wpar_q ? {pm, acc_q} : {{HW{1'b0}}, pm};
  assign vsel       = lane_sel(p2_word_q, p2_buf_q, b16_i);

  cache_sdp_ram #(.DEPTH(LB_DEPTH), .WIDTH(DATA_W)) u_lb (
    .clk_i,
    .we_i   (acc && completes && !rpar_q && !in_lrow_i),
    .waddr_i(oidx_q),
    .wdata_i(word_c),
    .re_i   (acc && completes && rpar_q),
    .raddr_i(oidx_q),
    .rlane_i(1'b0),
    .rdata_o(lb_rdata)
  );

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      wpar_q  <= 1'b0;
      rpar_q  <= 1'b0;
      oidx_q  <= '0;
      p1_v_q  <= 1'b0;
      p2_v_q  <= 1'b0;
      out_v_q <= 1'b0;
    end else begin
      if (acc) begin
        wpar_q <= in_eol_i ? 1'b0 : !wpar_q;
        oidx_q <= in_eol_i ? '0 : (completes ? oidx_q + LB_AW'(1) : oidx_q);
        if (in_eol_i) rpar_q <= in_lrow_i ? 1'b0 : !rpar_q;
      end
      if (adv) begin
        p1_v_q  <= acc && completes && (rpar_q || in_lrow_i);
        p2_v_q  <= p1_v_q;
        out_v_q <= p2_v_q;
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (acc && !wpar_q) acc_q <= pm;
    if (adv) begin
      p1_word_q  <= word_c;
      p1_lb_q    <= rpar_q;
      p1_eol_q   <= in_eol_i;
      p1_lrow_q  <= in_lrow_i;
      p2_word_q  <= p1_word_q;
      p2_buf_q   <= lb_rdata;
      p2_lb_q    <= p1_lb_q;
      p2_eol_q   <= p1_eol_q;
      p2_lrow_q  <= p1_lrow_q;
      for (int i = 0; i < DATA_W / 8; i++) begin
        out_word_q[8*i +: 8] <= (p2_lb_q && vsel[i]) ? p2_buf_q[8*i +: 8] : p2_word_q[8*i +: 8];
      end
      out_eol_q  <= p2_eol_q;
      out_lrow_q <= p2_lrow_q;
    end
  end

  assign out_valid_o = out_v_q;
  assign out_data_o  = out_word_q;
  assign out_eol_o   = out_eol_q;
  assign out_lrow_o  = out_lrow_q;

endmodule
