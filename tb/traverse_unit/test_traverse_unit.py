# SPDX-License-Identifier: Apache-2.0
"""traverse_unit against model.traverse.trace(pyr, rays, method, "f24"), bit for bit.

Harness (traverse_unit_tb.sv): the unit with height_rom on its lookup port (fixed latency 3,
random misses from an LFSR), once per configuration.  For every map (1x1 .. 100x128, unorm8 and
unorm16, rough / flat / spiky heights) and every method code, random + adversarial rays
(tests/test_traverse.py) are streamed in with random valid gaps and the results drained with
random back-pressure; every ray id must come back exactly once with the model's hit, invalid,
iterations and (for hits) t, u, v words.  The statistics counters are checked against the
model's per-action counts.  A last run measures clocks per iteration with an always-hit memory
and no back-pressure.

The unit is checked with traverse_loop's XOR descent path (XOR_PATH=1, every method as the
model) and without it (XOR_PATH=0), where the ring runs the XOR descent as the multi-level
descent: park-xor's code is then checked against the model's method with park-xor's fields and
descent="multi" (same `descent_levels`), and every other method as before; both at the
package's multipliers (pipe_pkg::F24_MUL_LAT = 2: a ring of loop_depth(2) = 22 stages), and
under make test-long with the XOR path at the paper's one-clock multipliers (MUL_LAT=1: 19
stages), whose results must be the same words.  traverse_ring_length measures the ring's length
(clocks between one lone ray's lookups) against the Python mirror of traverse_pkg::loop_depth.
The configurations are built once, side by side, in the wrapper ``traverse_unit_tb`` (one unit
and ROM each, own ports and reset, a shared clock; its parameter LONG adds make test-long's) and
every cocotb test runs on all of them at once, each instance with its own random stream from
the printed seed and its own checks; a failure names the configuration.

Environment: SEED, TRAVERSE_RAYS (rays per map and method, default 200), WAVES=1.
"""
from __future__ import annotations

import dataclasses
import os
from pathlib import Path
from typing import Any, Callable, Coroutine

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge

from model import heightmap, traverse
from model.traverse import EXACT_METHODS
from tb.common import cases, depths, report, runner
from tb.common.tables import write_table
from tb.common.traverse_stimulus import adversarial_rays, height_field
from tb.harness import traverse_words

HERE = Path(__file__).resolve().parent

ROM_AW = 18
ROM_BASE = 0x4000_0000
#: (height, width, unorm bits, height-field kind)
MAPS = [(1, 1, 8, 0), (2, 2, 8, 0), (7, 5, 16, 0), (16, 16, 8, 2), (37, 61, 8, 0),
        (17, 64, 16, 0), (64, 64, 16, 1), (64, 64, 8, 2), (100, 128, 16, 2)]


#: (XOR_PATH, MUL_LAT) of the instances g_case[0 ..] of traverse_unit_tb (the wrapper's table):
#: with and without traverse_loop's XOR descent path, at the package's multipliers.
CASES = [(1, depths.DEFAULT[1]), (0, depths.DEFAULT[1])]
#: The instances after CASES in the make test-long build (the wrapper's LONG = 1): the XOR path
#: at the other multiplier depths of depths.PAIRS (the paper's MUL_LAT = 1).
LONG_CASES = [(1, m) for m in sorted({m for _, m in depths.PAIRS} - {depths.DEFAULT[1]})]


def build_cases() -> list[tuple[int, int]]:
    """The (XOR_PATH, MUL_LAT) of the build's instances: CASES, and LONG_CASES under TB_LONG=1."""
    return CASES + (LONG_CASES if runner.long_stimulus() else [])


def case_name(xor_path: int, mul_lat: int) -> str:
    """How a failure names the configuration."""
    return f"traverse_unit XOR_PATH {xor_path}, MUL_LAT {mul_lat}"


def loop_depth(mul_lat: int) -> int:
    """traverse_pkg::loop_depth: the ring's stages for f24_mul latency ``mul_lat``."""
    return 17 + 3 * mul_lat


