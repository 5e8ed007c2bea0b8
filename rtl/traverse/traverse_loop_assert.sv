// SPDX-License-Identifier: Apache-2.0
// traverse_loop_assert: the simulation checks of traverse_loop, bound into every instance (the
// `bind` at the end of this file; not in synthesis).  Immediate assertions in a clocked block, in
// the form the formal flow's front end (Yosys read_slang) accepts ("disable iff (!rst_ni)" is a
// guard on rst_ni).
//
//   slot_counter            every stage's slot counter is (ph - s) mod D (ph = sl_q[0]);
//   no_spurious_response    a response only ever answers a request made LOOKUP_LAT clocks
//                           earlier;
//   plane_operand_in_range  f24_one_minus takes H in [+0, 1] only (f24_from_unorm gives nothing
//                           else);
//   new_ray_only_in_bubble  a new ray enters only where the last stage holds no ray or one that
//                           retires or parks;
//   live_ray_has_no_result  a ray that is not done has none of the final flags (the next state,
//                           S_NS, relies on it);
//   descent_not_admitted    the descent's node and a new (or parked) ray never take one entry in
//                           one clock (unless the descending ray parks);
//   nk0_is_n_minus_k        the address's n - k (nk0_q, made in the tail) is n minus the level
//                           of the live ray in S0 (cfg_i.n is static while rays run);
//   bits16_copy             the height conversion's width flag (bits16_q) is cfg_i.bits16
//                           whenever a height response arrives (static while rays run);
//   bdiff_operand_in_range  traverse_bdiff (boundary - u0) takes boundaries in [0, 2^15] and
//                           positions u0 in [+-0, 2^15) only, where it gives f24_add's word: the
//                           exit boundaries of a live ray in S1, the child's entry boundaries of
//                           a descent in S14;
//   check_only_live         no ray that is done has an exit check due (chkx, chky: a redo
//                           moves only a live ray; a descent that finishes, capped, sets none).
// The park queue (PARK):
//   park_no_overflow        no ray parks in a full queue (unless the head leaves in that clock);
//   park_no_underflow       no ray leaves an empty queue;
//   park_in_range           the queue's count is at most PARK_DEPTH and its head an entry;
//   park_only_not_done      only a ray at the tail that is not done parks;
//   park_old_leaves         a head that has waited PARK_MAX clocks leaves at once unless the tail
//                           holds a finished ray the result FIFO has no room for;
//   park_old_flag           the registered "waited PARK_MAX clocks" flag (pk_old) is the queue's
//                           count of them at PARK_MAX with a ray parked;
//   park_wait_bound         the clocks the head has waited, not counting those, are at most the
//                           queue's own count of them (pk_hw), and that at most PARK_MAX: no
//                           parked ray starves (each waits at most PARK_DEPTH (PARK_MAX + 1)
//                           such clocks);
//   rays_conserved          rays in the ring + parked = rays admitted - rays retired.
// Ray ids (every id leaves once; proven by formal/traverse_loop.sby with the float datapath cut,
// docs/formal.md):
//   ring_ids_distinct       no two slots of the ring or the park queue hold one id (any ID_W);
//   and with ID_W <= ID_TRACK_W a shadow of the ids in the ring or the park queue (in_ring_q: set
//   when a new ray enters the ring, cleared when it retires):
//   id_enter_free           a new ray's id (entering the ring, or straight to the result FIFO)
//                           is not in the ring: the user's obligation (ids unique in flight);
//   id_leave_once           a retiring ray's id is in the ring (no id leaves twice);
//   id_in_ring              every id of the shadow is in a slot of the ring or an entry of the
//                           park queue and every ray there has an id of the shadow (no id lost,
//                           none made up).
`ifndef SYNTHESIS
module traverse_loop_assert
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W       = 8,   // traverse_loop's ID_W
  parameter int unsigned D          = LOOP_DEPTH,  // traverse_loop's D: the ring's stages
  parameter int unsigned ID_TRACK_W = 10,  // the shadow of ids in the ring up to this ID_W
  parameter int unsigned PQ         = 1,   // park queue entries (traverse_loop's PQ)
  parameter int unsigned PARK_MAX   = 1    // traverse_loop's PARK_MAX
) (
  input logic                          clk_i,
  input logic                          rst_ni,
  input logic [$clog2(D)-1:0]          sl_i [D],           // sl_q: the stages' slot counters
  input logic                          lk_valid_i,         // lk_valid_o
  input logic                          rs_valid_i,
  input logic                          ok5_i,              // h_ok: H enters f24_one_minus
  input f24_t                          h_i,                // h_x (the plane unit's operand)
  input logic                          live0_i,            // live0_q
  input logic [LVL_W-1:0]              nk0_i,              // nk0_q
  input logic [LVL_W-1:0]              nk0_want_i,         // cfg_i.n - node_q[0].k
  input logic                          bits16_i,           // bits16_q
  input logic                          bits16_want_i,      // cfg_i.bits16
  input logic                          admit_i,            // admit: a new ray enters
  input logic                          v_last_i,           // v_q[D-1]
  input logic                          retire_i,
  input logic                          live_ns_i,          // live18 (S_NS): a live ray
  input logic                          st_ns_final_i,      // st18 (S_NS): hit, invalid, capped or err
  input logic                          down_tl_i,          // down19_q (the tail)
  input logic                          lv1_i,              // lv_q[1]: a live ray in S1
  input logic [IDX_W-1:0]              kb1_i [2],          // kbx1_q, kby1_q
  input f24_t                          uv1_i [2],          // uv_q[1]
  input logic                          dn14_i,             // dn_q[S_CB]: a descent in S14
  input logic [IDX_W-1:0]              kb14_i [2],         // kben_x14, kben_y14
  input logic [D-1:0]                  chk_i,              // chk_v: a ray with a check bit set
  input logic [D-1:0]                  done_i,             // chk_done: ... that is done
  input f24_t                          uv14_i [2],         // uv_q[S_CB]
  input logic [D-1:0]                  v_i,                // v_q: the slots holding a ray
  input logic [ID_W-1:0]               id_i [D],           // id_q: their ids
  input logic                          bypass_i,           // bypass: a new ray straight out
  input logic [ID_W-1:0]               new_id_i,
  input logic                          done_tl_i,          // done19_q (the tail)
  input logic                          res_full_i,
  input logic                          park_i,             // park
  input logic                          unpark_i,           // unpark
  input logic [$clog2(PQ+1)-1:0]       pk_cnt_i,           // pk_cnt: rays parked
  input logic [$clog2(PQ)+(PQ==1)-1:0] pk_rd_i,            // the queue's head entry
  input logic [PQ-1:0]                 pk_v_i,             // pk_v: entries holding a ray
  input logic [ID_W-1:0]               pk_id_i [PQ],       // pk_id: their ids
  input logic                          pk_old_i,           // pk_old
  input logic [$clog2(PARK_MAX+1)-1:0] pk_hw_i             // pk_hw
);

  // A boundary in [0, 2^15], a position u0 in [+-0, 2^15) (cells and u0 inside the pyramid).
  function automatic logic bound_ok(input logic [IDX_W-1:0] b);
    return b <= IDX_W'(1 << 15);
  endfunction
  function automatic logic pos_ok(input logic [7:0] se);  // a position's sign and exponent
    return (se[6:0] < 7'(63 + 15)) && (!se[7] || se[6:0] == 7'd0);
  endfunction

  // lk_d_q[i]: a request i + 1 clocks ago.
  logic [LOOKUP_LAT-1:0] lk_d_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) lk_d_q <= '0;
    else         lk_d_q <= {lk_d_q[LOOKUP_LAT-2:0], lk_valid_i};
  end

  for (genvar g = 0; g < D; g++) begin : g_sl_check
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        slot_counter: assert (32'(sl_i[g]) == (32'(sl_i[0]) + D - g) % D)
          else $error("traverse_loop: stage %0d's slot %0d, phase %0d", g, sl_i[g], sl_i[0]);
      end
    end
  end

  // The slots of the ring and then the park queue's entries.
  localparam int unsigned NA = D + PQ;
  logic            all_v  [NA];
  logic [ID_W-1:0] all_id [NA];
  always_comb begin
    for (int s = 0; s < D; s++) begin
      all_v[s]  = v_i[s];
      all_id[s] = id_i[s];
    end
    for (int e = 0; e < PQ; e++) begin
      all_v[D+e]  = pk_v_i[e];
      all_id[D+e] = pk_id_i[e];
    end
  end

  // No two slots or entries hold one id (O((D + PQ)^2) comparisons, any ID_W).
  logic ids_distinct;
  always_comb begin
    ids_distinct = 1'b1;
    for (int s = 0; s < NA; s++) begin
      for (int u = s + 1; u < NA; u++) begin
        if (all_v[s] && all_v[u] && all_id[s] == all_id[u]) ids_distinct = 1'b0;
      end
    end
  end

  // ---- the park queue --------------------------------------------------------------------------
  localparam int unsigned PHW = $clog2(PARK_MAX + 1);
  localparam int unsigned NW  = $clog2(NA + 1);
  logic           blocked;   // the tail holds a finished ray the result FIFO has no room for
  logic [PHW-1:0] w_q;       // clocks the head has waited, blocked clocks not counted
  logic [NW-1:0]  n_q;       // rays admitted - rays retired
  assign blocked = v_last_i && done_tl_i && res_full_i;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      w_q <= '0;
      n_q <= '0;
    end else begin
      w_q <= (unpark_i || pk_cnt_i == '0) ? '0 : blocked ? w_q : w_q + PHW'(1);
      n_q <= n_q + NW'(admit_i) - NW'(retire_i);
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      park_no_overflow:   assert (!park_i || unpark_i || 32'(pk_cnt_i) < PQ)
        else $error("traverse_loop: a ray parks in a full park queue");
      park_no_underflow:  assert (!unpark_i || pk_cnt_i != '0)
        else $error("traverse_loop: a parked ray leaves an empty park queue");
      park_in_range:      assert (32'(pk_cnt_i) <= PQ && 32'(pk_rd_i) < PQ)
        else $error("traverse_loop: park queue count %0d, head %0d", pk_cnt_i, pk_rd_i);
      park_only_not_done: assert (!park_i || (v_last_i && !done_tl_i))
        else $error("traverse_loop: a finished ray or no ray parks");
      park_old_leaves:    assert (!pk_old_i || blocked || unpark_i)
        else $error("traverse_loop: the park queue's head waited PARK_MAX clocks and stays");
      park_old_flag:      assert (pk_old_i == (pk_cnt_i != '0 && 32'(pk_hw_i) == PARK_MAX))
        else $error("traverse_loop: the park queue's registered PARK_MAX flag is %0d", pk_old_i);
      park_wait_bound:    assert (w_q <= pk_hw_i && 32'(pk_hw_i) <= PARK_MAX)
        else $error("traverse_loop: the park queue's head waited %0d clocks (%0d)", w_q, pk_hw_i);
      rays_conserved:     assert (32'(n_q) == 32'($countones(v_i)) + 32'(pk_cnt_i))
        else $error("traverse_loop: rays in the ring %0d + parked %0d != admitted - retired %0d",
                    $countones(v_i), pk_cnt_i, n_q);
    end
  end
  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      ring_ids_distinct: assert (ids_distinct)
        else $error("traverse_loop: two slots of the ring hold one ray id");
    end
  end

  // The shadow of the ids in the ring (2^ID_W bits: only for narrow ids, as in dm_pipeline).
  if (ID_W <= ID_TRACK_W) begin : g_ids
    localparam int unsigned NID = 1 << ID_W;
    logic [NID-1:0] in_ring_q;   // ids that entered the ring and have not retired
    logic [NID-1:0] occ;         // ids held by a slot or a park queue entry
    always_ff @(posedge clk_i) begin
      if (!rst_ni) begin
        in_ring_q <= '0;
      end else begin
        if (retire_i) in_ring_q[id_i[D-1]] <= 1'b0;
        if (admit_i)  in_ring_q[new_id_i]  <= 1'b1;
      end
    end
    always_comb begin
      for (int x = 0; x < NID; x++) begin
        occ[x] = 1'b0;
        for (int s = 0; s < NA; s++) occ[x] = occ[x] || (all_v[s] && all_id[s] == ID_W'(x));
      end
    end
    always_ff @(posedge clk_i) begin
      if (rst_ni) begin
        id_enter_free: assert (!(admit_i || bypass_i) || !in_ring_q[new_id_i])
          else $error("traverse_loop: ray id %0d enters while in the ring", new_id_i);
        id_leave_once: assert (!retire_i || in_ring_q[id_i[D-1]])
          else $error("traverse_loop: ray id %0d retires but is not in the ring", id_i[D-1]);
        id_in_ring:    assert (occ == in_ring_q)
          else $error("traverse_loop: ids in the slots differ from the ids that entered");
      end
    end
  end else begin : g_no_ids
    // Ids wider than ID_TRACK_W: no shadow; its inputs are read nowhere else.
    logic unused_ids;
    assign unused_ids = ^{bypass_i, new_id_i};
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      no_spurious_response: assert (!rs_valid_i || lk_d_q[LOOKUP_LAT-1])
        else $error("traverse_loop: height response without a request");
      plane_operand_in_range: assert (!ok5_i || (!h_i[23] && (h_i[22:16] < 7'd63 || h_i == F24_ONE)))
        else $error("traverse_loop: H = %h outside [+0, 1]", h_i);
      nk0_is_n_minus_k: assert (!live0_i || nk0_i == nk0_want_i)
        else $error("traverse_loop: S0's n - k %0d, want %0d", nk0_i, nk0_want_i);
      bits16_copy: assert (!rs_valid_i || bits16_i == bits16_want_i)
        else $error("traverse_loop: the height width flag's copy differs from cfg_i.bits16");
      new_ray_only_in_bubble: assert (!(admit_i || unpark_i) || !v_last_i || retire_i || park_i)
        else $error("traverse_loop: a new ray admitted over a ray that stays");
      live_ray_has_no_result: assert (!live_ns_i || !st_ns_final_i)
        else $error("traverse_loop: a live ray in S_NS has a final flag");
      descent_not_admitted: assert (!down_tl_i || !(admit_i || unpark_i) || park_i)
        else $error("traverse_loop: a descent and a new ray in one clock");
      bdiff_operand_in_range: assert (
          (!lv1_i || (bound_ok(kb1_i[0]) && bound_ok(kb1_i[1])
                      && pos_ok(uv1_i[0][23:16]) && pos_ok(uv1_i[1][23:16])))
          && (!dn14_i || (bound_ok(kb14_i[0]) && bound_ok(kb14_i[1])
                          && pos_ok(uv14_i[0][23:16]) && pos_ok(uv14_i[1][23:16]))))
        else $error("traverse_loop: boundary - u0 operands out of range (S1 %0d %0d %h %h, %s",
                    kb1_i[0], kb1_i[1], uv1_i[0], uv1_i[1],
                    $sformatf("S14 %0d %0d %h %h)", kb14_i[0], kb14_i[1], uv14_i[0],
                              uv14_i[1]));
      check_only_live: assert ((chk_i & done_i) == '0)
        else $error("traverse_loop: a finished ray still has an exit check due (%b)",
                    chk_i & done_i);
    end
  end

endmodule

bind traverse_loop traverse_loop_assert #(.ID_W(ID_W), .D(D), .PQ(PQ), .PARK_MAX(PARK_MAX))
u_assert (
  .clk_i, .rst_ni, .sl_i(sl_q), .lk_valid_i(lk_valid_o), .rs_valid_i, .ok5_i(h_ok),
  .h_i(h_x), .live0_i(live0_q), .nk0_i(nk0_q), .nk0_want_i(LVL_W'(cfg_i.n - node_q[0].k)),
  .bits16_i(bits16_q), .bits16_want_i(cfg_i.bits16),
  .admit_i(admit), .v_last_i(v_q[D-1]), .retire_i(retire), .live_ns_i(live18),
  .st_ns_final_i(st18.hit || st18.invalid || st18.capped || st18.err), .down_tl_i(down19_q),
  .lv1_i(lv_q[1]), .kb1_i('{kbx1_q, kby1_q}), .uv1_i('{uv_q[1].u, uv_q[1].v}),
  .dn14_i(dn_q[S_CB]), .kb14_i('{kben_x14, kben_y14}), .chk_i(chk_v), .done_i(chk_done),
  .uv14_i('{uv_q[S_CB].u, uv_q[S_CB].v}), .v_i(v_q), .id_i(id_q), .bypass_i(bypass),
  .new_id_i, .done_tl_i(done19_q), .res_full_i, .park_i(park), .unpark_i(unpark),
  .pk_cnt_i(pk_cnt), .pk_rd_i(pk_rd), .pk_v_i(pk_v), .pk_id_i(pk_id), .pk_old_i(pk_old),
  .pk_hw_i(pk_hw));
`endif
