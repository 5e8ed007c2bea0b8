// SPDX-License-Identifier: Apache-2.0
// dm_pipeline_pairs_formal: the pairing of a pixel's texture results in dm_pipeline under
// SymbiYosys (the pairs tasks of formal/dm_pipeline.sby): tex_filter's results come as colour,
// normal map, the normal-map result for the pixel of the colour result before it (the bound
// dm_pipeline_assert's tf_pairs, what the pairing into shade_unit relies on).  dm_pipeline is
// the top (every input free); this checker is bound into it here, for formal only.
//
// The request FIFOs, the alternating request select (rq_sel_q, pair_slot_q) and tex_filter
// (its valid and tag pipeline; its float datapath feeds only the cut shade_unit) are the real
// ones, and so is the skid buffer in front of the cache (u_rq_skid); tex_cache is
// formal/tex_cache_abs.sv (responses in request order with their tags, the real cache's proven
// rsp_tag_order), and the units in front (view_calc, traverse_rings,
// mip_level, tex_addr) and shade_unit are black boxes cut to free outputs, so the request FIFOs
// are written whenever and with whatever the solver likes.
// Assumed: reset in the first clock; resets may come again at any time.
//
// Induction invariant (inv_pairs): the texture lookups in flight, oldest first (the filter's
// stages from its output back, then the cache's requests from the oldest, then the skid
// buffer's two registers), continue the alternation where the filter's output left it
// (dm_pipeline_assert's tf_col_pend_q, tf_col_slot_q): a normal-map entry for the pending
// colour's slot, then colour, normal-map pairs of one slot each, and at the newest end a colour
// entry without its normal map exactly when the request select is at the normal map (rq_sel_q),
// for the slot it keeps (pair_slot_q); and the abstract cache's queue pointers agree with its
// count.
`ifdef FORMAL
module dm_pipeline_pairs_formal #(
  parameter int unsigned SLOTS  = 4,    // dm_pipeline's SLOTS
  parameter int unsigned TC_CAP = 3,    // the abstract cache's CAP
  parameter int unsigned TF_LAT = 15    // tex_filter's stages: u_filter's latency at the depths
                                        // dm_pipeline builds it at (the package's: TEX_FILTER_LAT;
                                        // a TF_LAT one short fails the induction)
) (
  input logic clk_i,
  input logic rst_ni
);

  localparam int unsigned SLOT_W = $clog2(SLOTS);
  localparam int unsigned TC_W   = SLOT_W + 1 + 48;   // the cache tag {slot, normal?, fx, fy}
  localparam int unsigned TF_W   = SLOT_W + 2;        // the filter tag {slot, normal?, err}
  localparam int unsigned PW     = $clog2(TC_CAP);

  logic started_q;   // 0 in the first clock only, rst_ni low in it (formal_reset)
  formal_reset u_reset (.clk_i, .rst_ni, .started_o(started_q));
  logic ok;
  always_comb begin
    logic              pend;   // a colour entry waits for its normal map
    logic [SLOT_W-1:0] slot;   // its slot
    logic              nmap;
    logic [SLOT_W-1:0] s;
    logic              valid;
    logic [TF_W-1:0]   ft;
    logic [TC_W-1:0]   ct;
    pend = dm_pipeline.u_assert.tf_col_pend_q;
    slot = dm_pipeline.u_assert.tf_col_slot_q;
    ok   = 1'b1;
    // the lookups from the oldest on: the filter's stages (S_TF_LAT down to S1), then the
    // abstract cache's queue from its head, then the requests in the skid buffer (its output
    // register, then its skid register); each must continue the alternation
    for (int j = 0; j <= TF_LAT + TC_CAP + 1; j++) begin
      if (j < TF_LAT) begin
        valid = dm_pipeline.u_filter.u_valid_tag.v_q[TF_LAT - j];
        ft    = dm_pipeline.u_filter.u_valid_tag.tag_q[TF_LAT - j];
        nmap  = ft[1];
        s     = ft[TF_W-1 -: SLOT_W];
      end else if (j < TF_LAT + TC_CAP) begin
        valid = j - TF_LAT < int'(dm_pipeline.u_tc.cnt_q);
        ct    = dm_pipeline.u_tc.q_tag_q[(int'(dm_pipeline.u_tc.rp_q) + j - TF_LAT) % TC_CAP];
        nmap  = ct[48];
        s     = ct[TC_W-1 -: SLOT_W];
      end else if (j == TF_LAT + TC_CAP) begin   // the skid buffer's output register
        valid = dm_pipeline.tc_req_valid;
        nmap  = dm_pipeline.tc_req[dm_pipeline.RS_W-1];
        s     = dm_pipeline.tc_req[dm_pipeline.REQ_W +: SLOT_W];
      end else begin   // its skid register {normal?, slot, request}
        valid = dm_pipeline.u_rq_skid.full_q;
        nmap  = dm_pipeline.u_rq_skid.data_q[dm_pipeline.RS_W-1];
        s     = dm_pipeline.u_rq_skid.data_q[dm_pipeline.REQ_W +: SLOT_W];
      end
      if (valid) begin
        if (pend) ok = ok && nmap && s == slot;
        else      ok = ok && !nmap;
        pend = !nmap;
        slot = s;
      end
    end
    ok = ok && pend == dm_pipeline.rq_sel_q && (!pend || slot == dm_pipeline.pair_slot_q);
    // the abstract cache's queue is well formed
    ok = ok && int'(dm_pipeline.u_tc.rp_q) < TC_CAP && int'(dm_pipeline.u_tc.cnt_q) <= TC_CAP
         && int'(dm_pipeline.u_tc.wp_q)
            == (int'(dm_pipeline.u_tc.rp_q) + int'(dm_pipeline.u_tc.cnt_q)) % TC_CAP;
  end

  always_comb begin
    if (rst_ni) begin
      inv_pairs: assert (ok);
    end
  end

  // Covers: a pixel's normal-map result leaves the filter; two pixels' pairs back to back in
  // the filter (a normal-map result with the next colour result two clocks behind it).
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      c_pair_out:  cover (dm_pipeline.tf_valid && dm_pipeline.tf_tag[1]);
      c_pair_next: cover (dm_pipeline.tf_valid && dm_pipeline.tf_tag[1]
                          && dm_pipeline.u_filter.u_valid_tag.v_q[TF_LAT - 2]
                          && !dm_pipeline.u_filter.u_valid_tag.tag_q[TF_LAT - 2][1]);
    end
  end

endmodule

bind dm_pipeline dm_pipeline_pairs_formal #(
  .SLOTS(SLOTS), .TF_LAT(pipe_pkg::TEX_FILTER_LAT)
) u_formal (.clk_i, .rst_ni);
`endif