def model_method(method: str, xor_path: int) -> traverse.Method:
    """The model's method that the unit runs for ``method``'s code with XOR_PATH ``xor_path``.

    Without the XOR descent path (XOR_PATH=0) the ring descends as the multi-level descent where a
    method asks for the XOR descent (traverse_loop's header); everything else is unchanged.
    """
    m = traverse.METHODS[method]
    if not xor_path and m.descent == "xor":
        return dataclasses.replace(m, descent="multi")
    return m


class Harness:
    """One instance ``g_case[i]`` of traverse_unit_tb (``dut``: its scope) and its configuration,
    on the shared clock ``clk``."""

    def __init__(self, dut, clk, xor_path: int, mul_lat: int):
        self.dut = dut
        self.clk = clk
        self.xor_path = xor_path
        self.mul_lat = mul_lat
        self.name = case_name(xor_path, mul_lat)
        self.s = {name: getattr(dut, name) for name in (
            "ray_valid_i", "ray_ready_o", "ray_id_i", "ray_u0_i", "ray_v0_i", "ray_du_i", "ray_dv_i",
            "res_valid_o", "res_ready_i", "res_id_o", "res_t_o", "res_u_o", "res_v_o", "res_hit_o",
            "res_invalid_o", "res_capped_o", "res_err_o", "res_iters_o", "idle_o")}

    def info(self, msg: str, *args: Any) -> None:
        """Log ``msg % args`` under the configuration's name."""
        cocotb.log.info("%s: " + msg, self.name, *args)

    def model_method(self, method: str) -> traverse.Method:
        """:func:`model_method` at this instance's XOR_PATH."""
        return model_method(method, self.xor_path)

    async def reset(self):
        """Reset this instance (the clock runs already)."""
        d = self.dut
        d.rst_ni.value = 0
        d.hlt_we_i.value = 0
        d.ray_valid_i.value = 0
        d.res_ready_i.value = 0
        d.wr_en_i.value = 0
        d.miss_thresh_i.value = 0
        d.rom_base_i.value = ROM_BASE
        await ClockCycles(self.clk, 4)
        await FallingEdge(self.clk)
        d.rst_ni.value = 1

    async def load(self, pyr: heightmap.Pyramid):
        img = pyr.memory_image()
        img += bytes(-len(img) % 4)
        words = np.frombuffer(img, dtype="<u4")
        assert len(img) <= 1 << ROM_AW
        d = self.dut
        await FallingEdge(self.clk)
        d.wr_en_i.value = 1
        for a, w in enumerate(words):
            d.wr_addr_i.value = a
            d.wr_data_i.value = int(w)
            await FallingEdge(self.clk)
        d.wr_en_i.value = 0

    async def configure(self, cfg: traverse_words.Config):
        await FallingEdge(self.clk)
        assert int(self.s["idle_o"].value) == 1, "configuration change while rays are in the unit"
        for name, val in cfg.ports().items():
            getattr(self.dut, name).value = val
        await write_table(self.dut, self.clk, "hlt", cfg.hlt_writes())
        await ClockCycles(self.clk, 7)   # register stage + the clip start time: 7 clocks
        await FallingEdge(self.clk)

    def stats(self) -> dict[str, int]:
        return {k: int(getattr(self.dut, f"stat_{k}_o").value) for k in (
            "cycles", "rays_in", "rays_out", "iters", "lookups", "crossings", "level_ups",
            "descents")}

    async def run(self, words, rng: np.random.Generator, valid_p: float, ready_p: float,
                  max_cycles: int) -> tuple[dict[int, tuple], int]:
        """Stream rays (id = index) in, collect results; returns {id: result} and the clocks used."""
        s = self.s
        u0, v0, du, dv = ([int(x) for x in w] for w in words)
        n = len(u0)
        got: dict[int, tuple] = {}
        dups = []
        nxt = 0
        presenting = False
        vr = rng.random(max_cycles + 1) < valid_p
        rr = rng.random(max_cycles + 1) < ready_p
        cyc = 0
        # We are at a falling edge: outputs show the state after the last rising edge.
        while len(got) < n:
            if cyc >= max_cycles:
                raise AssertionError(f"timeout: {len(got)} of {n} results after {cyc} clocks")
            # ray stream
            if not presenting and nxt < n and vr[cyc]:
                s["ray_id_i"].value = nxt
                s["ray_u0_i"].value = u0[nxt]
                s["ray_v0_i"].value = v0[nxt]
                s["ray_du_i"].value = du[nxt]
                s["ray_dv_i"].value = dv[nxt]
                s["ray_valid_i"].value = 1
                presenting = True
            if presenting and int(s["ray_ready_o"].value):
                nxt += 1          # transferred at the coming rising edge
                presenting = False
                fire_in = True
            else:
                fire_in = False
            # result stream
            ready = bool(rr[cyc])
            s["res_ready_i"].value = int(ready)
            if ready and int(s["res_valid_o"].value):
                rid = int(s["res_id_o"].value)
                rec = tuple(int(s[k].value) for k in (
                    "res_t_o", "res_u_o", "res_v_o", "res_hit_o", "res_invalid_o", "res_capped_o",
                    "res_err_o", "res_iters_o"))
                if rid in got:
                    dups.append(rid)
                got[rid] = rec
            await RisingEdge(self.clk)
            cyc += 1
            await FallingEdge(self.clk)
            if fire_in and not presenting:
                s["ray_valid_i"].value = 0
        s["ray_valid_i"].value = 0
        s["res_ready_i"].value = 0
        assert not dups, f"ray ids returned twice: {dups[:10]}"
        return got, cyc


