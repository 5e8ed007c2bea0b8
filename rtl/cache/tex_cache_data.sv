// SPDX-License-Identifier: Apache-2.0
// tex_cache_data: the texture cache's data RAMs and answer path (tex_cache.sv, "Pipeline" clocks
// 5 .. 8): the registered R beats written into the sub-caches' RAMs (w_*_i), the head pass's
// windows read every clock (hd_*_i; used the clock after a pop, h_pop_i), the RAMs' words
// registered, the texels selected and merged with the earlier passes of the request, and the
// output buffer (OUT_DEPTH answers) that drives the response stream.  out_room_o: the buffer
// has room for one more pass's answer besides those already popped.
module tex_cache_data #(
  parameter int unsigned DATA_W    = 64,  // AXI data width (<= 32 * WW)
  parameter int unsigned TAG_W     = 8,   // side-band width
  parameter int unsigned SETS      = 32,  // sets per sub-cache
  parameter int unsigned WAYS      = 4,   // ways per set
  parameter int unsigned WW        = 2,   // words per data window (a power of two)
  parameter int unsigned NWIN      = 4,   // windows per line
  parameter int unsigned BEAT_W    = 2,   // beat index width
  parameter int unsigned OUT_DEPTH = 4,   // output buffer entries (4: pointers of 2 bits)
  parameter int unsigned TQ_DEPTH  = 128, // tag queue entries (a power of two >= 2): more than
                                          // the requests that can be accepted and not answered
  // derived (tex_cache's values)
  parameter int unsigned SET_W     = $clog2(SETS),
  parameter int unsigned WAY_W     = $clog2(WAYS),
  parameter int unsigned WIN_W     = (NWIN > 1) ? $clog2(NWIN) : 1,
  parameter int unsigned TOFF_W    = $clog2(WW) + 1         // word in a read window, 0 .. WW
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,
  // an accepted request's side-band tag (in request order)
  input  logic                       tq_push_i,
  input  logic [TAG_W-1:0]           tq_tag_i,
  // the registered R beat: written into its sub-cache's RAM at its slot and window
  input  logic                       w_acc_i,
  input  logic [1:0]                 w_sub_i,
  input  logic [SET_W-1:0]           w_set_i,
  input  logic [WAY_W-1:0]           w_way_i,
  input  logic [BEAT_W-1:0]          w_beat_i,
  input  logic [DATA_W-1:0]          w_data_i,
  // the head pass: its slots and windows, texels and answer
  input  logic [3:0][SET_W-1:0]      hd_set_i,
  input  logic [3:0][WAY_W-1:0]      hd_way_i,
  input  logic [3:0][WIN_W-1:0]      hd_win_i,
  input  logic [3:0]                 hd_tsel_i,
  input  logic [3:0][1:0]            hd_tsub_i,
  input  logic [3:0][TOFF_W-1:0]     hd_toff_i,
  input  logic                       hd_last_i,
  input  logic                       hd_err_i,     // a line of the pass came back with an error
  input  logic                       h_pop_i,      // the head pass leaves the FIFO
  output logic                       out_room_o,
  // responses
  output logic                       rsp_valid_o,
  input  logic                       rsp_ready_i,
  output logic [3:0][31:0]           rsp_texel_o,
  output logic                       rsp_err_o,
  output logic [TAG_W-1:0]           rsp_tag_o
);

  localparam int unsigned NSUB      = 4;                        // sub-caches
  localparam int unsigned NLANE     = WW * 32 / DATA_W;         // beats per window
  localparam int unsigned LANE_B    = (NLANE > 1) ? $clog2(NLANE) : 1;
  localparam int unsigned OVL_W     = (DATA_W < 32) ? DATA_W : 32;  // overlap-word lane width
  localparam int unsigned NOVL      = 32 / OVL_W;               // beats per overlap word
  localparam int unsigned RAM_DEPTH = SETS * WAYS * NWIN;
  localparam int unsigned RAM_AW    = $clog2(RAM_DEPTH);

  if (SET_W != $clog2(SETS) || WAY_W != $clog2(WAYS) || WIN_W != ((NWIN > 1) ? $clog2(NWIN) : 1)
      || TOFF_W != $clog2(WW) + 1) begin : g_check_derived
    $error("tex_cache_data: the derived parameters must keep their defaults");
  end
  if (OUT_DEPTH != 4 || DATA_W > 32 * WW) begin : g_check
    $error("tex_cache_data: OUT_DEPTH must be 4 and DATA_W <= 32 * WW");
  end
  if (TQ_DEPTH < 2 || (1 << $clog2(TQ_DEPTH)) != TQ_DEPTH) begin : g_check_tq
    $error("tex_cache_data: TQ_DEPTH must be a power of two >= 2");
  end

  // Head read stage (the clock after the pop: the RAMs read the lines).
  logic              h0_valid_q, h0_last_q, h0_err_q;
  logic [3:0]        h0_tsel_q;
  logic [3:0][1:0]   h0_tsub_q;
  logic [3:0][TOFF_W-1:0] h0_toff_q;
  // Select stage (the clock after: the RAMs' words in registers, ram_rd_q).
  logic              h1_valid_q, h1_last_q, h1_err_q;
  logic [3:0]        h1_tsel_q;
  logic [3:0][31:0]  acc_texel_q;  // texels of the earlier passes of the request
  logic              acc_err_q;

  // Output buffer (the answers; their tags: the tag queue).
  typedef struct packed {
    logic [3:0][31:0] texel;
    logic             err;
  } rsp_t;

  rsp_t              out_rd;     // the buffer's head (u_out)
  logic [2:0]        out_cnt;    // answers buffered

  logic out_pop;
  assign out_pop = rsp_valid_o && rsp_ready_i;

  // room in the output buffer for the result and those of the passes popped before it
  // (out_cnt - out_pop + h0_valid_q + h1_valid_q + 1 <= OUT_DEPTH, with the registers' sum
  // compared apart from the late out_pop)
  logic [2:0] out_need;
  assign out_need = out_cnt + 3'(h0_valid_q) + 3'(h1_valid_q);
  assign out_room_o = out_need < 3'(OUT_DEPTH) || (out_need == 3'(OUT_DEPTH) && out_pop);


  // ---------------------------------------------------------------- data RAMs
  // A sub-cache stores a line as NWIN windows of WW words at RAM address {set, way, window}; a
  // pass reads one window and the word after it (the overlap word, kept in a second RAM at the
  // same address: word (k + 1) * WW of the line for window k), so a horizontal pair w, w + 1 is
  // always in one read.  Each R beat is written where it belongs as it arrives, one RAM per beat
  // lane (the beat's lane of the window; the overlap RAM takes the first 32 bits of a window
  // from its beats, for the window before).  The slot is pending until the last beat, so nothing
  // reads the partial line; a line that fails keeps its partial write, which the error bit makes
  // harmless (the slot is not valid).
  logic [WIN_W-1:0]  r_win;        // the registered beat's window
  logic [LANE_B-1:0] r_lane;       // ... and its lane in the window
  logic [WW:0][31:0] ram_rd [NSUB];  // window words 0 .. WW-1, then the overlap word
  logic [WW:0][31:0] ram_rd_q [NSUB];  // ... registered (the block RAMs' 4.3 ns clock-to-out)

  function automatic logic [RAM_AW-1:0] ram_addr(input logic [SET_W-1:0] s,
                                                 input logic [WAY_W-1:0] w,
                                                 input logic [WIN_W-1:0] k);
    return RAM_AW'((32'(s) * WAYS + 32'(w)) * NWIN + ((NWIN > 1) ? 32'(k) : 0));
  endfunction

  always_comb begin
    r_win  = WIN_W'(32'(w_beat_i) / NLANE);
    r_lane = LANE_B'(32'(w_beat_i) % NLANE);
  end

  for (genvar c = 0; c < NSUB; c++) begin : g_sub
    logic [RAM_AW-1:0] waddr, raddr;
    logic              wsub, rd;
    logic [WW*32-1:0]  rd_win;      // the window's words
    logic [31:0]       rd_ovl;      // the overlap word
    assign ram_rd[c] = {rd_ovl, rd_win};
    assign wsub  = w_acc_i && w_sub_i == 2'(c);
    assign waddr = ram_addr(w_set_i, w_way_i, r_win);
    assign rd    = 1'b1;  // the head's window, every clock (used the clock after a pop)
    assign raddr = ram_addr(hd_set_i[c], hd_way_i[c], hd_win_i[c]);
    for (genvar l = 0; l < NLANE; l++) begin : g_lane
      cache_sdp_ram #(.DEPTH(RAM_DEPTH), .WIDTH(DATA_W)) u_ram (
        .clk_i   (clk_i),
        .we_i    (wsub && 32'(r_lane) == l),
        .waddr_i (waddr),
        .wdata_i (w_data_i),
        .re_i    (rd),
        .raddr_i (raddr),
        .rdata_o (rd_win[l * DATA_W +: DATA_W])
      );
    end
    if (NWIN > 1) begin : g_ovl
      for (genvar o = 0; o < NOVL; o++) begin : g_lane
        cache_sdp_ram #(.DEPTH(RAM_DEPTH), .WIDTH(OVL_W)) u_ram (
          .clk_i   (clk_i),
          .we_i    (wsub && r_win != '0 && 32'(r_lane) == o),
          .waddr_i (RAM_AW'(waddr - RAM_AW'(1))),  // the window before, same slot
          .wdata_i (w_data_i[OVL_W-1:0]),
          .re_i    (rd),
          .raddr_i (raddr),
          .rdata_o (rd_ovl[o * OVL_W +: OVL_W])
        );
      end
    end else begin : g_no_ovl
      assign rd_ovl = '0;  // a window is the whole line: offset WW is never read
    end
  end

  // ---------------------------------------------------------------- select, merge, output
  logic [3:0][31:0] h1_texel;
  rsp_t             h1_rsp;

  // The select as an AND-OR over one-hot selects decoded a clock ahead (h1_pick_q[t][c][k]:
  // texel t takes word k of sub-cache c's read; none set: the texel keeps the value of the
  // request's earlier passes).  Out of context on the ECP5 this takes ~370 LUT4 fewer than
  // multiplexers steered by the encoded sub-cache and word (a 4:1 per word, then the word), for
  // 32 more flip-flops; indexing the words with {sub-cache, word} at once built a shifter.
  logic [3:0][NSUB-1:0][WW:0] h1_pick_q;
  always_comb begin
    for (int t = 0; t < 4; t++) begin
      h1_texel[t] = h1_tsel_q[t] ? '0 : acc_texel_q[t];
      for (int c = 0; c < NSUB; c++) begin
        for (int k = 0; k <= WW; k++) begin
          h1_texel[t] = h1_texel[t] | (ram_rd_q[c][k] & {32{h1_pick_q[t][c][k]}});
        end
      end
    end
    h1_rsp.texel = h1_texel;
    h1_rsp.err   = acc_err_q || h1_err_q;
  end

  always_ff @(posedge clk_i) begin
    for (int t = 0; t < 4; t++) begin
      for (int c = 0; c < NSUB; c++) begin
        for (int k = 0; k <= WW; k++) begin
          h1_pick_q[t][c][k] <= h0_tsel_q[t] && h0_tsub_q[t] == 2'(c)
                                && 32'(h0_toff_q[t]) == k;
        end
      end
    end
  end

  logic out_push;
  assign out_push = h1_valid_q && h1_last_q;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      h0_valid_q  <= 1'b0;
      h1_valid_q  <= 1'b0;
      acc_err_q   <= 1'b0;
      acc_texel_q <= '0;
    end else begin
      h0_valid_q <= h_pop_i;
      h1_valid_q <= h0_valid_q;
      if (h1_valid_q) begin
        if (h1_last_q) begin
          acc_err_q   <= 1'b0;
          acc_texel_q <= '0;
        end else begin
          acc_err_q   <= h1_rsp.err;
          acc_texel_q <= h1_texel;
        end
      end
    end
    // (loaded every clock, like the data RAMs' read: they matter only where h0_valid_q and
    // h1_valid_q say a popped pass is; so the pop, late in its clock, enables none of them)
    h0_last_q  <= hd_last_i;
    h0_err_q   <= hd_err_i;
    h0_tsel_q  <= hd_tsel_i;
    h0_tsub_q  <= hd_tsub_i;
    h0_toff_q  <= hd_toff_i;
    h1_last_q  <= h0_last_q;
    h1_err_q   <= h0_err_q;
    h1_tsel_q  <= h0_tsel_q;
    ram_rd_q   <= ram_rd;
  end

  // The output buffer: 129 bits an entry, in LUT RAM (33 16x4 RAMs; in block RAM it took 4 EBRs
  // and, for the read of an entry pushed in the clock before, about as many LUTs in a copy of
  // the written entry and its multiplexer).
  circ_queue #(
    .WIDTH($bits(rsp_t)), .DEPTH(OUT_DEPTH), .NPUSH(1), .NPOP(1), .RAM_STYLE("distributed")
  ) u_out (
    .clk_i, .rst_ni, .push_i(out_push), .wr_i(out_push), .wdata_i(h1_rsp), .pop_n_i(out_pop),
    .rdata_o(out_rd), .peek_o(), .count_o(out_cnt));

  assign rsp_valid_o = (out_cnt != '0);
  assign rsp_texel_o = out_rd.texel;
  assign rsp_err_o   = out_rd.err;

  // ---------------------------------------------------------------- request tags
  // The side-band tags wait in a queue of their own, in request order (pushed as a request is
  // accepted, popped with its answer), so that they pass neither through the pass queue and the
  // FIFO (per pass) nor through the answer path.  Block RAM, read through its registered port
  // every clock at the queue's head after this clock's pop, so rsp_tag_o comes from the RAM's
  // read register.  No read of the entry written in the same clock is ever used: a request is
  // answered 9 clocks after its handshake at the earliest, so its tag has been in the RAM for 8
  // clocks when its answer reaches the buffer's head (tex_cache_assert checks the distance).
  localparam int unsigned TQ_W = $clog2(TQ_DEPTH);
  (* ram_style = "block", no_rw_check *) logic [TAG_W-1:0] tq_mem [TQ_DEPTH];
  logic [TQ_W-1:0]  tq_wp_q, tq_rp_q, tq_rp_d;
  logic [TAG_W-1:0] tq_rd_q;

  assign tq_rp_d = tq_rp_q + TQ_W'(out_pop);

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      tq_wp_q <= '0;
      tq_rp_q <= '0;
    end else begin
      if (tq_push_i) tq_wp_q <= tq_wp_q + TQ_W'(1);
      tq_rp_q <= tq_rp_d;
    end
    if (tq_push_i) tq_mem[tq_wp_q] <= tq_tag_i;
    tq_rd_q <= tq_mem[tq_rp_d];
  end

  assign rsp_tag_o = tq_rd_q;

endmodule
