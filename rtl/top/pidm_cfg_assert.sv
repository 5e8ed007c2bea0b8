// SPDX-License-Identifier: Apache-2.0
// pidm_cfg_assert: the properties of pidm_cfg, bound into every instance (the `bind` at the end of
// this file), checked by simulation (Verilator --assert).  Immediate assertions only.
//
//   we_one_clock_late  tt_we_o is 1 exactly in the clock after a TT_WRITE bus write (swmod);
//   we_fields_stable   while tt_we_o is 1 the address and data it writes are the stored fields
//                      (no second TT_WRITE write arrived in between: the register block takes
//                      one write per clock, so the fields are those of the write being applied);
//   lvt_req_onehot     at most one of the 80 request strobes of the external registers
//                      HEIGHT.LEVEL_OFF[k], TEX[x].LEVEL_OFF[k] / LEVEL_SIZE[k] is 1 (the
//                      address encoding ORs them);
//   lvt_we_late        lvt_we_o is 1 exactly in the clock after such a request.
// Covers: a table write, two table writes in consecutive clocks, a level-table write.
`ifndef SYNTHESIS
module pidm_cfg_assert #(
  parameter int unsigned TRI_W = 4  // pidm_cfg's TRI_W
) (
  input logic           clk_i,
  input logic           rst_ni,
  input logic           swmod_i,      // hwif_i.TT_WRITE.data.swmod
  input logic [TRI_W:0] addr_i,       // hwif_i.TT_WRITE.addr.value[TRI_W:0]
  input logic [23:0]    data_i,       // hwif_i.TT_WRITE.data.value
  input logic           tt_we_i,      // tt_we_o
  input logic [TRI_W:0] tt_waddr_i,   // tt_waddr_o
  input logic [23:0]    tt_wdata_i,   // tt_wdata_o
  input logic [79:0]    lvt_req_i,    // the 80 level-table request strobes
                                      // ({height_req, off_req, size_req})
  input logic           lvt_we_i      // lvt_we_o
);

  logic swmod_q, rst_q, we_q, lvt_req_q;
  always_ff @(posedge clk_i) begin
    rst_q     <= rst_ni;
    lvt_req_q <= rst_ni && (|lvt_req_i);
    swmod_q <= rst_ni && swmod_i;
    we_q    <= rst_ni && tt_we_i;
  end

  always_ff @(posedge clk_i) begin
    if (rst_ni && rst_q) begin
      we_one_clock_late: assert (tt_we_i == swmod_q)
        else $error("pidm_cfg: tt_we_o %0d, TT_WRITE write one clock earlier %0d", tt_we_i, swmod_q);
      we_fields_stable: assert (!tt_we_i || (tt_waddr_i == addr_i && tt_wdata_i == data_i))
        else $error("pidm_cfg: table write of other fields than TT_WRITE holds");
      c_table_write:  cover (tt_we_i);
      c_back_to_back: cover (tt_we_i && we_q);
      lvt_req_onehot: assert ($onehot0(lvt_req_i))
        else $error("pidm_cfg: more than one level-table register requested in one clock");
      lvt_we_late: assert (lvt_we_i == lvt_req_q)
        else $error("pidm_cfg: lvt_we_o %0d, level-table request one clock earlier %0d",
                    lvt_we_i, lvt_req_q);
      c_lvt_write: cover (lvt_we_i);
    end
  end

endmodule

bind pidm_cfg pidm_cfg_assert #(.TRI_W(TRI_W)) u_assert (
  .clk_i, .rst_ni, .swmod_i(hwif_i.TT_WRITE.data.swmod), .addr_i(hwif_i.TT_WRITE.addr.value[TRI_W:0]),
  .data_i(hwif_i.TT_WRITE.data.value), .tt_we_i(tt_we_o), .tt_waddr_i(tt_waddr_o),
  .tt_wdata_i(tt_wdata_o), .lvt_req_i({height_req, off_req, size_req}), .lvt_we_i(lvt_we_o));
`endif