def compare(name: str, got: dict[int, tuple], exp: traverse_words.ExpectedWords, cap: int,
            log) -> int:
    n = len(exp.hit)
    bad = []
    for i in range(n):
        if i not in got:
            bad.append(f"ray {i}: no result")
            continue
        t, u, v, hit, inv, capped, err, iters = got[i]
        e_hit, e_inv, e_it = bool(exp.hit[i]), bool(exp.invalid[i]), int(exp.iterations[i])
        why = []
        if bool(hit) != e_hit:
            why.append(f"hit {hit} != {int(e_hit)}")
        if bool(inv) != e_inv:
            why.append(f"invalid {inv} != {int(e_inv)}")
        if iters != e_it:
            why.append(f"iterations {iters} != {e_it}")
        if err:
            why.append("err")
        if capped and (hit or iters != cap):
            why.append(f"capped with hit={hit} iterations={iters}")
        if e_hit and hit:
            for nm, g, e in (("t", t, exp.t[i]), ("u", u, exp.u[i]), ("v", v, exp.v[i])):
                if g != int(e):
                    why.append(f"{nm} 0x{g:06x} != 0x{int(e):06x}")
        if why:
            bad.append(f"ray {i}: " + ", ".join(why))
    for b in bad[:10]:
        log.error("%s: %s", name, b)
    return len(bad)


def dump(name: str, pyr: heightmap.Pyramid, rays, method: str, got: dict[int, tuple]) -> None:
    """Save a failing case (map codes, rays, method, RTL results) for offline debugging."""
    d = runner.BUILD / "traverse_unit_tb" / "failures"
    d.mkdir(parents=True, exist_ok=True)
    ids = sorted(got)
    f = d / (name.split(" miss")[0].replace(" ", "_").replace(",", "") + ".npz")
    np.savez(f, codes=pyr.codes, bits=pyr.bits, method=method,
             rays=np.stack([rays.u0, rays.v0, rays.du, rays.dv], axis=1),
             ids=np.array(ids), got=np.array([got[i] for i in ids], dtype=np.int64))
    cocotb.log.info("saved %s", f)


Check = Callable[[Harness, np.random.Generator], Coroutine[Any, Any, None]]


async def each_case(dut, check: Check) -> None:
    """Start the clock, then reset every instance of traverse_unit_tb and run ``check`` on it
    (all at once, each with its own random stream: :func:`cases.streams`); fail naming every
    configuration whose check failed."""
    async def one(inst, case: tuple[int, int], rng: np.random.Generator) -> None:
        h = Harness(inst, dut.clk_i, *case)
        await h.reset()
        await check(h, rng)

    await cases.run_each(dut, build_cases(), lambda c: case_name(*c), one,
                         lambda c: {"XOR_PATH": c[0], "MUL_LAT": c[1]})


@cocotb.test()
async def traverse_bit_exact(dut):
    """Every map, method and stress against the model (:func:`bit_exact`), every instance."""
    await each_case(dut, bit_exact)


