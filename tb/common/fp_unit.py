# SPDX-License-Identifier: Apache-2.0
"""Drive a fixed-latency float unit with random clock-enable gaps and check it bit for bit.

The unit has ``clk_i``, ``en_i`` and some inputs; registers advance only on enabled clocks.  Every
clock we present a new operand set and a random ``en_i``; the output after each edge must equal the
model's result for the operand set that was presented ``latency`` enabled edges earlier.  That
proves the latency, that a stalled unit holds its state, and the arithmetic, in one pass.

A float unit is checked at every latency under test (its ``LAT`` parameter; :func:`lat_set`)
in one build: :func:`run_lats` builds a wrapper (:mod:`tb.common.lat_wrapper`) holding the unit
once per LAT on the same inputs, and :func:`check_pipeline` checks each instance (a
:class:`Lane`, :func:`lanes`) at its own latency against the same expected words, with the same
``en_i``; each instance's count is recorded under its unit (``report.record``, one line per LAT,
as when each LAT was a build of its own) and its failures name its LAT.
"""
from __future__ import annotations

import os
import random
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import lat_wrapper, report, runner

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


#: The environment variable that carries the LATs under test (comma-separated) into the cocotb
#: test; :func:`run_lats` sets it.
LATS_ENV = "FP_LATS"


def lat_set(lats: Sequence[int], used: Sequence[int]) -> tuple[int, ...]:
    """The LATs a unit is checked at: ``make test`` the ones in ``used`` (the unit's default and
    every LAT the design builds it at), ``make test-long`` (TB_LONG=1) every one of ``lats``; in
    the order of ``lats``."""
    if not set(used) <= set(lats):
        raise ValueError(f"used LATs {list(used)} not all in {list(lats)}")
    return tuple(lat for lat in lats if runner.long_stimulus() or lat in used)


def run_lats(unit: str, test_module: str, test_dir: Path, lats: Sequence[int], default: int,
             parameters: Mapping[str, object] | None = None,
             extra_env: Mapping[str, str] | None = None) -> None:
    """Build ``unit`` at every latency of ``lats`` in one model and run ``test_module`` on it.

    The model's top is the wrapper of :mod:`tb.common.lat_wrapper` (written into the build's
    directory): one instance per LAT on the same inputs, the one at ``default`` built with no
    LAT parameter at all (so the run also checks that the unit's default is ``default``), every
    other one with ``LAT`` = its latency; ``parameters`` (W, ...) go to every instance.  The
    build is ``build/sim/<unit>[-<param><value>...]-LAT<a>_<b>...``, so each LAT set has its own.
    The cocotb test finds the instances with :func:`lanes` (``FP_LATS``).
    """
    params = dict(parameters or {})
    name = (unit + "".join(f"-{k}{v}" for k, v in sorted(params.items()))
            + "-LAT" + "_".join(str(lat) for lat in lats))
    wrapper = lat_wrapper.write(unit, lats, default, runner.build_path(name))
    env = dict(extra_env or {})
    env[LATS_ENV] = ",".join(str(lat) for lat in lats)
    runner.run(lat_wrapper.module_name(unit), test_module, test_dir, parameters=params,
               name=name, extra_env=env, extra_sources=[str(wrapper)], rtl_top=unit)


@dataclass(frozen=True)
class Lane:
    """One instance under check: its latency, the unit it is (for :func:`report.record`), and
    where its outputs are: ``handle.<name>`` (``wrapped`` False: the unit is the top) or
    ``handle.<name>_lat<latency>_o`` (``wrapped``: an instance of a :func:`run_lats` wrapper)."""

    latency: int
    unit: str
    handle: Any
    wrapped: bool = True

    def signal(self, name: str) -> Any:
        """The simulator object of this instance's output ``name`` (e.g. ``y_o``)."""
        return getattr(self.handle, lat_wrapper.lane_port(name, self.latency) if self.wrapped
                       else name)

    @property
    def tag(self) -> str:
        """The prefix of this instance's messages: ``LAT=<n>: `` in a wrapper, else none."""
        return f"LAT={self.latency}: " if self.wrapped else ""


