// SPDX-License-Identifier: Apache-2.0
// height_rom: a stand-in for the height cache in tests: a byte memory that answers every lookup
// exactly traverse_pkg::LOOKUP_LAT (3) clocks later, on the traverse unit's lookup interface
// (slave side).
//
// - The memory image (model.heightmap.Pyramid.memory_image()) is written through a 32-bit port
//   (word address, little-endian bytes) before use.
// - Lookups: byte address lk_addr_i - base_i; lk_wide_i = 1 reads a little-endian 16-bit code.
//   An address outside the 2^AW bytes (or an odd address for a 16-bit read) answers rs_err_o.
// - Random misses: a lookup answers rs_hit_o = 0 when a free-running 16-bit LFSR is below
//   miss_thresh_i (miss probability about miss_thresh_i / 65536; 0 = always hit), to exercise the
//   traverse unit's retry path as a non-blocking cache miss would.
module height_rom #(
  parameter int unsigned AW = 18  // memory size 2^AW bytes
) (
  input  logic        clk_i,
  input  logic        rst_ni,
  input  logic [31:0] base_i,
  input  logic [15:0] miss_thresh_i,
  // load port
  input  logic        wr_en_i,
  input  logic [AW-3:0] wr_addr_i,  // 32-bit word address
  input  logic [31:0] wr_data_i,
  // lookups
  input  logic        lk_valid_i,
  input  logic [31:0] lk_addr_i,
  input  logic        lk_wide_i,
  output logic        rs_valid_o,
  output logic        rs_hit_o,
  output logic        rs_err_o,
  output logic [15:0] rs_data_o
);

  if (AW < 3 || AW > 31) begin : g_check_aw
    $error("height_rom: AW must be in 3..31");
  end

  logic [31:0] mem_q [2**(AW-2)];

  always_ff @(posedge clk_i) begin
    if (wr_en_i) mem_q[wr_addr_i] <= wr_data_i;
  end

  // Galois LFSR x^16 + x^14 + x^13 + x^11 + 1 (period 2^16 - 1).
  logic [15:0] lfsr_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) lfsr_q <= 16'hACE1;
    else         lfsr_q <= {1'b0, lfsr_q[15:1]} ^ (lfsr_q[0] ? 16'hB400 : 16'h0000);
  end

  // Clock 1: decode.
  logic [31:0]   off;
  logic          v1_q, hit1_q, err1_q, wide1_q;
  logic [AW-1:0] a1_q;
  assign off = lk_addr_i - base_i;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) v1_q <= 1'b0;
    else         v1_q <= lk_valid_i;
  end
  always_ff @(posedge clk_i) begin
    a1_q    <= off[AW-1:0];
    wide1_q <= lk_wide_i;
    err1_q  <= (off >> AW) != '0 || (lk_wide_i && off[0]);
    hit1_q  <= lfsr_q >= miss_thresh_i;
  end

  // Clock 2: read (a 16-bit code is aligned, so both bytes are in one word); clocks 3 ..
  // LOOKUP_LAT: the answer {valid, err, hit, data} delayed to the traverse unit's latency.
  localparam int unsigned LAT = traverse_pkg::LOOKUP_LAT;
  if (LAT < 2) begin : g_check_lat
    $error("height_rom: needs traverse_pkg::LOOKUP_LAT >= 2 (decode, read)");
  end
  logic [31:0] w1;
  logic [7:0]  b0, b1;
  logic [LAT-2:0] v_q;            // v_q[i]: the answer of clock i + 2 is valid
  logic [17:0]    ans_q [LAT-1];  // {err, hit, data}, clocks 2 .. LAT
  assign w1 = mem_q[a1_q[AW-1:2]];
  assign b0 = w1[8*a1_q[1:0] +: 8];
  assign b1 = w1[8*{a1_q[1], 1'b1} +: 8];
  always_ff @(posedge clk_i) begin
    if (!rst_ni) v_q <= '0;
    else         v_q <= (LAT-1)'({v_q, v1_q});  // shift in at bit 0
  end
  always_ff @(posedge clk_i) begin
    ans_q[0] <= {err1_q, hit1_q && !err1_q, wide1_q ? b1 : 8'd0, b0};
    for (int i = 1; i < LAT - 1; i++) ans_q[i] <= ans_q[i-1];
  end
  assign rs_valid_o = v_q[LAT-2];
  assign {rs_err_o, rs_hit_o, rs_data_o} = ans_q[LAT-2];

endmodule
