# SPDX-License-Identifier: Apache-2.0
"""Drive a fixed-latency pipeline unit with valid / tag side band, clock-enable gaps and bubbles.

The units of ``rtl/pipe`` and ``rtl/mip`` (view_calc, mip_level) have ``clk_i``, ``rst_ni``,
``en_i``, ``valid_i``, ``tag_i`` and data inputs, and ``valid_o``, ``tag_o`` and data outputs;
every register advances only on enabled clocks and valid is reset synchronously by ``rst_ni``.
This is :func:`tb.common.fp_unit.check_pipeline` with that side band:

* every clock a random ``en_i``; on an enabled clock either the next operand set with
  ``valid_i = 1`` and a random tag, or (with probability ``bubble``) a bubble: ``valid_i = 0``
  with another operand set's data and a random tag; on a stalled clock random data and a random
  ``valid_i`` (the unit must ignore both);
* after every enabled edge ``valid_o`` must equal the valid bit taken ``latency`` enabled edges
  earlier, and for a valid slot ``tag_o`` and the data outputs are collected for that operand
  set; after a stalled edge every output must hold its value;
* the data outputs of valid slots are compared bit for bit with the expected arrays at the end,
  and the count is recorded with :func:`tb.common.report.record` (mismatches included).

Units that turn one operand set into several results (``jobs`` > 1: mip_level gives the colour
texture's level, then the normal map's) show result ``j`` of an operand set ``latency + j``
enabled edges after it, and need ``spacing`` >= ``jobs`` enabled clocks between operand sets:
after a valid slot the driver puts ``spacing - 1`` bubbles; the expected arrays then hold
``jobs`` entries per operand set (operand set ``k``'s result ``j`` at ``k * jobs + j``) and
``tag_o`` repeats the tag.  ``forbid`` lists distances (enabled clocks) at which no operand set
may follow an earlier one (mip_level: its shared adder's mip_gap and mip_gap + 1); the driver
puts a bubble there.

The unit's pipeline must hold only bubbles when :meth:`ValidPipe.run` starts: after
:meth:`ValidPipe.reset` or a previous :meth:`run` (which stops when its last operand set came
out, so that only bubbles follow it).  Configuration inputs are set by the caller between runs.

One ValidPipe per instance drives a wrapper's ``g_case[i]`` (tb/common/cases.py): ``clk`` the
wrapper's shared clock (started by the test, not here), ``unit`` the unit's name for the vector
table (else the handle's name: the top's).

(Used by tb/view_calc, tb/mip_level, tb/tex_addr; tb/tex_filter, whose driver has a ready input, uses its reset.)
"""
from __future__ import annotations

import collections
from typing import Callable, Mapping

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.common import report


