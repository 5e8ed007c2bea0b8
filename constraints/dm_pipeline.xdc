# SPDX-License-Identifier: Apache-2.0
# Vivado (Xilinx 7-series / UltraScale) timing constraint for dm_pipeline_fpga_top or dm_pipeline.
# NOT run by this repository (no vendor tools here); `make synth` uses the open flow
# (constraints/dm_pipeline.lpf).  Kept with the same 100 MHz target for a vendor flow.
#
# Out-of-context block synthesis:  synth_design -top dm_pipeline -mode out_of_context ...
# (the HD.CLK_SRC line below tells the OOC timing engine where the clock would come from).
create_clock -name clk -period 10.000 [get_ports clk_i]
# set_property HD.CLK_SRC BUFGCTRL_X0Y0 [get_ports clk_i]

# The register port of dm_pipeline_fpga_top is registered at the pins; give its I/O the whole
# cycle minus an assumed 2 ns board delay (adjust for a real board).
set_input_delay  -clock clk 2.000 [get_ports -filter {DIRECTION == IN && NAME != clk_i}]
set_output_delay -clock clk 2.000 [get_ports -filter {DIRECTION == OUT}]
# rst_ni is synchronous and registered once inside the wrapper.