async def bit_exact(h: Harness, rng: np.random.Generator) -> None:
    """The maps of MAPS, every method, random + adversarial rays on instance ``h``."""
    nrays = int(os.environ.get("TRAVERSE_RAYS", "200"))
    dut = h.dut
    total = mism = 0
    xor_differs = 0  # XOR_PATH=0: rays whose park-xor result the multi-level descent changes
    relocations = 0  # redos of locate's exit check the model predicts (the RTL's path covered)
    failures = []
    for case, (hh, ww, bits, kind) in enumerate(MAPS):
        pyr = heightmap.build(height_field(rng, hh, ww, kind), bits)
        await h.load(pyr)
        rays = adversarial_rays(rng, ww, hh, nrays)
        words = traverse_words.ray_words(rays)
        for mi, method in enumerate(EXACT_METHODS):
            cfg = traverse_words.config(pyr, method, base=ROM_BASE)
            await h.configure(cfg)
            # Alternate the stress: cache misses and result back-pressure on most runs.
            miss = [0, 0x2000, 0x6000][(case + mi) % 3]
            dut.miss_thresh_i.value = miss
            ready_p = [1.0, 0.5, 0.15][(case + 2 * mi) % 3]
            valid_p = [1.0, 0.7][mi % 2]
            st: dict[str, int] = {}
            res = traverse.trace(pyr, rays, h.model_method(method), "f24", stats=st)
            exp = traverse_words.expected_words(res)
            if h.model_method(method) != traverse.METHODS[method]:
                full = traverse.trace(pyr, rays, method, "f24")
                xor_differs += int(np.count_nonzero((full.iterations != res.iterations)
                                                    | (full.hit != res.hit)))
            before = h.stats()
            got, cyc = await h.run(words, rng, valid_p, ready_p,
                                   max_cycles=200 * nrays + 20 * int(res.iterations.sum()) + 10000)
            after = h.stats()
            d = {k: after[k] - before[k] for k in after}
            name = (f"{hh}x{ww} u{bits} kind{kind} {method}"
                    f"{' (as multi)' if h.model_method(method) != traverse.METHODS[method] else ''}"
                    f" miss={miss / 65536:.2f} ready={ready_p}")
            nbad = compare(f"{h.name}: {name}", got, exp, cfg.iter_cap, cocotb.log)
            if nbad:
                dump(f"xor{h.xor_path} mul{h.mul_lat} {name}", pyr, rays, method, got)
            sbad = []
            want = {"rays_in": len(rays), "rays_out": len(rays),
                    "iters": int(res.iterations.sum()), "descents": st.get("down", 0),
                    "crossings": st.get("cross", 0), "level_ups": st.get("up", 0)}
            for k, v in want.items():
                if d[k] != v:
                    sbad.append(f"stat {k} {d[k]} != {v}")
            # (every iteration and every redo of locate's exit check reads once; lookup misses
            # read again)
            reads = d["iters"] + st.get("relocate", 0)
            relocations += st.get("relocate", 0)
            if d["lookups"] < reads or (miss == 0 and d["lookups"] != reads):
                sbad.append(f"stat lookups {d['lookups']} vs iterations {d['iters']} + "
                            f"relocations {st.get('relocate', 0)}")
            h.info("%-55s %5d rays, %6d iterations, %7d clocks, %d mismatches%s", name,
                   len(rays), d["iters"], cyc, nbad, (" " + "; ".join(sbad)) if sbad else "")
            total += len(rays)
            mism += nbad
            if nbad or sbad:
                failures.append(name)
    report.record("traverse_unit", "rays vs model f24" + ("" if h.xor_path else " (XOR_PATH=0)"),
                  total, mism)
    h.info("VECTORS traverse_unit: %d rays, %d mismatches; %d redos of locate's exit check",
           total, mism, relocations)
    assert not failures, f"mismatches in: {failures}"
    assert relocations > 0, "no ray's locate moved its estimate: the exit check's redo untested"
    if not h.xor_path:
        # The build without the XOR path must be told apart from one with it by these rays.
        h.info("XOR_PATH=0: park-xor ran as multi; %d rays differ from park-xor's result",
               xor_differs)
        assert xor_differs > 0, "no ray tells park-xor from its multi-level descent"


