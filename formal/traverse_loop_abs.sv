// SPDX-License-Identifier: Apache-2.0
// traverse_loop (formal model only; formal/traverse_unit.sby reads this file instead of
// rtl/traverse/traverse_loop.sv): the ring abstracted to what traverse_unit relies on for its
// ray ids.  It holds up to CAP rays (their ids).  In a clock it may take the setup FIFO's head
// (new_pop_o, only when the FIFO is not empty) into a free slot or into the slot of the ray
// retiring in that clock, and it may push one result (res_push_o, only when the result FIFO is
// not full): a ray it holds (retire), or the FIFO's head straight through (bypass: a ray that
// setup finished, popped and pushed in one clock).  Which, and when, are free choices.  That is
// the guarantee of the real ring (formal/traverse_loop.sby: id_enter_free, id_leave_once,
// id_in_ring, res_id_source, res_once; res_push_o and new_pop_o carry !res_full_i and
// new_valid_i in their definitions).  The result's other fields are 0 (traverse_unit carries
// them without reading them), the height lookups idle, the statistics strobes 0.
module traverse_loop
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W       = 8,
  parameter int unsigned MUL_LAT    = pipe_pkg::F24_MUL_LAT,  // (unused: the real ring's)
  parameter bit          XOR_PATH   = 1'b1,                   // (unused)
  parameter bit          PARK       = 1'b0,                   // (unused)
  parameter int unsigned PARK_DEPTH = PARK_DEPTH_DEF, // (unused)
  parameter int unsigned PARK_WAIT  = 16,                     // (unused)
  parameter int unsigned PARK_MAX   = 4 * loop_depth(MUL_LAT), // (unused)
  parameter int unsigned CAP        = 2                       // rays held
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  /* verilator lint_off UNUSEDSIGNAL */
  input  cfg_t              cfg_i,
  input  logic              hlt_we_i,     // the level-offset table's write port (unused here)
  input  logic [LVL_W-1:0]  hlt_waddr_i,
  input  logic [ADDR_W-1:0] hlt_wdata_i,
  /* verilator lint_on UNUSEDSIGNAL */
  input  logic              new_valid_i,
  input  logic [ID_W-1:0]   new_id_i,
  /* verilator lint_off UNUSEDSIGNAL */
  input  ray_t              new_ray_i,
  /* verilator lint_on UNUSEDSIGNAL */
  output logic              new_pop_o,
  input  logic              res_full_i,
  output logic              res_push_o,
  output logic [ID_W-1:0]   res_id_o,
  output result_t           res_o,
  output logic              lk_valid_o,
  output logic [ADDR_W-1:0] lk_addr_o,
  output logic              lk_wide_o,
  /* verilator lint_off UNUSEDSIGNAL */
  input  logic              rs_valid_i,
  input  logic              rs_hit_i,
  input  logic              rs_err_i,
  input  logic [CODE_W-1:0] rs_data_i,
  /* verilator lint_on UNUSEDSIGNAL */
  output logic              st_iter_o,
  output logic              st_down_o,
  output logic              st_cross_o,
  output logic              st_up_o,
  output logic [LOOP_BUSY_W-1:0] busy_o
);

  localparam int unsigned KW = (CAP > 1) ? $clog2(CAP) : 1;

  // Free choices: undriven nets (see formal/traverse_setup_abs.sv).
  wire          take_en;   // take the FIFO's head if there is room
  wire          ret_en;    // retire a held ray
  wire          byp_en;    // pass the FIFO's head straight to the result FIFO
  wire [KW-1:0] pick;      // which held ray retires

  logic [CAP-1:0]           h_v_q;   // slot k holds a ray
  logic [CAP-1:0][ID_W-1:0] h_id_q;

  logic retire, bypass, admit, room;
  logic [KW-1:0] fk;   // the slot a new ray takes
  always_comb begin
    retire = ret_en && 32'(pick) < CAP && h_v_q[pick] && !res_full_i;
    bypass = !retire && byp_en && new_valid_i && !res_full_i;
    // the first free slot, else the one retiring now
    room = 1'b0;
    fk   = pick;
    for (int k = CAP - 1; k >= 0; k--) begin
      if (!h_v_q[k]) begin
        room = 1'b1;
        fk   = KW'(k);
      end
    end
    admit = !bypass && take_en && new_valid_i && (room || retire);
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      h_v_q <= '0;
    end else begin
      if (retire) h_v_q[pick] <= 1'b0;
      if (admit) begin
        h_v_q[fk]  <= 1'b1;
        h_id_q[fk] <= new_id_i;
      end
    end
  end

  assign new_pop_o  = admit || bypass;
  assign res_push_o = retire || bypass;
  assign res_id_o   = retire ? h_id_q[pick] : new_id_i;
  assign res_o      = '0;
  assign lk_valid_o = 1'b0;
  assign lk_addr_o  = '0;
  assign lk_wide_o  = 1'b0;
  assign {st_iter_o, st_down_o, st_cross_o, st_up_o} = '0;
  assign busy_o     = LOOP_BUSY_W'($countones(h_v_q));

endmodule
