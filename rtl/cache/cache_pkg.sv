// SPDX-License-Identifier: Apache-2.0
// cache_pkg: constants shared by the height cache and its clients (the traverse unit's lookup
// port).  See height_cache.sv for the behaviour.
package cache_pkg;

  // A package's constants serve every unit; no single unit uses all of them.
  /* verilator lint_off UNUSEDPARAM */

  // Clocks from a lookup (lk_valid_i at clock c) to its answer (rs_valid_o at clock c + 3).
  // Refer to it as cache_pkg::LOOKUP_LAT (traverse_pkg has its own LOOKUP_LAT of the same value).
  localparam int unsigned LOOKUP_LAT = 3;

  // AXI4 encodings used by the read master.
  localparam logic [1:0] AXI_BURST_INCR = 2'b01;
  localparam logic [1:0] AXI_RESP_OKAY  = 2'b00;
  localparam logic [1:0] AXI_RESP_SLVERR = 2'b10;
  localparam logic [1:0] AXI_RESP_DECERR = 2'b11;
  /* verilator lint_on UNUSEDPARAM */

  // Miss status holding register (MSHR) states.
  typedef enum logic [1:0] {
    MSHR_FREE = 2'd0,  // unused
    MSHR_WAIT = 2'd1,  // allocated: AR queued or issued, beats arriving
    MSHR_FILL = 2'd2,  // all beats in, no error: the line is written into the cache this clock
    MSHR_ERR  = 2'd3   // a beat came back SLVERR/DECERR: answers lookups to the line with rs_err_o
  } mshr_state_e;

endpackage
