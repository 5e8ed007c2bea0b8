// SPDX-License-Identifier: Apache-2.0
// pipe_f0_formal: the admission of dm_pipeline into view_calc and FIFO #0 under SymbiYosys
// (formal/pipe_f0.sby), wired as rtl/pipe/dm_pipeline.sv wires it: a fragment is accepted when
// it is offered, the free list has a slot, the unit is not filling its free list, the credit
// (u_f0_credit: LIMIT = F0_DEPTH, held_i = FIFO #0's fill) has room and no fragment was accepted
// in the 3 clocks before; view_calc's valid and tag travel in its pipe_valid_tag (LAT =
// VIEW_CALC_LAT, en_i = 1); what comes out is written into FIFO #0 (traverse_fifo, RAM_STYLE
// "block") without looking at full_o; traverse_system reads the head whenever it is ready.  The
// datapath around is left out: its words are the tag (free here).
// Everything outside is free (offers, slot availability, the free-list fill, traverse_system's
// ready, reset after the first clock).  Proven: the bound properties of the three modules with
// no assumption on their inputs, among them FIFO #0's no_overflow (no write while full) and the
// credit's within_limit (in view_calc + in FIFO #0 <= F0_DEPTH).  credit_in_flight below is the
// lemma that ties the two counts together (the credit's count is the number of fragments inside
// view_calc), what the induction step needs beside the modules' own invariants.
module pipe_f0_formal
  import pipe_pkg::*;
#(
  parameter int unsigned F0_DEPTH = 16,             // FIFO #0 (dm_pipeline's F0_DEPTH)
  parameter int unsigned LAT      = VIEW_CALC_LAT,  // view_calc's latency
  parameter int unsigned W        = 4               // tag bits (the properties do not depend on it)
) (
  input logic         clk_i,
  input logic         rst_ni,
  input logic         frag_valid_i,  // a fragment is offered
  input logic         init_i,        // dm_pipeline's init_q: filling the free list
  input logic         free_empty_i,  // no free slot
  input logic         ray_ready_i,   // traverse_system takes a ray
  input logic [W-1:0] tag_i          // the fragment's tag (slot id and data)
);

  localparam int unsigned F0_CW = $clog2(F0_DEPTH) + 1;

  logic             acc, f0_room, vc_valid, f0_wr, f0_rd, f0_full, f0_empty;
  logic [2:0]       acc_q;           // [k]: a fragment was accepted k + 1 clocks ago
  logic [W-1:0]     vc_tag, f0_head;
  logic [F0_CW-1:0] vc_cnt, f0_count;
  logic [LAT:1]     vc_stage;

  always_ff @(posedge clk_i) begin
    if (!rst_ni) acc_q <= '0;
    else         acc_q <= {acc_q[1:0], acc};
  end
  assign acc = frag_valid_i && !init_i && !free_empty_i && f0_room && acc_q == '0;

  pipe_valid_tag #(.TAG_W(W), .DEPTH(LAT)) u_view (
    .clk_i, .rst_ni, .en_i(1'b1), .valid_i(acc), .tag_i, .valid_o(vc_valid), .tag_o(vc_tag),
    .stage_valid_o(vc_stage));

  pipe_credit #(.LIMIT(F0_DEPTH), .CW(F0_CW)) u_f0_credit (
    .clk_i, .rst_ni, .take_i(acc), .give_i(vc_valid), .held_i(f0_count), .room_o(f0_room),
    .count_o(vc_cnt));

  assign f0_wr = vc_valid;
  assign f0_rd = !f0_empty && ray_ready_i;

  traverse_fifo #(.W(W), .DEPTH(F0_DEPTH), .RAM_STYLE("block")) u_fifo0 (
    .clk_i, .rst_ni, .wr_i(f0_wr), .wr_data_i(vc_tag), .rd_i(f0_rd), .rd_data_o(f0_head),
    .full_o(f0_full), .empty_o(f0_empty), .count_o(f0_count));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // The lemma: the credit counts exactly the fragments inside view_calc.
  logic [F0_CW-1:0] n_view;
  always_comb begin
    n_view = '0;
    for (int s = 1; s <= LAT; s++) n_view = n_view + F0_CW'(vc_stage[s]);
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      credit_in_flight: assert (vc_cnt == n_view);
      c_f0_full_read:   cover (f0_full && f0_rd);
    end
  end

  logic unused;
  assign unused = ^{f0_head};

endmodule
