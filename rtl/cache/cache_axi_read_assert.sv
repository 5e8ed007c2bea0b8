// SPDX-License-Identifier: Apache-2.0
// cache_axi_read_assert: the AXI checks of every cache_axi_read (the height cache's and the texture
// cache's), bound into it (the bind at the end of this file; not in synthesis), checked by
// simulation (Verilator --assert) and proven by `make formal` (formal/cache_axi_read.sby;
// docs/formal.md).  Immediate assertions in a clocked block (the state before the clock edge);
// "disable iff (!rst_ni)" is a guard on rst_ni, "a |=> b" a guard on registered copies of the
// clock before.
//
// A shadow of every MSHR's read, from the ports: pend (allocated, its AR not yet accepted), out
// (its AR accepted in this epoch, its line's last beat not yet accepted), the beats accepted of
// its line and whether one of them carried an error.  Reset clears it (reads issued before a
// reset are another epoch's: their beats are not the current epoch's and never accepted).
//
//   alloc_free          the cache allocates only an MSHR that has no read (neither pend nor
//                       out), with an index below MSHRS, one lane per MSHR (the cache's
//                       obligation: the formal wrapper assumes it);
//   r_acc_ours          the cache accepts only a beat of the current epoch naming an MSHR (its
//                       obligation);
//   ar_stable           the AR payload holds and arvalid stays up until the handshake;
//   ar_once             an AR handshake is for an MSHR that is pend, in the current epoch: one
//                       read per allocation, none for an MSHR not allocated;
//   r_outstanding       no beat is accepted but for an MSHR whose read is out;
//   r_beat_expected     a beat of the current epoch belongs to an MSHR waiting for its line;
//   rlast_on_last_beat  rlast marks exactly the last beat of each of the cache's bursts;
//   r_count             r_beat_o is the number of beats accepted on the MSHR's line (so its
//                       last beat, the MSHR's answer, comes once per read, after BEATS beats);
//   r_err_marks         r_bad_o is 1 exactly when this beat or an earlier one of the line
//                       carried SLVERR / DECERR (an error marks its line).
`ifndef SYNTHESIS
module cache_axi_read_assert #(
  parameter int unsigned ADDR_W = 32,  // cache_axi_read's parameters
  parameter int unsigned ID_W   = 4,
  parameter int unsigned MSHRS  = 4,
  parameter int unsigned NPUSH  = 1,
  parameter int unsigned BEATS  = 4,   // cache_axi_read's derived widths
  parameter int unsigned BEAT_W = 2,
  parameter int unsigned MIDX_W = 2
) (
  input logic                         clk_i,
  input logic                         rst_ni,
  input logic [NPUSH-1:0]             alloc_i,
  input logic [NPUSH-1:0][MIDX_W-1:0] alloc_idx_i,
  input logic [ID_W-MIDX_W-1:0]       epoch_q,    // the reset epoch
  input logic [ID_W-1:0]              m_axi_arid,
  input logic [ADDR_W-1:0]            m_axi_araddr,
  input logic [7:0]                   m_axi_arlen,
  input logic [2:0]                   m_axi_arsize,
  input logic [1:0]                   m_axi_arburst,
  input logic                         m_axi_arvalid,
  input logic                         m_axi_arready,
  input logic                         rresp_err_i,  // m_axi_rresp[1]: SLVERR / DECERR
  input logic                         m_axi_rlast,
  input logic [MIDX_W-1:0]            r_idx_o,    // the beat's MSHR
  input logic                         r_cur_o,    // rvalid, of the current epoch
  input logic                         r_ours_o,   // ... naming an MSHR
  input logic                         r_acc_i,    // the cache accepts the beat
  input logic [BEAT_W-1:0]            r_beat_o,   // its index in the line
  input logic                         r_last_o,   // the beat is its line's last by the count
  input logic                         r_bad_o     // the line has an error
);

  localparam int unsigned EPOCH_W = ID_W - MIDX_W;
  localparam int unsigned AR_W    = ID_W + ADDR_W + 8 + 3 + 2;

  logic            p_rst_q, p_ar_wait_q;
  logic [AR_W-1:0] p_ar_q;
  always_ff @(posedge clk_i) begin
    p_rst_q     <= rst_ni;
    p_ar_wait_q <= m_axi_arvalid && !m_axi_arready;
    p_ar_q      <= {m_axi_arid, m_axi_araddr, m_axi_arlen, m_axi_arsize, m_axi_arburst};
  end

  // ---- the shadow of the reads -------------------------------------------------------------
  logic [MSHRS-1:0]             pend_q, out_q, err_q;
  logic [MSHRS-1:0][BEAT_W-1:0] nbeat_q;
  logic                         ar_hs;
  logic [MIDX_W-1:0]            ar_idx;
  logic [EPOCH_W-1:0]           ar_epoch;
  assign ar_hs    = m_axi_arvalid && m_axi_arready;
  assign ar_idx   = m_axi_arid[MIDX_W-1:0];
  assign ar_epoch = m_axi_arid[ID_W-1:MIDX_W];

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      pend_q  <= '0;
      out_q   <= '0;
      err_q   <= '0;
      nbeat_q <= '0;
    end else begin
      for (int m = 0; m < MSHRS; m++) begin
        if (r_acc_i && 32'(r_idx_o) == m) begin
          nbeat_q[m] <= r_last_o ? '0 : nbeat_q[m] + BEAT_W'(1);
          err_q[m]   <= !r_last_o && (err_q[m] || rresp_err_i);
          if (r_last_o) out_q[m] <= 1'b0;
        end
        if (ar_hs && 32'(ar_idx) == m) begin
          pend_q[m] <= 1'b0;
          out_q[m]  <= 1'b1;
        end
        for (int k = 0; k < NPUSH; k++) begin
          if (alloc_i[k] && 32'(alloc_idx_i[k]) == m) pend_q[m] <= 1'b1;
        end
      end
    end
  end

  // the cache's obligations, evaluated per lane
  logic alloc_ok;
  always_comb begin
    alloc_ok = 1'b1;
    for (int k = 0; k < NPUSH; k++) begin
      if (alloc_i[k]) begin
        if (32'(alloc_idx_i[k]) >= MSHRS) alloc_ok = 1'b0;
        else if (pend_q[alloc_idx_i[k]] || out_q[alloc_idx_i[k]]) alloc_ok = 1'b0;
        for (int j = 0; j < k; j++) begin
          if (alloc_i[j] && alloc_idx_i[j] == alloc_idx_i[k]) alloc_ok = 1'b0;
        end
      end
    end
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      alloc_free: assert (alloc_ok)
        else $error("%m: an MSHR allocated while its read is pending or out");
      r_acc_ours: assert (!r_acc_i || r_ours_o)
        else $error("%m: a beat accepted that is not the current epoch's or names no MSHR");
      // AR: the payload holds and arvalid stays up until the handshake.
      if (p_rst_q && p_ar_wait_q) begin
        ar_stable: assert (m_axi_arvalid && p_ar_q == {m_axi_arid, m_axi_araddr, m_axi_arlen,
                                                       m_axi_arsize, m_axi_arburst})
          else $error("%m: AR dropped or changed before arready");
      end
      ar_once: assert (!ar_hs || (32'(ar_idx) < MSHRS && pend_q[ar_idx] && ar_epoch == epoch_q))
        else $error("%m: AR for an MSHR without an allocation waiting for it (or of another epoch)");
      r_outstanding: assert (!r_acc_i || (32'(r_idx_o) < MSHRS && out_q[r_idx_o]))
        else $error("%m: beat accepted for an MSHR whose read is not out");
      // rlast marks exactly the last beat of each of the cache's bursts.
      rlast_on_last_beat: assert (!r_acc_i || m_axi_rlast == r_last_o)
        else $error("%m: rlast on a beat other than the last");
      // A beat carrying the current epoch belongs to an MSHR waiting for its line.
      r_beat_expected: assert (!r_cur_o || r_acc_i)
        else $error("%m: R beat for no outstanding read");
      r_count: assert (!r_acc_i || (r_beat_o == nbeat_q[r_idx_o]
                                    && r_last_o == (nbeat_q[r_idx_o] == BEAT_W'(BEATS - 1))))
        else $error("%m: beat %0d of the line counted as %0d", nbeat_q[r_idx_o], r_beat_o);
      r_err_marks: assert (!r_acc_i || r_bad_o == (err_q[r_idx_o] || rresp_err_i))
        else $error("%m: the line's error bit disagrees with the beats' responses");
    end
  end

endmodule

bind cache_axi_read cache_axi_read_assert #(
  .ADDR_W(ADDR_W), .ID_W(ID_W), .MSHRS(MSHRS), .NPUSH(NPUSH), .BEATS(BEATS), .BEAT_W(BEAT_W),
  .MIDX_W(MIDX_W)
) u_assert (.*, .rresp_err_i(m_axi_rresp[1]));
`endif
