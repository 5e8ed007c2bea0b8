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
//                           retires;
//   live_ray_has_no_result  a ray that is not done has none of the final flags (S17 relies on
//                           it);
//   descent_not_admitted    the descent's node and a new ray never take one entry in one clock;
//   bdiff_operand_in_range  traverse_bdiff (boundary - u0) takes boundaries in [0, 2^15] and
//                           positions u0 in [+-0, 2^15) only, where it gives f24_add's word: the
//                           exit boundaries of a live ray in S1, the child's boundaries of a
//                           descent in S14.
// Ray ids (every id leaves once; proven by formal/traverse_loop.sby with the float datapath cut,
// docs/formal.md):
//   ring_ids_distinct       no two slots of the ring hold one id (any ID_W);
//   and with ID_W <= ID_TRACK_W a shadow of the ids in the ring (in_ring_q: set when a ray
//   enters the ring, cleared when it retires):
//   id_enter_free           a new ray's id (entering the ring, or straight to the result FIFO)
//                           is not in the ring: the user's obligation (ids unique in flight);
//   id_leave_once           a retiring ray's id is in the ring (no id leaves twice);
//   id_in_ring              every id of the shadow is in a slot of the ring and every ray in
//                           the ring has an id of the shadow (no id lost, none made up).
`ifndef SYNTHESIS
module traverse_loop_assert
  import f24_pkg::*;
  import traverse_pkg::*;
#(
  parameter int unsigned ID_W       = 8,   // traverse_loop's ID_W
  parameter int unsigned ID_TRACK_W = 10   // the shadow of ids in the ring up to this ID_W
) (
  input logic                          clk_i,
  input logic                          rst_ni,
  input logic [$clog2(LOOP_DEPTH)-1:0] sl_i [LOOP_DEPTH],  // sl_q: the stages' slot counters
  input logic                          lk_valid_i,         // lk_valid_o
  input logic                          rs_valid_i,
  input logic                          ok5_i,              // ok_q[5]: H enters f24_one_minus
  input f24_t                          h_i,                // h
  input logic                          admit_i,            // admit: a new ray enters
  input logic                          v_last_i,           // v_q[D-1]
  input logic                          retire_i,
  input logic                          live17_i,
  input logic                          st17_final_i,       // st17: hit, invalid, capped or err
  input logic                          down18_i,           // down18_q
  input logic                          lv1_i,              // lv_q[1]: a live ray in S1
  input logic [IDX_W-1:0]              kb1_i [2],          // kbx1_q, kby1_q
  input f24_t                          uv1_i [2],          // uv_q[1]
  input logic                          dn14_i,             // dn_q[14]: a descent in S14
  input logic [IDX_W-1:0]              kb14_i [4],         // kben_x14, kbex_x14, kben_y14, kbex_y14
  input f24_t                          uv14_i [2],         // uv_q[14]
  input logic [LOOP_DEPTH-1:0]         v_i,                // v_q: the slots holding a ray
  input logic [ID_W-1:0]               id_i [LOOP_DEPTH],  // id_q: their ids
  input logic                          bypass_i,           // bypass: a new ray straight out
  input logic [ID_W-1:0]               new_id_i
);

  localparam int unsigned D = LOOP_DEPTH;

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

  // No two slots hold one id (O(D^2) comparisons, any ID_W).
  logic ids_distinct;
  always_comb begin
    ids_distinct = 1'b1;
    for (int s = 0; s < D; s++) begin
      for (int u = s + 1; u < D; u++) begin
        if (v_i[s] && v_i[u] && id_i[s] == id_i[u]) ids_distinct = 1'b0;
      end
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
    logic [NID-1:0] occ;         // ids held by a slot
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
        for (int s = 0; s < D; s++) occ[x] = occ[x] || (v_i[s] && id_i[s] == ID_W'(x));
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
      new_ray_only_in_bubble: assert (!admit_i || !v_last_i || retire_i)
        else $error("traverse_loop: a new ray admitted over a ray that stays");
      live_ray_has_no_result: assert (!live17_i || !st17_final_i)
        else $error("traverse_loop: a live ray in S17 has a final flag");
      descent_not_admitted: assert (!down18_i || !admit_i)
        else $error("traverse_loop: a descent and a new ray in one clock");
      bdiff_operand_in_range: assert (
          (!lv1_i || (bound_ok(kb1_i[0]) && bound_ok(kb1_i[1])
                      && pos_ok(uv1_i[0][23:16]) && pos_ok(uv1_i[1][23:16])))
          && (!dn14_i || (bound_ok(kb14_i[0]) && bound_ok(kb14_i[1]) && bound_ok(kb14_i[2])
                          && bound_ok(kb14_i[3]) && pos_ok(uv14_i[0][23:16])
                          && pos_ok(uv14_i[1][23:16]))))
        else $error("traverse_loop: boundary - u0 operands out of range (S1 %0d %0d %h %h, %s",
                    kb1_i[0], kb1_i[1], uv1_i[0], uv1_i[1],
                    $sformatf("S14 %0d %0d %0d %0d %h %h)", kb14_i[0], kb14_i[1], kb14_i[2],
                              kb14_i[3], uv14_i[0], uv14_i[1]));
    end
  end

endmodule

bind traverse_loop traverse_loop_assert #(.ID_W(ID_W)) u_assert (
  .clk_i, .rst_ni, .sl_i(sl_q), .lk_valid_i(lk_valid_o), .rs_valid_i, .ok5_i(ok_q[5]), .h_i(h),
  .admit_i(admit), .v_last_i(v_q[LOOP_DEPTH-1]), .retire_i(retire), .live17_i(live17),
  .st17_final_i(st17.hit || st17.invalid || st17.capped || st17.err), .down18_i(down18_q),
  .lv1_i(lv_q[1]), .kb1_i('{kbx1_q, kby1_q}), .uv1_i('{uv_q[1].u, uv_q[1].v}), .dn14_i(dn_q[14]),
  .kb14_i('{kben_x14, kbex_x14, kben_y14, kbex_y14}),
  .uv14_i('{uv_q[14].u, uv_q[14].v}), .v_i(v_q), .id_i(id_q), .bypass_i(bypass),
  .new_id_i);
`endif
