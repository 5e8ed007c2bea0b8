# SPDX-License-Identifier: Apache-2.0
"""Drive a purely combinational DUT with vectors and read its settled outputs (cocotb)."""
from __future__ import annotations

import numpy as np
from cocotb.triggers import Timer


async def apply(dut, inputs: dict[str, np.ndarray],
                outputs: tuple[str, ...]) -> dict[str, np.ndarray]:
    """Apply every vector (one per ns) and return the outputs as unsigned int64 arrays.

    Inputs are masked to their port widths; a port is written only when its value changes.
    """
    n = len(next(iter(inputs.values())))
    sig = {k: getattr(dut, k) for k in inputs}
    mask = {k: (1 << len(s)) - 1 for k, s in sig.items()}
    vals = {k: [int(x) & mask[k] for x in v] for k, v in inputs.items()}
    osig = [(k, getattr(dut, k)) for k in outputs]
    got = {k: np.zeros(n, dtype=np.int64) for k in outputs}
    for i in range(n):
        for k, s in sig.items():
            if i == 0 or vals[k][i] != vals[k][i - 1]:
                s.value = vals[k][i]
        await Timer(1, "ns")
        for k, s in osig:
            got[k][i] = int(s.value)
    return got
