// SPDX-License-Identifier: Apache-2.0
// traverse_unit_assert: the simulation checks of traverse_unit, bound into every instance (the
// `bind` at the end of this file; not in synthesis).  Immediate assertions in a clocked block, in
// the form the formal flow's front end (Yosys read_slang) accepts: "disable iff (!rst_ni)" is a
// guard on rst_ni, "a |=> b" a guard on a registered copy of a, $stable a comparison with a
// registered copy.
//
//   slot_conservation           every ray that came in is in exactly one place until it goes
//                               out (counted one bit wider than inflight_q, so an occupancy
//                               beyond MAX_INFLIGHT cannot alias);
//   setup_credits               the credit counter = rays in setup + rays in the setup FIFO
//                               (summed without wrapping), at most SETUP_FIFO_DEPTH;
//   setup_fifo_never_overflows  setup never writes the setup FIFO while full;
//   ray_in_stable / res_out_stable  stream protocol: once valid, the payload stable and valid
//                               held until the transfer.
// Ray ids, with ID_W <= ID_TRACK_W (dm_pipeline's slot ids): a shadow of the ids inside
// (in_unit_q: set when a ray is taken, cleared when its result is taken):
//   uid_enter_free              a ray's id is not inside when it is taken (the user's
//                               obligation: ids unique in flight);
//   uid_leave_once              a result's id is inside when it is taken (no id leaves twice,
//                               none made up).
// formal/traverse_unit.sby proves them, and that every id inside is in exactly one place of the
// unit (setup, its FIFO, the ring, the result FIFO), with setup and the ring abstracted to what
// their own proofs show (formal/traverse_setup_abs.sv, formal/traverse_loop_abs.sv).
`ifndef SYNTHESIS
module traverse_unit_assert
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W             = 16,  // traverse_unit's ID_W
  parameter int unsigned SETUP_FIFO_DEPTH = 32,  // traverse_unit's SETUP_FIFO_DEPTH
  parameter int unsigned RES_FIFO_DEPTH   = 16,  // traverse_unit's RES_FIFO_DEPTH
  parameter int unsigned ID_TRACK_W       = 10   // the id shadow up to this ID_W
) (
  input logic                                   clk_i,
  input logic                                   rst_ni,
  input logic [$clog2(SETUP_FIFO_DEPTH+31+RES_FIFO_DEPTH+1)-1:0] inflight_i,  // inflight_q
  input logic [SETUP_BUSY_W-1:0]                su_busy_i,
  input logic [$clog2(SETUP_FIFO_DEPTH):0]      sf_count_i,
  input logic [$clog2(SETUP_FIFO_DEPTH):0]      sf_used_i,    // sf_used_q
  input logic [LOOP_BUSY_W-1:0]                 lp_busy_i,
  input logic [$clog2(RES_FIFO_DEPTH):0]        rf_count_i,
  input logic                                   su_valid_i,
  input logic                                   sf_full_i,
  input logic                                   ray_valid_i,
  input logic                                   ray_ready_i,  // ray_ready_o
  input logic [ID_W-1:0]                        ray_id_i,
  input f24_t                                   ray_u0_i,
  input f24_t                                   ray_v0_i,
  input f24_t                                   ray_du_i,
  input f24_t                                   ray_dv_i,
  input logic                                   res_valid_i,  // res_valid_o
  input logic                                   res_ready_i,
  input logic [ID_W+$bits(result_t)-1:0]        rf_head_i,    // rf_head: the result's payload
  input logic [ID_W-1:0]                        res_id_i      // res_id_o
);

  localparam int unsigned IF_W  = $clog2(SETUP_FIFO_DEPTH + 31 + RES_FIFO_DEPTH + 1);
  localparam int unsigned RF_W  = ID_W + $bits(result_t);

  logic [IF_W:0] occupancy;
  assign occupancy = (IF_W+1)'(su_busy_i) + (IF_W+1)'(sf_count_i) + (IF_W+1)'(lp_busy_i)
                   + (IF_W+1)'(rf_count_i);

  // The clock before: the guards of "|=>" (cleared in reset) and the values $stable compares.
  logic                      ray_wait_q, res_wait_q;
  logic [ID_W+4*24-1:0]      ray_q;
  logic [RF_W-1:0]           rf_head_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      ray_wait_q <= 1'b0;
      res_wait_q <= 1'b0;
    end else begin
      ray_wait_q <= ray_valid_i && !ray_ready_i;
      res_wait_q <= res_valid_i && !res_ready_i;
    end
    ray_q     <= {ray_id_i, ray_u0_i, ray_v0_i, ray_du_i, ray_dv_i};
    rf_head_q <= rf_head_i;
  end

  if (ID_W <= ID_TRACK_W) begin : g_ids
    localparam int unsigned NID = 1 << ID_W;
    logic [NID-1:0] in_unit_q;   // ids taken whose results are not
    logic           in_fire, out_fire;
    assign in_fire  = ray_valid_i && ray_ready_i;
    assign out_fire = res_valid_i && res_ready_i;
    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        in_unit_q <= '0;
      end else begin
        if (out_fire) in_unit_q[res_id_i] <= 1'b0;
        if (in_fire)  in_unit_q[ray_id_i] <= 1'b1;
      end
    end
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        uid_enter_free: assert (!in_fire || !in_unit_q[ray_id_i])
          else $error("traverse_unit: ray id %0d taken while inside", ray_id_i);
        uid_leave_once: assert (!out_fire || in_unit_q[res_id_i])
          else $error("traverse_unit: result id %0d not inside", res_id_i);
      end
    end
  end else begin : g_no_ids
    // Ids wider than ID_TRACK_W: no shadow; its inputs are read nowhere else.
    logic unused_ids;
    assign unused_ids = ^{res_id_i};
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      slot_conservation: assert ((IF_W+1)'(inflight_i) == occupancy)
        else $error("traverse_unit: rays in (%0d) != rays out + in flight (%0d)", inflight_i,
                    occupancy);
      setup_credits: assert (32'(sf_used_i) == 32'(su_busy_i) + 32'(sf_count_i)
                             && 32'(sf_used_i) <= SETUP_FIFO_DEPTH)
        else $error("traverse_unit: setup credits %0d != rays in setup %0d + setup FIFO %0d",
                    sf_used_i, su_busy_i, sf_count_i);
      setup_fifo_never_overflows: assert (!su_valid_i || !sf_full_i)
        else $error("traverse_unit: setup FIFO written while full");
      ray_in_stable: assert (!ray_wait_q
                             || (ray_valid_i && {ray_id_i, ray_u0_i, ray_v0_i, ray_du_i, ray_dv_i}
                                                == ray_q))
        else $error("traverse_unit: ray stream changed while waiting for ray_ready_o");
      res_out_stable: assert (!res_wait_q || (res_valid_i && rf_head_i == rf_head_q))
        else $error("traverse_unit: result stream changed while waiting for res_ready_i");
    end
  end

endmodule

bind traverse_unit traverse_unit_assert #(.ID_W(ID_W), .SETUP_FIFO_DEPTH(SETUP_FIFO_DEPTH),
                                          .RES_FIFO_DEPTH(RES_FIFO_DEPTH)) u_assert (
  .clk_i, .rst_ni, .inflight_i(inflight_q), .su_busy_i(su_busy), .sf_count_i(sf_count),
  .sf_used_i(sf_used_q), .lp_busy_i(lp_busy), .rf_count_i(rf_count), .su_valid_i(su_valid),
  .sf_full_i(sf_full), .ray_valid_i, .ray_ready_i(ray_ready_o), .ray_id_i, .ray_u0_i, .ray_v0_i,
  .ray_du_i, .ray_dv_i, .res_valid_i(res_valid_o), .res_ready_i, .rf_head_i(rf_head),
  .res_id_i(res_id_o));
`endif