@cocotb.test()
async def traverse_iteration_cap(dut):
    """A small iteration cap (:func:`iteration_cap`), every instance."""
    await each_case(dut, iteration_cap)


async def iteration_cap(h: Harness, rng: np.random.Generator) -> None:
    """A small iteration cap (the model's cap patched to match): capped rays stop bit-exactly."""
    pyr = heightmap.build(height_field(rng, 37, 61, 2), 8)
    await h.load(pyr)
    rays = adversarial_rays(rng, 61, 37, 300)
    total = bad = capped = 0
    orig = traverse.iteration_cap
    for cap, method in ((3, "oh"), (5, "park"), (8, "drobot"), (4, "park-xor")):
        # (patched and restored with no await between: the other instances' checks never see it)
        traverse.iteration_cap = lambda _pyr, c=cap: c
        try:
            res = traverse.trace(pyr, rays, h.model_method(method), "f24")
        finally:
            traverse.iteration_cap = orig
        cfg = dataclasses.replace(traverse_words.config(pyr, method, base=ROM_BASE), iter_cap=cap)
        await h.configure(cfg)
        h.dut.miss_thresh_i.value = 0x3000
        got, _ = await h.run(traverse_words.ray_words(rays), rng, 0.8, 0.5, 200000)
        name = f"cap {cap} {method}"
        bad += compare(f"{h.name}: {name}", got, traverse_words.expected_words(res), cap,
                       cocotb.log)
        capped += sum(r[5] for r in got.values())
        total += len(rays)
    report.record("traverse_unit", "rays vs model f24, small iteration cap", total, bad)
    h.info("iteration cap: %d rays, %d capped, %d mismatches", total, capped, bad)
    assert bad == 0 and capped > 0


@cocotb.test()
async def traverse_read_errors(dut):
    """Lookups outside the memory (:func:`read_errors`), every instance."""
    await each_case(dut, read_errors)


async def read_errors(h: Harness, rng: np.random.Generator) -> None:
    """Lookups outside the memory answer rs_err: every ray that reads finishes with res_err_o."""
    pyr = heightmap.build(height_field(rng, 16, 16, 0), 8)
    await h.load(pyr)
    rays = adversarial_rays(rng, 16, 16, 200)
    cfg = traverse_words.config(pyr, "park", base=ROM_BASE + (1 << ROM_AW))  # outside the ROM
    await h.configure(cfg)
    res = traverse.trace(pyr, rays, "park", "f24")
    got, _ = await h.run(traverse_words.ray_words(rays), rng, 1.0, 0.5, 100000)
    bad = 0
    for i in range(len(rays)):
        t, u, v, hit, inv, capped, err, iters = got[i]
        reads = res.iterations[i] > 0
        if err != int(reads) or hit or iters != 0 or inv != int(res.invalid[i]) or capped:
            bad += 1
    report.record("traverse_unit", "read errors", len(rays), bad)
    assert bad == 0, f"{bad} rays with a wrong error result"


@cocotb.test()
async def traverse_throughput(dut):
    """Clocks per iteration (:func:`throughput`), every instance."""
    await each_case(dut, throughput)


async def throughput(h: Harness, rng: np.random.Generator) -> None:
    """Clocks per iteration with an always-hit memory, rays always offered, results always taken."""
    pyr = heightmap.build(height_field(rng, 64, 64, 0), 8)
    await h.load(pyr)
    n = 2000
    u0 = rng.uniform(0, 64, n)
    v0 = rng.uniform(0, 64, n)
    ang = rng.uniform(0, 2 * np.pi, n)
    ln = rng.uniform(0, 32, n)
    from model.rays import Rays
    rays = Rays(u0, v0, ln * np.cos(ang), ln * np.sin(ang))
    for method in ("oh", "park", "park-xor"):
        await h.configure(traverse_words.config(pyr, method, base=ROM_BASE))
        h.dut.miss_thresh_i.value = 0
        res = traverse.trace(pyr, rays, h.model_method(method), "f24")
        before = h.stats()
        got, cyc = await h.run(traverse_words.ray_words(rays), rng, 1.0, 1.0, 100 * n + 100000)
        after = h.stats()
        iters = after["iters"] - before["iters"]
        busy = after["cycles"] - before["cycles"]
        assert iters == int(res.iterations.sum())
        h.info("THROUGHPUT %-9s %d rays, %d iterations, %d clocks (%d busy): "
               "%.3f clocks / iteration", method, n, iters, cyc, busy, busy / iters)
        assert busy / iters <= 1.15, "loop under-used"


