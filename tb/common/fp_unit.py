# SPDX-License-Identifier: Apache-2.0
"""Drive a fixed-latency float unit with random clock-enable gaps and check it bit for bit.

The unit has ``clk_i``, ``en_i`` and some inputs; registers advance only on enabled clocks.  Every
clock we present a new operand set and a random ``en_i``; the output after each edge must equal the
model's result for the operand set that was presented ``latency`` enabled edges earlier.  That
proves the latency, that a stalled unit holds its state, and the arithmetic, in one pass.
"""
from __future__ import annotations

import os
import random
import shutil
import subprocess
from pathlib import Path
from typing import Callable, Mapping, Sequence

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import report, runner

#: Random seed for stimulus: printed by every test, settable with SEED=...
def seed() -> int:
    s = int(os.environ.get("SEED", random.randrange(1 << 31)))
    cocotb.log.info("SEED=%d", s)
    return s


#: Random vectors per float unit (and per composite unit with TB_LONG=1, make test-long).
VECTORS = 50_000
#: Random vectors per build of a composite unit (shade_unit, view_calc, tex_addr, ...) in make
#: test: each is built in several configurations, each seeing its own random stream.
VECTORS_COMPOSITE = 10_000


def vectors(default: int = VECTORS) -> int:
    """Random vectors per unit: VECTORS=... if set, else ``default`` (at least :data:`VECTORS`
    with TB_LONG=1)."""
    if "VECTORS" in os.environ:
        return int(os.environ["VECTORS"])
    return max(default, VECTORS) if runner.long_stimulus() else default


#: The environment variable that carries the latency under test (the unit's LAT) into the cocotb
#: test; :func:`run_lat` sets it.
LAT_ENV = "FP_LAT"


def latency(default: int) -> int:
    """The latency under test: ``FP_LAT`` (set by :func:`run_lat`), else the unit's default."""
    return int(os.environ.get(LAT_ENV, default))


def lat_cases(lats: Sequence[int], used: Sequence[int]) -> list:
    """pytest parameters ``lat`` for every LAT a unit accepts: ``make test`` runs the ones in
    ``used`` (the unit's default and every LAT the design builds it at), ``make test-long``
    (TB_LONG=1) every one of ``lats``."""
    return [pytest.param(lat, id=str(lat), marks=[] if lat in used else pytest.mark.skipif(
                not runner.long_stimulus(),
                reason="a LAT the design does not build: make test-long (TB_LONG=1)"))
            for lat in lats]


def run_lat(top: str, test_module: str, test_dir: Path, lat: int, default: int,
            parameters: Mapping[str, object] | None = None,
            extra_env: Mapping[str, str] | None = None) -> None:
    """Build ``top`` at latency ``lat`` and run ``test_module`` with ``FP_LAT`` = ``lat``.

    The default latency is built with no LAT parameter at all (so the run also checks that the
    unit's default is ``default``); every other one with ``LAT`` = ``lat``.
    """
    params = dict(parameters or {})
    if lat != default:
        params["LAT"] = lat
    env = dict(extra_env or {})
    env[LAT_ENV] = str(lat)
    runner.run(top, test_module, test_dir, parameters=params, extra_env=env)


def elaborate(top: str, parameters: Mapping[str, object]) -> tuple[int, str]:
    """Verilator --lint-only of ``top`` with ``parameters``: (exit status, output)."""
    verilator = shutil.which("verilator")
    if verilator is None:
        raise RuntimeError("verilator not found on PATH (run through make)")
    cmd = ([verilator, "--lint-only", "--top-module", top]
           + [f"-G{k}={v}" for k, v in parameters.items()]
           + [str(p) for p in runner.sources_for(top)])
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=runner.ROOT)
    return p.returncode, p.stdout + p.stderr


