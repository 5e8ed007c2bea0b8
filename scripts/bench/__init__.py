# SPDX-License-Identifier: Apache-2.0
"""Long measurements: model and RTL benches, soak, the paper's study, coverage, vector tables."""