def lanes(dut: Any) -> list[Lane]:
    """The instances of the :func:`run_lats` wrapper ``dut``, one per LAT of ``FP_LATS``."""
    if LATS_ENV not in os.environ:
        raise RuntimeError(f"{LATS_ENV} is not set: build the unit with fp_unit.run_lats")
    unit = dut._name.removesuffix("_lats")
    return [Lane(int(lat), unit, dut) for lat in os.environ[LATS_ENV].split(",")]


def lat_list(units: Sequence[Lane]) -> str:
    """``2,3,4``: the latencies of ``units``, for log lines."""
    return ",".join(str(u.latency) for u in units)


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


async def check_pipeline(dut, latency: int | Sequence[Lane], inputs: Mapping[str, np.ndarray],
                         outputs: Mapping[str, np.ndarray], rng: np.random.Generator,
                         en_prob: float = 0.8, describe: Callable[[int], str] | None = None,
                         label: str = "RTL vs model.f24") -> int:
    """Stream ``inputs`` through the unit and compare every output signal with ``outputs``.

    ``inputs[name][k]`` is applied as the k-th operand set; ``outputs[name][k]`` is the expected
    value of output ``name`` for it.  ``latency`` is the unit's latency (``dut`` is the unit), or
    the instances of a :func:`run_lats` wrapper (:func:`lanes`): all see the same operands and
    ``en_i``, each is checked at its own latency, each is recorded (``report.record``) under its
    unit.  Returns the number of operand sets checked (per instance).  Raises on the first
    mismatches (up to 10 reported per instance and output, the LAT named) after the whole stream
    ran, or at once when an output changes while ``en_i`` = 0.
    """
    units = [Lane(latency, dut._name, dut, wrapped=False)] if isinstance(latency, int) \
        else list(latency)
    max_lat = max(u.latency for u in units)
    n = len(next(iter(inputs.values())))
    cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start())
    in_sigs = {k: getattr(dut, k) for k in inputs}
    out_sigs = [{k: u.signal(k) for k in outputs} for u in units]
    in_lists = {k: [int(x) for x in v] for k, v in inputs.items()}
    en_seq = rng.random(n * 2 + max_lat * 4) < en_prob
    dut.en_i.value = 0
    for k, s in in_sigs.items():
        s.value = 0
    await FallingEdge(dut.clk_i)
    # Fill: the first `latency` enabled edges produce outputs of garbage; skip them.
    got: list[dict[str, list[int]]] = [{k: [] for k in outputs} for _ in units]
    got_idx: list[list[int]] = [[] for _ in units]
    issued = 0          # operand sets applied on an enabled edge
    cyc = 0
    while any(len(g) < n for g in got_idx):
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
        for u, sigs, u_got, u_idx in zip(units, out_sigs, got, got_idx):
            # After this edge the output shows operand set (issued - latency), if it exists.
            idx = issued - u.latency
            if en and 0 <= idx < n:
                for name, s in sigs.items():
                    u_got[name].append(int(s.value))
                u_idx.append(idx)
            elif (not en) and u_idx and idx == u_idx[-1]:
                # A stalled unit holds: the output must still show the last result.
                for name, s in sigs.items():
                    if int(s.value) != u_got[name][-1]:
                        raise AssertionError(f"{u.tag}{name} changed while en_i=0 (cycle {cyc})")
    mism = []
    for u, u_got, u_idx in zip(units, got, got_idx):
        sel = np.array(u_idx)
        nbad = 0
        for name, exp in outputs.items():
            g = np.array(u_got[name], dtype=np.int64)
            e = np.asarray(exp, dtype=np.int64)[sel]
            bad = np.nonzero(g != e)[0]
            nbad += len(bad)
            for b in bad[:10]:
                i = u_idx[b]
                what = describe(i) if describe else ", ".join(
                    f"{k}=0x{int(v[i]):06x}" for k, v in inputs.items())
                mism.append(f"{u.tag}{name}: {what}: got 0x{int(g[b]):06x} "
                            f"expected 0x{int(e[b]):06x}")
            if len(bad):
                mism.append(f"{u.tag}{name}: {len(bad)} mismatches of {len(g)}")
        report.record(u.unit, label, n, nbad)
        dut._log.info("%schecked %d operand sets in %d clocks, latency %d", u.tag, n, cyc,
                      u.latency)
    if mism:
        raise AssertionError("\n".join(mism))
    return n
