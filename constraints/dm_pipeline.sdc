# SPDX-License-Identifier: Apache-2.0
# SDC timing constraint (Synopsys Design Constraints: Quartus, Lattice Radiant, OpenROAD/OpenSTA,
# Design Compiler) for dm_pipeline_fpga_top or dm_pipeline, 100 MHz on clk_i.
# NOT run by this repository; `make synth` uses the open ECP5 flow (constraints/dm_pipeline.lpf).
create_clock -name clk -period 10.000 [get_ports {clk_i}]
set_clock_uncertainty 0.100 [get_clocks {clk}]
# I/O: an assumed 2 ns of board delay on both sides (adjust for a real board).
set_input_delay  -clock clk 2.000 [all_inputs]   ;# tools ignore it on the clock port itself
set_output_delay -clock clk 2.000 [all_outputs]
