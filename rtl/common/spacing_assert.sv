// SPDX-License-Identifier: Apache-2.0
// spacing_assert: the check of a unit that shares its datapath over two clocks (mip_level,
// tex_addr): no input on the enabled clock after one.  More generally, no valid_i in an enabled
// clock with taken_i (mip_level also binds it for its shared adder's rule; RULE names the rule
// in the message).  A checker module for `bind`
// (the binds stand in <unit>_assert.sv beside each unit; not in synthesis).  Immediate assertion
// in a clocked block, the form the formal flow's front end (Yosys read_slang) accepts.
`ifndef SYNTHESIS
module spacing_assert #(
  parameter string WHAT = "unit: inputs",  // the message's subject: "<module>: <items>"
  parameter string RULE = "on two consecutive enabled clocks"  // the broken rule, after WHAT
) (
  input logic clk_i,
  input logic rst_ni,
  input logic en_i,     // the unit's clock enable
  input logic valid_i,  // an input this clock
  input logic taken_i   // the unit's first stage holds an input: the last enabled clock took one
                        // (or, with another RULE, the condition that forbids valid_i)
);

  always_ff @(posedge clk_i) begin
    if (rst_ni) begin
      spacing: assert (!(en_i && valid_i) || !taken_i)
        else $error("%s %s", WHAT, RULE);
    end
  end

endmodule
`endif
