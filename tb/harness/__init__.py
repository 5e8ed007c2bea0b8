# SPDX-License-Identifier: Apache-2.0
"""The Verilator C++ harnesses of the RTL and their Python drivers.

- :mod:`tb.harness.build`: the Verilator build of a harness (:class:`~tb.harness.build.HarnessSpec`,
  variants fast / checked / waves, the input hash and the build lock);
- :mod:`tb.harness.traverse_system`: ray batches through traverse_system (``trace_rtl``);
- :mod:`tb.harness.dm_pipeline`: frames through the whole pipeline, dm_pipeline (``render_rtl``);
- :mod:`tb.harness.traverse_words`, :mod:`tb.harness.pipeline_words`: model objects as the
  configuration and port words of traverse_unit and dm_pipeline (also used by the cocotb tests);
- :mod:`tb.harness.sv_params`: integer constants read from the RTL packages (``rtl/**/*_pkg.sv``).
"""
