# SPDX-License-Identifier: Apache-2.0
"""EDA flow: Verilator lint, Yosys checks and synthesis, congestion, GTKWave save files, the f24
approximation tables."""
