// SPDX-License-Identifier: Apache-2.0
// traverse_setup (formal model only; formal/traverse_unit.sby reads this file instead of
// rtl/traverse/traverse_setup.sv): the setup pipeline abstracted to what traverse_unit relies on
// for its ray ids and credits.  A ray enters when the unit offers it (in_valid_i, only while
// in_ready_o) and leaves LAT clocks later with its id; busy_o counts the rays inside.  That is
// the guarantee the real pipeline's proof gives (formal/traverse_setup.sby: setup_id_order,
// out_when_in; there LAT = setup_lat(ADD_LAT, MUL_LAT), 26 stages).  Here LAT is small, so the
// unit's credit check is proven with a setup FIFO of a few entries; the check does not depend
// on the latency, only on busy_o counting the rays inside.  in_ready_o (the real pipeline's
// phase, one clock in four) is a free choice every clock.  The ray out is 0: traverse_unit
// carries it without reading it (the FIFOs' own proofs show that any word comes out in order),
// and free words in the FIFOs' RAMs cost the solver more than three times the time.
module traverse_setup
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W    = 8,
  parameter int unsigned ADD_LAT = pipe_pkg::F24_ADD_LAT,  // (unused: the real pipeline's)
  parameter int unsigned MUL_LAT = pipe_pkg::F24_MUL_LAT,  // (unused)
  parameter int unsigned LAT     = 3                       // clocks from a ray in to it out
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,
  /* verilator lint_off UNUSEDSIGNAL */
  input  cfg_t                    cfg_i,
  input  logic                    idle_i,
  /* verilator lint_on UNUSEDSIGNAL */
  output logic                    in_ready_o,
  input  logic                    in_valid_i,
  input  logic [ID_W-1:0]         in_id_i,
  /* verilator lint_off UNUSEDSIGNAL */
  input  f24_t                    in_u0_i,
  input  f24_t                    in_v0_i,
  input  f24_t                    in_du_i,
  input  f24_t                    in_dv_i,
  /* verilator lint_on UNUSEDSIGNAL */
  output logic                    out_valid_o,
  output logic [ID_W-1:0]         out_id_o,
  output ray_t                    out_ray_o,
  output logic [SETUP_BUSY_W-1:0] busy_o
);

  // Free choices: undriven nets, free inputs every clock under SymbiYosys (nets, not
  // variables: read_slang gives an undriven variable the constant x).
  wire  rdy_en;   // the pipeline's phase lets a ray in

  logic [LAT-1:0]           v_q;
  logic [LAT-1:0][ID_W-1:0] id_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      v_q <= '0;
    end else begin
      v_q <= {v_q[LAT-2:0], in_valid_i};
    end
    id_q <= {id_q[LAT-2:0], in_id_i};
  end

  assign in_ready_o  = rdy_en;
  assign out_valid_o = v_q[LAT-1];
  assign out_id_o    = id_q[LAT-1];
  assign out_ray_o   = '0;
  assign busy_o      = SETUP_BUSY_W'($countones(v_q));

endmodule
