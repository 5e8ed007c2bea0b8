// SPDX-License-Identifier: Apache-2.0
// pipe_valid_tag: the valid bit and side-band tag of a fixed-latency pipeline unit, delayed by
// DEPTH enabled clocks beside its datapath (every pipe unit of rtl/pipe and rtl/mip uses one).
// Valid clears on rst_ni low (synchronous, whatever en_i is); the tag needs no reset.
// stage_valid_o[s] is the valid bit of stage s (an operand set entered s enabled clocks ago), for
// units whose schedule shares a float unit between stages (view_calc, shade_unit, and the
// spacing checks of tex_addr and mip_level); the others leave it open.
module pipe_valid_tag #(
  parameter int unsigned TAG_W = 8,  // side-band bits carried from tag_i to tag_o
  parameter int unsigned DEPTH = 1   // latency in enabled clocks, >= 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             en_i,     // the unit's clock enable: everything advances together
  input  logic             valid_i,
  input  logic [TAG_W-1:0] tag_i,
  output logic             valid_o,
  output logic [TAG_W-1:0] tag_o,
  output logic [DEPTH:1]   stage_valid_o  // [DEPTH] is valid_o
);

  if (DEPTH < 1) begin : g_check_depth
    $error("pipe_valid_tag: DEPTH must be >= 1");
  end

  logic [DEPTH:1]   v_q;
  logic [TAG_W-1:0] tag_q [1:DEPTH];

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      v_q <= '0;
    end else if (en_i) begin
      v_q[1] <= valid_i;
      for (int s = 2; s <= DEPTH; s++) v_q[s] <= v_q[s-1];
    end
  end

  always_ff @(posedge clk_i) begin
    if (en_i) begin
      tag_q[1] <= tag_i;
      for (int s = 2; s <= DEPTH; s++) tag_q[s] <= tag_q[s-1];
    end
  end

  assign valid_o       = v_q[DEPTH];
  assign stage_valid_o = v_q;
  assign tag_o   = tag_q[DEPTH];

endmodule
