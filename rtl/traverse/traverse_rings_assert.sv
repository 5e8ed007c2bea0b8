// SPDX-License-Identifier: Apache-2.0
// traverse_rings_assert: the properties of traverse_rings, bound into every instance (the `bind`
// at the end of this file) and checked by simulation (Verilator --assert); the ray-id checks are
// also proven by `make formal` (formal/traverse_rings.sby, each ring abstracted; docs/formal.md).
// Immediate assertions.
//
//   deal_one     a ray is offered to one ring at most, and only to a ready one when it is taken;
//   take_one     one ring's result is taken at most per clock;
//   inside_wrap  a ring's count of rays inside never goes below zero (no result without its ray).
// Ray ids, with RAY_ID_W <= ID_TRACK_W (dm_pipeline's slot ids): a shadow of the ids inside
// (in_q: set when a ray is dealt, cleared when its result is taken) and of the ring each went to
// (ring_q):
//   rid_enter_free  a ray's id is not inside when it is taken: the user's obligation (ids unique
//                   in flight; in dm_pipeline the free list of slot ids);
//   rid_leave_once  a result's id is inside when the result is taken (no id leaves twice, none
//                   made up) ...
//   rid_ring        ... and it is taken from the ring the ray was dealt to: the result stream
//                   carries the granted ring's id (res_id_o = the ring's, the ring's ready);
//   rid_count       the ids inside per ring = the ring's count of rays inside (inside_q): with
//                   every ring returning each ray once, no id is lost or duplicated here.
`ifndef SYNTHESIS
module traverse_rings_assert #(
  parameter int unsigned R          = 2,
  parameter int unsigned CNT_W      = 17,
  parameter int unsigned ID_W       = 16,  // traverse_rings' RAY_ID_W
  parameter int unsigned ID_TRACK_W = 10   // the id shadow up to this ID_W
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic [R-1:0]          ray_valid_i,   // traverse_rings' r_ray_valid
  input logic [R-1:0]          res_take_i,    // r_res_valid & r_res_ready
  input logic [R-1:0]          ray_take_i,    // r_ray_valid & r_ray_ready
  input logic [R-1:0][CNT_W-1:0] inside_i,
  input logic [ID_W-1:0]       ray_id_i,      // the ray stream's id
  input logic [R-1:0][ID_W-1:0] ring_res_id_i, // r_id: each ring's result id
  input logic                  res_take_o_i,  // res_valid_o && res_ready_i
  input logic [ID_W-1:0]       res_id_i       // res_id_o
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      deal_one: assert ($onehot0(ray_valid_i))
        else $error("traverse_rings: a ray offered to several rings (%b)", ray_valid_i);
      take_one: assert ($onehot0(res_take_i))
        else $error("traverse_rings: results of several rings taken in one clock (%b)", res_take_i);
    end
  end
  // (one labelled assertion per ring: a label in a procedural loop would name several checks)
  for (genvar r = 0; r < R; r++) begin : g_wrap
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        inside_wrap: assert (!(res_take_i[r] && !ray_take_i[r] && inside_i[r] == '0))
          else $error("traverse_rings: ring %0d returned a result for no ray", r);
      end
    end
  end

  if (ID_W <= ID_TRACK_W) begin : g_ids
    localparam int unsigned NID   = 1 << ID_W;
    localparam int unsigned SEL_W = (R > 1) ? $clog2(R) : 1;
    logic [NID-1:0]            in_q;    // ids dealt whose results are not taken
    logic [NID-1:0][SEL_W-1:0] ring_q;  // the ring each id was dealt to
    logic [SEL_W-1:0]          deal_r, take_r;
    logic                      deal, take;
    always_comb begin
      deal_r = '0;
      take_r = '0;
      for (int r = 0; r < R; r++) begin
        if (ray_take_i[r]) deal_r = SEL_W'(r);
        if (res_take_i[r]) take_r = SEL_W'(r);
      end
    end
    assign deal = |ray_take_i;
    assign take = |res_take_i;
    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        in_q <= '0;
      end else begin
        if (take) in_q[ring_res_id_i[take_r]] <= 1'b0;
        if (deal) begin
          in_q[ray_id_i]   <= 1'b1;
          ring_q[ray_id_i] <= deal_r;
        end
      end
    end
    // the ids inside per ring
    logic [R-1:0][CNT_W-1:0] n_in;
    always_comb begin
      n_in = '0;
      for (int x = 0; x < NID; x++) begin
        for (int r = 0; r < R; r++) begin
          if (in_q[x] && ring_q[x] == SEL_W'(r)) n_in[r] = n_in[r] + CNT_W'(1);
        end
      end
    end
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        rid_enter_free: assert (!deal || !in_q[ray_id_i])
          else $error("traverse_rings: ray id %0d dealt while inside", ray_id_i);
        rid_leave_once: assert (!take || in_q[ring_res_id_i[take_r]])
          else $error("traverse_rings: result id %0d not inside", ring_res_id_i[take_r]);
        rid_ring:       assert (!take || (ring_q[ring_res_id_i[take_r]] == take_r
                                          && res_take_o_i && res_id_i == ring_res_id_i[take_r]))
          else $error("traverse_rings: result id %0d from ring %0d, dealt to ring %0d",
                      ring_res_id_i[take_r], take_r, ring_q[ring_res_id_i[take_r]]);
        rid_count:      assert (n_in == inside_i)
          else $error("traverse_rings: ids inside per ring differ from the rings' counts");
      end
    end
  end else begin : g_no_ids
    // Ids wider than ID_TRACK_W: no shadow; its inputs are read nowhere else.
    logic unused_ids;
    assign unused_ids = ^{ray_id_i, ring_res_id_i, res_take_o_i, res_id_i};
  end

endmodule

bind traverse_rings traverse_rings_assert #(.R(R), .CNT_W(CNT_W), .ID_W(RAY_ID_W)) u_assert (
  .clk_i, .rst_ni, .ray_valid_i(r_ray_valid), .res_take_i(r_res_valid & r_res_ready),
  .ray_take_i(r_ray_valid & r_ray_ready), .inside_i(inside_q), .ray_id_i,
  .ring_res_id_i(r_id), .res_take_o_i(res_valid_o && res_ready_i), .res_id_i(res_id_o));
`endif
