// SPDX-License-Identifier: Apache-2.0
// traverse_rings_assert: the properties of traverse_rings, bound into every instance (the `bind`
// at the end of this file) and checked by simulation (Verilator --assert).  Immediate assertions.
//
//   deal_one     a ray is offered to one ring at most, and only to a ready one when it is taken;
//   take_one     one ring's result is taken at most per clock;
//   inside_wrap  a ring's count of rays inside never goes below zero (no result without its ray).
`ifndef SYNTHESIS
module traverse_rings_assert #(
  parameter int unsigned R     = 2,
  parameter int unsigned CNT_W = 17
) (
  input logic                  clk_i,
  input logic                  rst_ni,
  input logic [R-1:0]          ray_valid_i,   // traverse_rings' r_ray_valid
  input logic [R-1:0]          res_take_i,    // r_res_valid & r_res_ready
  input logic [R-1:0]          ray_take_i,    // r_ray_valid & r_ray_ready
  input logic [R-1:0][CNT_W-1:0] inside_i
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      deal_one: assert ($onehot0(ray_valid_i))
        else $error("traverse_rings: a ray offered to several rings (%b)", ray_valid_i);
      take_one: assert ($onehot0(res_take_i))
        else $error("traverse_rings: results of several rings taken in one clock (%b)", res_take_i);
      for (int r = 0; r < R; r++) begin
        inside_wrap: assert (!(res_take_i[r] && !ray_take_i[r] && inside_i[r] == '0))
          else $error("traverse_rings: ring %0d returned a result for no ray", r);
      end
    end
  end

endmodule

bind traverse_rings traverse_rings_assert #(.R(R), .CNT_W(CNT_W)) u_assert (
  .clk_i, .rst_ni, .ray_valid_i(r_ray_valid), .res_take_i(r_res_valid & r_res_ready),
  .ray_take_i(r_ray_valid & r_ray_ready), .inside_i(inside_q));
`endif
