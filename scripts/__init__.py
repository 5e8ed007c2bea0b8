# SPDX-License-Identifier: Apache-2.0
"""The project's command-line tools (trace, render, terrain, ...); ``bench`` the measurements,
``flow`` the lint, synthesis and waveform tooling."""