@cocotb.test()
async def traverse_ring_length(dut):
    """The ring's length (:func:`ring_length`), every instance."""
    await each_case(dut, ring_length)


async def ring_length(h: Harness, rng: np.random.Generator) -> None:
    """One ray alone in the unit, every lookup a hit: its lookups come one pass =
    loop_depth(MUL_LAT) clocks apart (the ring's length)."""
    pyr = heightmap.build(height_field(rng, 64, 64, 0), 8)
    await h.load(pyr)
    await h.configure(traverse_words.config(pyr, "oh", base=ROM_BASE))
    h.dut.miss_thresh_i.value = 0
    rays = adversarial_rays(rng, 64, 64, 400)
    res = traverse.trace(pyr, rays, "oh", "f24")
    i = int(np.argmax(res.iterations))
    assert res.iterations[i] >= 3, "no ray with three iterations"
    st: dict[str, int] = {}  # the ray's redos of locate's exit check read once more each
    traverse.trace(pyr, rays.subset([i]), "oh", "f24", stats=st)
    one = traverse_words.ray_words(rays)
    s = h.s
    s["ray_id_i"].value = 0
    for name, w in zip(("ray_u0_i", "ray_v0_i", "ray_du_i", "ray_dv_i"), one):
        s[name].value = int(w[i])
    s["ray_valid_i"].value = 1
    while not int(s["ray_ready_o"].value):
        await RisingEdge(h.clk)
        await FallingEdge(h.clk)
    await RisingEdge(h.clk)
    await FallingEdge(h.clk)
    s["ray_valid_i"].value = 0
    s["res_ready_i"].value = 1
    when: list[int] = []
    last = int(h.dut.stat_lookups_o.value)
    for cyc in range(100000):
        if int(s["res_valid_o"].value):
            break
        await RisingEdge(h.clk)
        await FallingEdge(h.clk)
        now = int(h.dut.stat_lookups_o.value)
        if now != last:
            assert now == last + 1
            when.append(cyc)
        last = now
    else:
        raise AssertionError("the ray did not come back")
    await RisingEdge(h.clk)
    await FallingEdge(h.clk)
    s["res_ready_i"].value = 0
    gaps = sorted(set(b - a for a, b in zip(when, when[1:])))
    want = loop_depth(h.mul_lat)
    h.info("RING MUL_LAT %d: %d lookups, clocks between them %s (loop_depth %d)",
           h.mul_lat, len(when), gaps, want)
    report.record("traverse_unit", f"ring length, MUL_LAT {h.mul_lat}", 1, int(gaps != [want]))
    assert len(when) == int(res.iterations[i]) + st.get("relocate", 0), \
        "lookups != the model's iterations + relocations"
    assert gaps == [want], f"lookups {gaps} clocks apart, loop_depth({h.mul_lat}) = {want}"


def test_loop_depth_mirror():
    """The Python mirror of traverse_pkg::loop_depth gives the package's LOOP_DEPTH at
    pipe_pkg::F24_MUL_LAT."""
    from tb.harness import sv_params
    assert loop_depth(sv_params.value("pipe_pkg", "F24_MUL_LAT")) == traverse_words.LOOP_DEPTH


def test_traverse_unit() -> None:
    """Build traverse_unit_tb once (the configurations of CASES; under make test-long, TB_LONG=1,
    with LONG = 1: LONG_CASES too) and run the cocotb tests on every instance."""
    diff = traverse_words.method_differences()
    assert not diff, "rtl/traverse/traverse_pkg.sv decode_method is out of date: " + "; ".join(diff)
    runner.run("traverse_unit_tb", "test_traverse_unit", HERE, rtl_top="traverse_unit",
               parameters={"LONG": 1} if runner.long_stimulus() else {},
               extra_env={"TB_LONG": "1" if runner.long_stimulus() else "0"},
               extra_sources=[str(HERE / "traverse_unit_tb.sv")])
