# SPDX-License-Identifier: Apache-2.0
"""Shared pieces of the cocotb testbenches (runner wrapper, stimulus helpers)."""