def check_lats(top: str, lats: Sequence[int], parameters: Mapping[str, object] | None = None
               ) -> None:
    """Elaborate ``top`` at every LAT from 0 to max(lats) + 2: each of ``lats`` elaborates clean,
    each other one stops at the unit's ``$error`` ("<top>: LAT must ...")."""
    for lat in range(0, max(lats) + 3):
        rc, out = elaborate(top, {**(parameters or {}), "LAT": lat})
        rejected = f"{top}: LAT must" in out
        if lat in lats:
            assert rc == 0 and not rejected, f"{top} LAT={lat} does not elaborate:\n{out}"
        else:
            assert rc != 0 and rejected, f"{top} LAT={lat} is not rejected:\n{out}"


async def check_pipeline(dut, latency: int, inputs: Mapping[str, np.ndarray],
                         outputs: Mapping[str, np.ndarray], rng: np.random.Generator,
                         en_prob: float = 0.8, describe: Callable[[int], str] | None = None,
                         label: str = "RTL vs model.f24") -> int:
    """Stream ``inputs`` through the unit and compare every output signal with ``outputs``.

    ``inputs[name][k]`` is applied as the k-th operand set; ``outputs[name][k]`` is the expected value
    of output ``name`` for it.  Returns the number of operand sets checked.  Raises on the first
    mismatches (up to 10 reported) after the whole stream ran.
    """
    n = len(next(iter(inputs.values())))
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    in_sigs = {k: getattr(dut, k) for k in inputs}
    out_sigs = {k: getattr(dut, k) for k in outputs}
    in_lists = {k: [int(x) for x in v] for k, v in inputs.items()}
    en_seq = rng.random(n * 2 + latency * 4) < en_prob
    dut.en_i.value = 0
    for k, s in in_sigs.items():
        s.value = 0
    await FallingEdge(dut.clk_i)
    # Fill: the first `latency` enabled edges produce outputs of garbage; skip them.
    got: dict[str, list[int]] = {k: [] for k in outputs}
    got_idx: list[int] = []
    issued = 0          # operand sets applied on an enabled edge
    cyc = 0
    while len(got_idx) < n:
        en = bool(en_seq[cyc % len(en_seq)]) or issued >= n
        cyc += 1
        k = min(issued, n - 1)
        for name, s in in_sigs.items():
            s.value = in_lists[name][k]
        dut.en_i.value = int(en)
        await RisingEdge(dut.clk_i)
        if en:
            issued += 1
        await FallingEdge(dut.clk_i)  # outputs settled; inputs writable again
        # After this edge the output shows operand set (issued - latency), if it exists.
        idx = issued - latency
        if en and 0 <= idx < n:
            for name, s in out_sigs.items():
                got[name].append(int(s.value))
            got_idx.append(idx)
        elif (not en) and got_idx and idx == got_idx[-1]:
            # A stalled unit holds: the output must still show the last result.
            for name, s in out_sigs.items():
                if int(s.value) != got[name][-1]:
                    raise AssertionError(f"{name} changed while en_i=0 (cycle {cyc})")
    mism = []
    for name, exp in outputs.items():
        g = np.array(got[name], dtype=np.int64)
        e = np.asarray(exp, dtype=np.int64)[np.array(got_idx)]
        bad = np.nonzero(g != e)[0]
        for b in bad[:10]:
            i = got_idx[b]
            what = describe(i) if describe else ", ".join(
                f"{k}=0x{int(v[i]):06x}" for k, v in inputs.items())
            mism.append(f"{name}: {what}: got 0x{int(g[b]):06x} expected 0x{int(e[b]):06x}")
        if len(bad):
            mism.append(f"{name}: {len(bad)} mismatches of {len(g)}")
    nbad = sum(int(np.count_nonzero(np.array(got[k], dtype=np.int64) !=
                                   np.asarray(outputs[k], dtype=np.int64)[np.array(got_idx)]))
               for k in outputs)
    report.record(dut._name, label, n, nbad)
    dut._log.info("checked %d operand sets in %d clocks, latency %d", n, cyc, latency)
    if mism:
        raise AssertionError("\n".join(mism))
    return n
