"""Shared pieces of the cocotb testbenches (runner wrapper, stimulus helpers)."""
