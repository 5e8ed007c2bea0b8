// SPDX-License-Identifier: Apache-2.0
// height_cache_assert: the height cache's simulation checks (MSHR bookkeeping, fills, the reset
// sweep, the client contract), bound into every height_cache (the bind at the end of this file;
// not in synthesis).  Immediate assertions in a clocked block (the state before the clock edge;
// "disable iff (!rst_ni)" is a guard on rst_ni).  The AXI channel checks are
// cache_axi_read_assert's.
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
  input logic              s2_hit,
  input logic              s2_alloc,
  input logic [MSHRS-1:0]  mshr_busy,
  input logic [MSHRS-1:0]  mshr_match,
  input mshr_state_e       mshr_state_q [MSHRS],
  input logic [LA_W-1:0]   mshr_la_q    [MSHRS],
  input logic [QCNT_W-1:0] arq_cnt,
  input logic              fill_q,
  input logic [MIDX_W-1:0] fill_idx_q,
  input logic [LA_W-1:0]   fill_la_q
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      // MSHR bookkeeping: the queue holds only busy MSHRs, never more than MSHRS.
      mshr_count: assert (($countones(mshr_busy) <= MSHRS)
                          && (32'(arq_cnt) <= $countones(mshr_busy)))
        else $error("height_cache: MSHR / AR queue count out of range");
      fill_is_mshr_fill: assert (!fill_q || ((mshr_state_q[fill_idx_q] == MSHR_FILL)
                                             && (fill_la_q == mshr_la_q[fill_idx_q])))
        else $error("height_cache: fill without an MSHR in MSHR_FILL, or of another line");
      no_fill_in_sweep: assert (!sweep || (!fill_q && !s2_alloc))
        else $error("height_cache: a fill or an allocation during the valid bits' reset sweep");
      hit_not_in_mshr: assert (!s2_hit || !(|mshr_match))
        else $error("height_cache: a line both in the cache and in an MSHR");
      // Client contract: 16-bit texels are 2-byte aligned.
      wide_aligned: assert (!(lk_valid_i && lk_wide_i) || !lk_addr0)
        else $error("height_cache: unaligned 16-bit lookup");
      for (int i = 0; i < MSHRS; i++) begin
        for (int j = i + 1; j < MSHRS; j++) begin
          // mshr_unique
          assert (!(mshr_busy[i] && mshr_busy[j] && (mshr_la_q[i] == mshr_la_q[j])))
            else $error("height_cache: two MSHRs hold line %h", mshr_la_q[i]);
        end
      end
    end
  end

endmodule

`ifndef SYNTHESIS
bind height_cache height_cache_assert #(
  .MSHRS(MSHRS), .LA_W(LA_W), .MIDX_W(MIDX_W), .QCNT_W(QCNT_W)
) u_assert (.*, .lk_addr0(lk_addr_i[0]));
`endif
