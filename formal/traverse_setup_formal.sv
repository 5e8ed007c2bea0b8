// SPDX-License-Identifier: Apache-2.0
// traverse_setup_formal: the traverse unit's setup pipeline (traverse_setup) under SymbiYosys
// (formal/traverse_setup.sby), for its ray ids: the properties are the bound
// traverse_setup_assert's (setup_id_order, trk_in_setup, ray_phase, ray_spacing) and the wrapper's
//   out_when_in  a ray comes out exactly NS = setup_lat(ADD_LAT, MUL_LAT) clocks after a ray went
//                in (none lost, none made up).
// The float datapath is cut: the script makes the ray setup computes (out_ray_o) a free value,
// so the id path is proven alone, whatever the arithmetic.  Free: the rays (ids, fields), the
// configuration, idle_i.  Assumed: a ray only while in_ready_o (ray_phase, the unit's
// admission), reset in the first clock and at any time after.
module traverse_setup_formal
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W    = 5,
  parameter int unsigned ADD_LAT = pipe_pkg::F24_ADD_LAT,  // traverse_setup's ADD_LAT, MUL_LAT
  parameter int unsigned MUL_LAT = pipe_pkg::F24_MUL_LAT
) (
  input logic            clk_i,
  input logic            rst_ni,
  input cfg_t            cfg_i,
  input logic            idle_i,
  input logic            in_valid_i,
  input logic [ID_W-1:0] in_id_i,
  input f24_t            in_u0_i,
  input f24_t            in_v0_i,
  input f24_t            in_du_i,
  input f24_t            in_dv_i
);

  logic                    in_ready;
  logic                    out_valid;
  logic [ID_W-1:0]         out_id;
  ray_t                    out_ray;
  logic [SETUP_BUSY_W-1:0] busy;

  localparam int unsigned NS = setup_lat(ADD_LAT, MUL_LAT);  // the setup's latency

  traverse_setup #(.ID_W(ID_W), .ADD_LAT(ADD_LAT), .MUL_LAT(MUL_LAT)) u_dut (
    .clk_i, .rst_ni, .cfg_i, .idle_i, .in_valid_i, .in_id_i, .in_u0_i, .in_v0_i, .in_du_i,
    .in_dv_i, .in_ready_o(in_ready), .out_valid_o(out_valid), .out_id_o(out_id),
    .out_ray_o(out_ray), .busy_o(busy));

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));

  // the rays in of the last NS clocks
  logic [NS-1:0] in_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) in_q <= '0;
    else         in_q <= {in_q[NS-2:0], in_valid_i};
  end

  always_comb begin
    assume (!in_valid_i || in_ready);
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      out_when_in: assert (out_valid == in_q[NS-1] && u_dut.v_q == in_q
                           && 32'(busy) == 32'($countones(in_q)));
      c_out:       cover (out_valid && u_dut.u_assert.trk_out);
      c_busy:      cover (busy == SETUP_BUSY_W'(NS / 4));  // rays 4 clocks apart
    end
  end

endmodule
