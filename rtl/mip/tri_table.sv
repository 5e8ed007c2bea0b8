// SPDX-License-Identifier: Apache-2.0
// tri_table: the per-triangle constants of the MIP-level unit, log2(Pb) of each triangle for the
// two textures (colour, normal map), as f24 words (model/mip.py: table_words; the driver writes
// the f24 rounding of model.camera.log2_pb for each texture's resolution).
//
// Two simple dual-port memories of TRIS words (one per texture), each with one write port and
// one registered read port: the shape of a LUT RAM / block RAM.
//   write: on a clock edge with we_i = 1, word waddr_i = {triangle, texture} takes wdata_i
//          (texture bit 0 = colour, 1 = normal map).  Independent of re_i: configuration writes
//          happen while the pipeline is stalled or idle.
//   read:  on a clock edge with re_i = 1 (the pipeline's en_i), both words of triangle raddr_i
//          are loaded into the output registers (latency TRI_TABLE_LAT = 1, pipe_pkg); the
//          outputs hold while re_i = 0.  A read of the word written on the same edge returns
//          the old word (the table is configuration: static while the pipeline is busy).
// Triangle ids at or beyond TRIS (possible when TRIS is not a power of two) read +0 and their
// writes are ignored.  No reset: the table holds whatever was last written (X after power-up
// in simulation until written).
module tri_table
  import f24_pkg::*;
#(
  parameter int unsigned TRIS  = 16,                          // triangles (entries per texture)
  parameter int unsigned TRI_W = (TRIS > 1) ? $clog2(TRIS) : 1  // triangle id width
) (
  input  logic             clk_i,
  // configuration write port
  input  logic             we_i,
  input  logic [TRI_W:0]   waddr_i,         // {triangle id, texture}: texture 0 colour, 1 normal
  input  f24_t             wdata_i,         // log2(Pb) as f24
  // read port (registered)
  input  logic             re_i,            // read enable (the pipeline's clock enable)
  input  logic [TRI_W-1:0] raddr_i,         // triangle id
  output f24_t             rdata_colour_o,  // log2(Pb) of the colour texture, 1 clock after
  output f24_t             rdata_normal_o   // log2(Pb) of the normal map
);

  if (TRIS < 1 || TRIS > (1 << TRI_W)) begin : g_check
    $error("tri_table: TRIS must be in 1 .. 2^TRI_W");
  end

  f24_t mem_c [TRIS];   // colour texture
  f24_t mem_n [TRIS];   // normal map
  f24_t rd_c_q, rd_n_q;

  logic [TRI_W-1:0] wtri;
  logic             wtex;
  logic             w_in, r_in;  // the addressed triangle exists
  assign wtri = waddr_i[TRI_W:1];
  assign wtex = waddr_i[0];

  if (TRIS == (1 << TRI_W)) begin : g_full  // every id addresses a word
    assign w_in = 1'b1;
    assign r_in = 1'b1;
  end else begin : g_part
    assign w_in = ({1'b0, wtri} < (TRI_W + 1)'(TRIS));
    assign r_in = ({1'b0, raddr_i} < (TRI_W + 1)'(TRIS));
  end

  always_ff @(posedge clk_i) begin
    if (we_i && w_in && !wtex) mem_c[wtri] <= wdata_i;
    if (we_i && w_in && wtex)  mem_n[wtri] <= wdata_i;
  end

  always_ff @(posedge clk_i) begin
    if (re_i) begin
      rd_c_q <= r_in ? mem_c[raddr_i] : '0;
      rd_n_q <= r_in ? mem_n[raddr_i] : '0;
    end
  end

  assign rdata_colour_o = rd_c_q;
  assign rdata_normal_o = rd_n_q;

endmodule
