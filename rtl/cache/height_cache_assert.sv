// SPDX-License-Identifier: Apache-2.0
// height_cache_assert: the height cache's simulation checks (MSHR bookkeeping, fills, the reset
// sweep, the client contract), bound into every height_cache (the bind at the end of this file;
// not in synthesis).  Immediate assertions in a clocked block (the state before the clock edge;
// "disable iff (!rst_ni)" is a guard on rst_ni).  The AXI channel checks are
// cache_axi_read_assert's.  Proven by `make formal` (formal/height_cache.sby; docs/formal.md).
//
//   mshr_count         the AR queue holds busy MSHRs only, never more than MSHRS;
//   fill_is_mshr_fill  a fill writes the line of an MSHR in MSHR_FILL;
//   fill_state_once    an MSHR is in MSHR_FILL only in its fill's clock (the clock after its
//                      line's last beat): then it is free again (no MSHR kept from the free pool);
//   no_fill_in_sweep   no fill and no allocation during the valid bits' reset sweep;
//   sweep_idle         ... every MSHR is free then, and every lookup in flight is a conflict
//                      (no miss waits in stage 3);
//   hit_not_in_mshr    a line is never both in the cache and in an MSHR (so an MSHR's error
//                      needs no hit test);
//   mshr_unique        the merge rule: two busy MSHRs never hold the same line (a miss to a line
//                      an MSHR holds, or the stage-3 miss holds, allocates nothing);
//   merge_no_alloc     ... the miss waiting in stage 3 is for a line no busy MSHR holds (so its
//                      allocation is too);
//   wide_aligned       the client's 16-bit lookups are 2-byte aligned (its obligation).
module height_cache_assert
  import cache_pkg::*;
#(
  parameter int unsigned MSHRS  = 4,
  parameter int unsigned LA_W   = 27,  // line address width
  parameter int unsigned MIDX_W = 2,   // MSHR index width
  parameter int unsigned QCNT_W = 3    // MSHR count width
) (
  input logic              clk_i,
  input logic              rst_ni,
  input logic              lk_valid_i,
  input logic              lk_addr0,    // lk_addr_i[0]
  input logic              lk_wide_i,
  input logic              sweep,       // the valid bits' reset sweep
  input logic              s1_valid_q,
  input logic              s1_conflict_q,
  input logic              s2_valid_q,
  input logic              s2_conflict_q,
  input logic              s2_hit,
  input logic              s3_miss_q,
  input logic              s3_alloc,
  input logic [LA_W-1:0]   s3_la_q,
  input logic [MSHRS-1:0]  mshr_busy,
  input logic [MSHRS-1:0]  mshr_match,
  input mshr_state_e       mshr_state_q [MSHRS],
  input logic [LA_W-1:0]   mshr_la_q    [MSHRS],
  input logic [QCNT_W-1:0] arq_cnt,
  input logic              fill_q,
  input logic [MIDX_W-1:0] fill_idx_q,
  input logic [LA_W-1:0]   fill_la_q
);

  logic unique_ok, line_held, fill_once_ok;
  always_comb begin
    unique_ok    = 1'b1;
    line_held    = 1'b0;
    fill_once_ok = 1'b1;
    for (int i = 0; i < MSHRS; i++) begin
      for (int j = i + 1; j < MSHRS; j++) begin
        if (mshr_busy[i] && mshr_busy[j] && (mshr_la_q[i] == mshr_la_q[j])) unique_ok = 1'b0;
      end
      if (mshr_busy[i] && mshr_la_q[i] == s3_la_q) line_held = 1'b1;
      if (mshr_state_q[i] == MSHR_FILL && !(fill_q && 32'(fill_idx_q) == i)) fill_once_ok = 1'b0;
    end
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      // MSHR bookkeeping: the queue holds only busy MSHRs, never more than MSHRS.
      mshr_count: assert (($countones(mshr_busy) <= MSHRS)
                          && (32'(arq_cnt) <= $countones(mshr_busy)))
        else $error("height_cache: MSHR / AR queue count out of range");
      fill_is_mshr_fill: assert (!fill_q || ((mshr_state_q[fill_idx_q] == MSHR_FILL)
                                             && (fill_la_q == mshr_la_q[fill_idx_q])))
        else $error("height_cache: fill without an MSHR in MSHR_FILL, or of another line");
      no_fill_in_sweep: assert (!sweep || (!fill_q && !s3_alloc))
        else $error("height_cache: a fill or an allocation during the valid bits' reset sweep");
      sweep_idle: assert (!sweep || (mshr_busy == '0 && (!s1_valid_q || s1_conflict_q)
                                     && (!s2_valid_q || s2_conflict_q) && !s3_miss_q))
        else $error("height_cache: an MSHR busy or a lookup not a conflict during the sweep");
      hit_not_in_mshr: assert (!s2_hit || !(|mshr_match))
        else $error("height_cache: a line both in the cache and in an MSHR");
      // Client contract: 16-bit texels are 2-byte aligned.
      wide_aligned: assert (!(lk_valid_i && lk_wide_i) || !lk_addr0)
        else $error("height_cache: unaligned 16-bit lookup");
      mshr_unique: assert (unique_ok)
        else $error("height_cache: two MSHRs hold one line");
      merge_no_alloc: assert (!s3_miss_q || !line_held)
        else $error("height_cache: an MSHR allocated for a line an MSHR holds");
      fill_state_once: assert (fill_once_ok)
        else $error("height_cache: an MSHR in MSHR_FILL outside its fill's clock");
    end
  end

endmodule

`ifndef SYNTHESIS
bind height_cache height_cache_assert #(
  .MSHRS(MSHRS), .LA_W(LA_W), .MIDX_W(MIDX_W), .QCNT_W(QCNT_W)
) u_assert (.*, .lk_addr0(lk_addr_i[0]));
`endif
