// SPDX-License-Identifier: Apache-2.0
// ring_probe: a measurement-only module (never synthesised, not in any RTL directory) bound into
// dm_pipeline with N_RINGS = 1 by scripts/bench/ring_probe.py (an extra source of a pipeline
// harness build of its own).  It reads dm_pipeline's and the traverse ring's
// internal signals through the bind's hierarchical port connections and counts, in every clock
// with a pixel inside the unit (dm_pipeline's !idle_o, the clocks the bench's clock count spans):
//
//   what the slot leaving the ring's tail (stage D-1, into S0) carries:
//     ring_new        a new ray from setup (admit)
//     ring_recirc     a ray that is not done, going round again
//     ring_blocked    a finished ray that cannot leave (the result FIFO is full)
//     ring_empty_*    nothing: why no new ray took the free slot
//       _sf_bypass      the setup FIFO's head is a ray setup finished (it bypasses the ring)
//       _sf_busy        the setup FIFO is empty, rays are inside traverse_setup
//       _f0_wait        setup is empty, FIFO #0 holds rays (setup's one ray per 4 clocks, or
//                       setup's credits)
//       _vc             setup and FIFO #0 are empty, fragments are inside view_calc
//       _front          setup, FIFO #0 and view_calc are all empty
//     each empty slot also by what last held the fragment input back within WINDOW clocks
//     before it (ring_empty_by_*): free slot ids exhausted (SLOTS), FIFO #0 credits, no
//     fragment offered, or none of them (the fragment input ran at its one per 4 clocks);
//   the fragment input in the clocks it may take one (not in the 3 after a fragment):
//     fe_taken, fe_no_frag, fe_no_slot, fe_no_credit;
//   the result side: res_full (the result FIFO full), res_wait_* (a result waits at the
//     traverse system's output: a hit in the 3 clocks after a hit, the texture-request FIFOs'
//     or the out FIFO's credits, the miss FIFO full), setup_credit_stall (FIFO #0 holds a ray
//     and setup is at its phase, but setup and its FIFO hold SETUP_FIFO_DEPTH rays);
//   occupancy: sums of the ring's rays, the slots in use, FIFO #0's and the setup FIFO's fill.
// The counts go to the file FILE (appended, one "name value" line each) at the end of the
// simulation (the harness's final()).
`ifndef SYNTHESIS
module ring_probe #(
  parameter int unsigned SLOT_W = 7,   // dm_pipeline's SLOT_W
  parameter int unsigned D      = 22,  // the ring's stages (traverse_pkg::LOOP_DEPTH)
  parameter int unsigned WINDOW = 64,  // clocks from the fragment input to the ring, about
  parameter string       FILE   = "ring_probe.txt"  // output file (appended)
) (
  input logic              clk_i,
  input logic              rst_ni,
  input logic              idle_i,        // dm_pipeline idle_o
  // fragment input
  input logic              init_i,        // the free list is being filled
  input logic              frag_valid_i,
  input logic              acc_i,         // a fragment is taken
  input logic [2:0]        acc_q_i,       // fragments taken 1 .. 3 clocks ago
  input logic              free_empty_i,  // no free slot id
  input logic              f0_room_i,     // FIFO #0 credit
  input logic [SLOT_W:0]   live_i,        // slots in use (SLOTS - free count)
  input logic [7:0]        vc_cnt_i,      // fragments inside view_calc
  input logic [7:0]        f0_count_i,    // FIFO #0 fill
  // traverse unit
  input logic              ray_ready_i,   // traverse unit ray_ready_o
  input logic              su_in_ready_i, // setup's phase
  input logic [7:0]        sf_used_i,     // setup credits used
  input logic [7:0]        su_busy_i,     // rays in traverse_setup
  input logic [7:0]        sf_count_i,    // setup FIFO fill
  input logic              rf_full_i,     // result FIFO full
  // ring tail
  input logic              tail_v_i,      // v_q[D-1]
  input logic              tail_done_i,   // done19_q
  input logic              new_valid_i,   // setup FIFO not empty
  input logic              new_cand_i,    // ... and its head is not done
  input logic              admit_i,
  input logic              bypass_i,
  input logic              retire_i,
  input logic [4:0]        ring_busy_i,   // rays in the ring
  // result side (dm_pipeline)
  input logic              res_valid_i,
  input logic              res_ready_i,
  input logic              res_hit_i,
  input logic              hit_spacing_i,  // the admission's grid holds a hit back
  input logic              req_room_i,
  input logic              hit_room_i,
  input logic              miss_full_i
);
  localparam int unsigned WW = $clog2(WINDOW + 1);
  longint unsigned busy, ring_new, ring_recirc, ring_blocked, ring_retire;
  longint unsigned e_bypass, e_sf_busy, e_f0_wait, e_vc, e_front;
  longint unsigned by_slots, by_credit, by_nofrag, by_rate;
  longint unsigned fe_elig, fe_taken, fe_no_frag, fe_no_slot, fe_no_credit;
  longint unsigned res_full, res_wait_spacing, res_wait_req, res_wait_out, res_wait_miss;
  longint unsigned setup_credit_stall, f0_wait_phase;
  longint unsigned sum_ring, sum_live, sum_f0, sum_sf, sum_su;
  logic [WW-1:0] since_slot_q, since_credit_q, since_nofrag_q;  // clocks since the input was
                                                                  // last held back by each

  logic elig, empty_slot;
  assign elig       = !init_i && acc_q_i == '0;
  assign empty_slot = (!tail_v_i || retire_i) && !admit_i;

  initial begin
    busy = 0; ring_new = 0; ring_recirc = 0; ring_blocked = 0; ring_retire = 0;
    e_bypass = 0; e_sf_busy = 0; e_f0_wait = 0; e_vc = 0; e_front = 0;
    by_slots = 0; by_credit = 0; by_nofrag = 0; by_rate = 0;
    fe_elig = 0; fe_taken = 0; fe_no_frag = 0; fe_no_slot = 0; fe_no_credit = 0;
    res_full = 0; res_wait_spacing = 0; res_wait_req = 0; res_wait_out = 0; res_wait_miss = 0;
    setup_credit_stall = 0; f0_wait_phase = 0;
    sum_ring = 0; sum_live = 0; sum_f0 = 0; sum_sf = 0; sum_su = 0;
  end

  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      since_slot_q   <= WW'(WINDOW);
      since_credit_q <= WW'(WINDOW);
      since_nofrag_q <= WW'(WINDOW);
    end else begin
      // the fragment input, held back in an eligible clock (first reason in this order)
      since_slot_q   <= (elig && free_empty_i) ? '0
                        : (since_slot_q < WW'(WINDOW)) ? since_slot_q + 1'b1 : since_slot_q;
      since_credit_q <= (elig && !free_empty_i && !f0_room_i) ? '0
                        : (since_credit_q < WW'(WINDOW)) ? since_credit_q + 1'b1 : since_credit_q;
      since_nofrag_q <= (elig && !free_empty_i && f0_room_i && !frag_valid_i && !idle_i) ? '0
                        : (since_nofrag_q < WW'(WINDOW)) ? since_nofrag_q + 1'b1 : since_nofrag_q;
      if (!idle_i) begin
        busy <= busy + 1;
        sum_ring <= sum_ring + 64'(ring_busy_i);
        sum_live <= sum_live + 64'(live_i);
        sum_f0   <= sum_f0 + 64'(f0_count_i);
        sum_sf   <= sum_sf + 64'(sf_count_i);
        sum_su   <= sum_su + 64'(su_busy_i);
        if (retire_i) ring_retire <= ring_retire + 1;
        if (admit_i) ring_new <= ring_new + 1;
        else if (tail_v_i && !tail_done_i) ring_recirc <= ring_recirc + 1;
        else if (tail_v_i && tail_done_i && !retire_i) ring_blocked <= ring_blocked + 1;
        if (empty_slot) begin
          if (new_valid_i && !new_cand_i) e_bypass <= e_bypass + 1;
          else if (su_busy_i != '0) e_sf_busy <= e_sf_busy + 1;
          else if (f0_count_i != '0) e_f0_wait <= e_f0_wait + 1;
          else if (vc_cnt_i != '0) e_vc <= e_vc + 1;
          else e_front <= e_front + 1;
          if (since_slot_q < WW'(WINDOW)) by_slots <= by_slots + 1;
          else if (since_credit_q < WW'(WINDOW)) by_credit <= by_credit + 1;
          else if (since_nofrag_q < WW'(WINDOW)) by_nofrag <= by_nofrag + 1;
          else by_rate <= by_rate + 1;
        end
        if (elig) begin
          fe_elig <= fe_elig + 1;
          if (acc_i) fe_taken <= fe_taken + 1;
          else if (free_empty_i) fe_no_slot <= fe_no_slot + 1;
          else if (!f0_room_i) fe_no_credit <= fe_no_credit + 1;
          else fe_no_frag <= fe_no_frag + 1;
        end
        if (rf_full_i) res_full <= res_full + 1;
        if (res_valid_i && !res_ready_i) begin
          if (!res_hit_i) res_wait_miss <= res_wait_miss + 1;
          else if (hit_spacing_i) res_wait_spacing <= res_wait_spacing + 1;
          else if (!req_room_i) res_wait_req <= res_wait_req + 1;
          else res_wait_out <= res_wait_out + 1;
        end
        if (f0_count_i != '0 && su_in_ready_i && !ray_ready_i) setup_credit_stall <= setup_credit_stall + 1;
        if (f0_count_i != '0 && !su_in_ready_i) f0_wait_phase <= f0_wait_phase + 1;
      end
    end
  end

  // (read only in a waveform of the probe build)
  logic unused;
  assign unused = hit_room_i ^ bypass_i ^ miss_full_i ^ (sf_used_i != '0);

  final begin
    int fd;
    fd = $fopen(FILE, "a");
    if (fd != 0) begin
      $fwrite(fd, "busy %0d\nring_new %0d\nring_recirc %0d\nring_blocked %0d\nring_retire %0d\n",
              busy, ring_new, ring_recirc, ring_blocked, ring_retire);
      $fwrite(fd, "ring_empty_sf_bypass %0d\nring_empty_sf_busy %0d\nring_empty_f0_wait %0d\n",
              e_bypass, e_sf_busy, e_f0_wait);
      $fwrite(fd, "ring_empty_vc %0d\nring_empty_front %0d\n", e_vc, e_front);
      $fwrite(fd, "ring_empty_by_slots %0d\nring_empty_by_credit %0d\nring_empty_by_nofrag %0d\n",
              by_slots, by_credit, by_nofrag);
      $fwrite(fd, "ring_empty_by_rate %0d\n", by_rate);
      $fwrite(fd, "fe_elig %0d\nfe_taken %0d\nfe_no_frag %0d\nfe_no_slot %0d\nfe_no_credit %0d\n",
              fe_elig, fe_taken, fe_no_frag, fe_no_slot, fe_no_credit);
      $fwrite(fd, "res_full %0d\nres_wait_spacing %0d\nres_wait_req %0d\nres_wait_out %0d\n",
              res_full, res_wait_spacing, res_wait_req, res_wait_out);
      $fwrite(fd, "res_wait_miss %0d\nsetup_credit_stall %0d\nf0_wait_phase %0d\n",
              res_wait_miss, setup_credit_stall, f0_wait_phase);
      $fwrite(fd, "sum_ring %0d\nsum_live %0d\nsum_f0 %0d\nsum_sf %0d\nsum_su %0d\n",
              sum_ring, sum_live, sum_f0, sum_sf, sum_su);
      $fclose(fd);
    end
  end
endmodule

bind dm_pipeline ring_probe #(.SLOT_W(SLOT_W), .D(traverse_pkg::LOOP_DEPTH)) u_ring_probe (
  .clk_i, .rst_ni, .idle_i(idle_o),
  .init_i(init_q), .frag_valid_i, .acc_i(acc), .acc_q_i(acc_q), .free_empty_i(free_empty),
  .f0_room_i(f0_room), .live_i(live_q), .vc_cnt_i(8'(vc_cnt)), .f0_count_i(8'(f0_count)),
  .ray_ready_i(u_trav.g_ring[0].u_sys.u_unit.ray_ready_o),
  .su_in_ready_i(u_trav.g_ring[0].u_sys.u_unit.su_in_ready),
  .sf_used_i(8'(u_trav.g_ring[0].u_sys.u_unit.sf_used_q)),
  .su_busy_i(8'(u_trav.g_ring[0].u_sys.u_unit.su_busy)),
  .sf_count_i(8'(u_trav.g_ring[0].u_sys.u_unit.sf_count)),
  .rf_full_i(u_trav.g_ring[0].u_sys.u_unit.rf_full),
  .tail_v_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.v_q[traverse_pkg::LOOP_DEPTH-1]),
  .tail_done_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.done19_q),
  .new_valid_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.new_valid_i),
  .new_cand_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.new_cand),
  .admit_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.admit),
  .bypass_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.bypass),
  .retire_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.retire),
  .ring_busy_i(u_trav.g_ring[0].u_sys.u_unit.u_loop.busy_o),
  .res_valid_i(res_valid), .res_ready_i(res_ready), .res_hit_i(res_hit),
  .hit_spacing_i(hit_ph_q != '0),
  .req_room_i(req_room), .hit_room_i(hit_room),
  .miss_full_i(miss_full)
);
`endif