class ValidPipe:
    """One unit under test; starts its clock (unless given ``clk``, a running clock) and keeps
    the count of vectors checked."""

    def __init__(self, dut, latency: int, data_in: list[str], data_out: list[str],
                 report_what: str, jobs: int = 1, spacing: int = 1,
                 forbid: tuple[int, ...] = (), clk=None, unit: str | None = None) -> None:
        if spacing < jobs:
            raise ValueError("spacing must be at least jobs (results would overlap)")
        if any(f < 1 for f in forbid):
            raise ValueError("forbidden distances are enabled clocks, 1 or more")
        self.dut = dut
        self.jobs = jobs            # results per operand set, in consecutive enabled clocks
        self.spacing = spacing      # enabled clocks from one operand set to the next, at least
        self.forbid = tuple(forbid)  # distances at which no operand set may follow another
        self.report_what = report_what  # the comparison's name in tb/common/report.py's table
        self.latency = latency
        self.data_in = data_in
        self.data_out = data_out
        self.tag_w = len(dut.tag_i)
        self.in_sigs = {k: getattr(dut, k) for k in data_in}
        self.out_sigs = {k: getattr(dut, k) for k in ["valid_o", "tag_o"] + data_out}
        self.checked = 0
        self.mismatches = 0
        self.unit = unit or dut._name  # the unit in the vector table
        if clk is None:
            clk = dut.clk_i
            cocotb.start_soon(Clock(clk, 10, unit="ns").start())
        self.clk = clk

    def sample(self) -> dict[str, int]:
        return {k: int(s.value) for k, s in self.out_sigs.items()}

    async def reset(self, cycles: int = 2) -> None:
        """rst_ni low for ``cycles`` edges with en_i = 0 (the reset does not wait for en_i)."""
        d = self.dut
        d.rst_ni.value = 0
        d.en_i.value = 0
        d.valid_i.value = 1
        await FallingEdge(self.clk)
        for _ in range(cycles):
            await RisingEdge(self.clk)
            await FallingEdge(self.clk)
            assert int(d.valid_o.value) == 0, "valid_o not cleared by rst_ni"
        d.rst_ni.value = 1
        d.valid_i.value = 0

    async def flush_check(self, rng: np.random.Generator) -> None:
        """Fill the pipeline with valid slots, reset it while stalled: nothing may come out."""
        d = self.dut
        d.rst_ni.value = 1
        d.en_i.value = 1
        taken: list[int] = []
        for i in range(self.latency):
            ok = all(i - t >= self.spacing and i - t not in self.forbid for t in taken)
            if ok:
                taken.append(i)
            d.valid_i.value = int(ok)
            d.tag_i.value = int(rng.integers(0, 1 << self.tag_w))
            await RisingEdge(self.clk)
            await FallingEdge(self.clk)
        assert int(d.valid_o.value) == 1, "valid_o should show the first valid slot"
        d.en_i.value = 0
        d.rst_ni.value = 0
        await RisingEdge(self.clk)
        await FallingEdge(self.clk)
        assert int(d.valid_o.value) == 0, "rst_ni with en_i = 0 did not clear valid_o"
        d.rst_ni.value = 1
        d.valid_i.value = 0
        for _ in range(self.latency + self.jobs + 2):
            d.en_i.value = 1
            await RisingEdge(self.clk)
            await FallingEdge(self.clk)
            assert int(d.valid_o.value) == 0, "a slot cleared by rst_ni came out valid"

    async def run(self, what: str, inputs: Mapping[str, np.ndarray],
                  outputs: Mapping[str, np.ndarray], rng: np.random.Generator,
                  en_prob: float = 0.8, bubble: float = 0.2,
                  describe: Callable[[int], str] | None = None) -> int:
        """Stream the operand sets ``inputs[name][k]`` through the unit and compare the data
        outputs with ``outputs[name][k]``; ``what`` names the run in the log.  Raises after the
        stream on any mismatch (up to 10 reported per output; a mismatching operand set counts
        once).  Returns the count checked."""
        d = self.dut
        lat, jobs = self.latency, self.jobs
        n = len(next(iter(inputs.values())))
        in_lists = {k: [int(x) for x in inputs[k]] for k in self.data_in}
        tags = rng.integers(0, 1 << self.tag_w, n)
        # Per clock: enable, bubble choice, the operand set shown in a bubble / a stall.
        m = 2 * n + 4 * lat + 16
        en_seq = (rng.random(m) < en_prob).tolist()
        bub_seq = (rng.random(m) < bubble).tolist()
        junk_idx = rng.integers(0, n, m).tolist()
        junk_valid = rng.integers(0, 2, m).tolist()
        junk_tag = rng.integers(0, 1 << self.tag_w, m).tolist()
        # The operand set of each of the last lat + jobs - 1 enabled clocks (-1: a bubble).
        depth = max(lat + jobs - 1, *self.forbid, 1)
        hist: collections.deque = collections.deque([-1] * depth, maxlen=depth)
        got: dict[str, list[int]] = {k: [] for k in ["tag_o"] + self.data_out}
        got_idx: list[int] = []
        d.rst_ni.value = 1
        prev = self.sample()
        issued = cyc = 0
        gap = 0  # enabled clocks still to leave empty after the last operand set
        while len(got_idx) < n * jobs:
            j = cyc % m
            cyc += 1
            en = en_seq[j]
            take = (en and issued < n and not bub_seq[j] and gap == 0
                    and all(hist[-f] < 0 for f in self.forbid))
            if en:
                gap = self.spacing - 1 if take else max(gap - 1, 0)
            k = issued if take else junk_idx[j]
            for name, s in self.in_sigs.items():
                s.value = in_lists[name][k]
            d.valid_i.value = 1 if take else (0 if en else junk_valid[j])
            d.tag_i.value = int(tags[k]) if take else junk_tag[j]
            d.en_i.value = int(en)
            await RisingEdge(self.clk)
            await FallingEdge(self.clk)
            now = self.sample()
            if en:
                hist.append(issued if take else -1)
                if take:
                    issued += 1
                # result jb of the operand set taken lat + jb enabled edges ago
                slot = next((hist[depth - lat - jb] * jobs + jb for jb in range(jobs)
                             if hist[depth - lat - jb] >= 0), -1)
                if now["valid_o"] != int(slot >= 0):
                    raise AssertionError(f"{what}: valid_o = {now['valid_o']} at clock {cyc}, "
                                         f"expected {int(slot >= 0)}")
                if slot >= 0:
                    got_idx.append(slot)
                    for name in got:
                        got[name].append(now[name])
            elif now != prev:
                raise AssertionError(f"{what}: outputs changed while en_i = 0 (clock {cyc}): "
                                     f"{prev} -> {now}")
            prev = now
        d.valid_i.value = 0
        d.en_i.value = 0
        order = np.array(got_idx)
        assert np.array_equal(order, np.arange(n * jobs)), f"{what}: operand sets out of order"
        expect = dict(outputs)
        expect["tag_o"] = np.repeat(tags, jobs)
        mism = []
        for name in got:
            g = np.array(got[name], dtype=np.int64)
            e = np.asarray(expect[name], dtype=np.int64)
            bad = np.nonzero(g != e)[0]
            for b in bad[:10]:
                k = int(b) // jobs
                desc = describe(k) if describe else ", ".join(
                    f"{kk}=0x{int(v[k]):06x}" for kk, v in inputs.items())
                if jobs > 1:
                    desc += f" (result {int(b) % jobs})"
                mism.append(f"{what}: {name}: {desc}: got 0x{int(g[b]):06x} "
                            f"expected 0x{int(e[b]):06x}")
            if len(bad):
                mism.append(f"{what}: {name}: {len(bad)} mismatches of {n * jobs}")
        bad_any = np.zeros(n, dtype=bool)
        for name in got:
            bad = np.array(got[name], dtype=np.int64) != np.asarray(expect[name], np.int64)
            bad_any |= bad.reshape(n, jobs).any(axis=1)
        nbad = int(bad_any.sum())
        self.checked += n
        self.mismatches += nbad
        report.record(self.unit, self.report_what, n, nbad)
        d._log.info("%s: %d operand sets in %d clocks (latency %d), %d mismatches", what, n, cyc,
                    lat, nbad)
        if mism:
            raise AssertionError("\n".join(mism))
        return n
