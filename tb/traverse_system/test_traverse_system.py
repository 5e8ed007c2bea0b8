# SPDX-License-Identifier: Apache-2.0
"""traverse_system (traverse_unit + height_cache + AXI4 read master) against model.traverse f24.

The pyramid's memory image (model.heightmap.Pyramid.memory_image()) lies in cocotbext-axi's
AxiRamRead (sparse memory) at a non-zero base (0x1000_0000 + 4 MiB per map, so the maps of
different cases never share a cache line); reads outside the images are flagged and answered
SLVERR.  The memory has random latency (on each burst's first beat; bursts return in order) and
random back-pressure (pause generators on AR and R); the ray stream has random valid gaps and the
result stream random ready back-pressure.

Rays: random + adversarial (tests/test_traverse.py) and camera rays of procedural scenes
(model.scenes + model.camera) on maps of 2x2 .. 1024x1024 (non-square 37x61, unorm8 and unorm16),
with several methods per map (every method code at least once).  Checked per case: every ray id
back exactly once, hit / invalid / capped / err / iterations and (for hits) t, u, v words equal
to model.traverse.trace(..., "f24"); the unit's counters against the model's per-action counts;
the cache's counters (hits = iterations, plus at most one per redo of locate's exit check;
hits + misses = lookups; bytes = lines * LINE_BYTES); no read outside the image.  SLVERR case:
whole cache lines of the pyramid answer SLVERR; the rays whose model path (per-ray ``record``)
reads a texel in them must come back with res_err (after exactly the iterations before that
read, no hit), every other ray exactly as the model (a redo's read of an estimate is not an
iteration: its error is ignored, as its data is).

Incoherent case: random positions and directions on a 256x256 map, with a slow memory (40 .. 80
clocks per line) and then with the result stream nearly stalled, bit-exact as above, with the ring's park queue watched:
rays must park, the queue must fill (missed rays then stay in the ring), parked rays must wait
while the result FIFO is full, and every parked ray must come back.

Printed / recorded per case: cache hit rate and clocks per iteration (busy clocks of the unit and
wall clocks of the run).

Environment: SEED, SYS_SCALE (ray-count factor, default 0.5; 1.0 with TB_LONG=1), WAVES=1.
"""
from __future__ import annotations

import json
import logging
import os
import random
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, FallingEdge
from cocotbext.axi import AxiRamRead, AxiReadBus

from model import camera, heightmap, scenes, traverse
from model.rays import Rays
from model.traverse import EXACT_METHODS
from tb.common import report, runner
from tb.common.tables import write_table
from tb.common.traverse_stimulus import adversarial_rays, height_field
from tb.harness import traverse_words

HERE = Path(__file__).resolve().parent
#: Per-batch performance lines (JSON), for reading after a run.
PERF = runner.BUILD / "traverse_system" / "perf.jsonl"

BASE0 = 0x1000_0000
REGION = 0x0040_0000      # address space per map (the 1024 x 1024 unorm8 image is 1.4 MB)
LINE_BYTES = 32           # traverse_system default
#: Statistics counters (Harness.stats names) and their widths: UNIT_CNT_W = 48 and the cache's.
CNT_BITS = {k: 48 for k in ("cycles", "rays_in", "rays_out", "iters", "lookups", "crossings",
                            "level_ups", "descents", "cache_hits", "cache_misses", "mem_bytes",
                            "mem_lines")}
#: The register behind each counter (instance, signal), for Harness.preset.
PRESET_REGS = {**{k: ("u_unit", f"stat_{k}_o") for k in ("cycles", "rays_in", "rays_out",
                                                         "iters", "lookups", "crossings",
                                                         "level_ups", "descents")},
               "cache_hits": ("u_cache", "st_hits_q"), "cache_misses": ("u_cache", "st_misses_q"),
               "mem_bytes": ("u_cache", "st_bytes_q"), "mem_lines": ("u_cache", "st_lines_q")}
RES_FIELDS = ("res_t_o", "res_u_o", "res_v_o", "res_hit_o", "res_invalid_o", "res_capped_o",
              "res_err_o", "res_iters_o")


def seed() -> int:
    s = int(os.environ.get("SEED", random.randrange(1 << 31)))
    cocotb.log.info("SEED=%d", s)
    return s


def scale(n: int) -> int:
    """``n`` rays times SYS_SCALE (default 0.5 in make test, 1.0 with TB_LONG=1)."""
    default = "1.0" if runner.long_stimulus() else "0.5"
    return max(16, int(n * float(os.environ.get("SYS_SCALE", default))))


def pauses(rng: random.Random, p: float):
    while True:
        yield rng.random() < p


class MapRam(AxiRamRead):
    """AxiRamRead with random burst latency, an address check and injected SLVERR ranges."""

    def __init__(self, *args, rng: random.Random, **kwargs):
        super().__init__(*args, **kwargs)
        self.rng = rng
        self.lat = (0, 0)
        self.regions: list[tuple[int, int]] = []   # [lo, hi) byte ranges holding images
        self.err_ranges: list[tuple[int, int]] = []
        self.outside: list[int] = []               # beat addresses read outside every image
        self.err_beats = 0

    async def _read(self, address, length):
        if address % LINE_BYTES == 0 and self.lat[1] > 0:   # first beat of a line burst
            n = self.rng.randint(*self.lat)
            if n:
                await ClockCycles(self.clock, n)
        if not any(lo <= address and address + length <= hi for lo, hi in self.regions):
            self.outside.append(address)
            raise IOError("read outside the pyramid")
        if any(lo < address + length and address < hi for lo, hi in self.err_ranges):
            self.err_beats += 1
            raise IOError("injected SLVERR")   # AxiSlaveRead answers rresp = SLVERR
        return await super()._read(address, length)


@dataclass
class Case:
    name: str
    pyr: heightmap.Pyramid
    base: int
    rays: Rays
    methods: tuple[str, ...]
    valid_p: float = 0.8       # ray stream: probability of offering a ray in a clock
    ready_p: float = 0.7       # result stream: probability of res_ready_i
    ar_pause: float = 0.2      # AXI AR / R pause probabilities
    r_pause: float = 0.2
    lat: tuple[int, int] = (0, 20)


class Harness:
    def __init__(self, dut, rng: random.Random):
        self.dut = dut
        self.clk = dut.clk_i
        self.rng = rng
        self.s = {name: getattr(dut, name) for name in (
            "ray_valid_i", "ray_ready_o", "ray_id_i", "ray_u0_i", "ray_v0_i", "ray_du_i",
            "ray_dv_i", "res_valid_o", "res_ready_i", "res_id_o", "idle_o") + RES_FIELDS}
        cocotb.start_soon(Clock(self.clk, 10, unit="ns").start())
        # Never reset (the cache's reads must all return anyway; the memory holds every map).
        self.ram = MapRam(AxiReadBus.from_prefix(dut, "m_axi"), self.clk, reset=None, rng=rng,
                          size=1 << 32)
        self.ram.log.setLevel(logging.ERROR)
        self.next_base = BASE0
        self.sent = 0          # rays that went in during the last run

    async def reset(self):
        d = self.dut
        d.rst_ni.value = 0
        d.hlt_we_i.value = 0
        d.ray_valid_i.value = 0
        d.res_ready_i.value = 0
        d.clr_stats_i.value = 0
        await ClockCycles(self.clk, 4)
        await FallingEdge(self.clk)
        d.rst_ni.value = 1

    def place(self, pyr: heightmap.Pyramid) -> int:
        """Write the pyramid's image into the memory at a fresh base; returns the base."""
        img = pyr.memory_image()
        assert len(img) <= REGION
        base = self.next_base
        self.next_base += REGION
        self.ram.write(base, img)
        self.ram.regions.append((base, base + len(img)))
        return base

    def preset(self, values: dict[str, int]) -> None:
        """Deposit values into statistics counters (names as :meth:`stats`): the counter
        registers themselves, so the next clocks count on from there."""
        for k, v in values.items():
            inst, reg = PRESET_REGS[k]
            getattr(getattr(self.dut, inst), reg).value = v

    def stats(self) -> dict[str, int]:
        d = self.dut
        out = {k: int(getattr(d, f"stat_{k}_o").value) for k in (
            "cycles", "rays_in", "rays_out", "iters", "lookups", "crossings", "level_ups",
            "descents", "cache_hits", "cache_misses", "mem_bytes", "mem_lines")}
        return out

    async def configure(self, cfg: traverse_words.Config, case: Case):
        await FallingEdge(self.clk)
        assert int(self.s["idle_o"].value) == 1, "configuration change while rays are in the unit"
        for name, val in cfg.ports().items():
            getattr(self.dut, name).value = val
        await write_table(self.dut, self.clk, "hlt", cfg.hlt_writes())
        self.ram.ar_channel.set_pause_generator(pauses(self.rng, case.ar_pause))
        self.ram.r_channel.set_pause_generator(pauses(self.rng, case.r_pause))
        self.ram.lat = case.lat
        self.dut.clr_stats_i.value = 1      # cache statistics per case
        await FallingEdge(self.clk)
        self.dut.clr_stats_i.value = 0
        await ClockCycles(self.clk, 7)      # the unit's 7 clocks (register stage, clip start time)
        await FallingEdge(self.clk)

    async def run(self, words, valid_p: float, ready_p: float, max_cycles: int,
                  stop: int | None = None) -> tuple[dict[int, tuple], int, list[int]]:
        """Stream rays (id = index) in, collect results; {id: result}, clocks, duplicate ids.
        ``stop``: end after that many clocks, rays still in flight (a batch to be cut short by
        a reset); ``self.sent`` is then the number of rays that went in."""
        s = self.s
        u0, v0, du, dv = ([int(x) for x in w] for w in words)
        n = len(u0)
        got: dict[int, tuple] = {}
        dups: list[int] = []
        nxt = 0
        presenting = False
        rnd = self.rng.random
        ray_valid, ray_ready = s["ray_valid_i"], s["ray_ready_o"]
        res_valid, res_ready, res_id = s["res_valid_o"], s["res_ready_i"], s["res_id_o"]
        res_sig = [s[k] for k in RES_FIELDS]
        cyc = 0
        # At a falling edge: outputs show the state after the last rising edge; inputs written
        # now are sampled at the next one (ray_ready_o does not depend on ray_valid_i, nor
        # res_valid_o on res_ready_i), so both handshakes are known before that edge.
        while len(got) < n:
            if stop is not None and cyc >= stop:
                self.sent = nxt
                return got, cyc, dups
            if cyc >= max_cycles:
                raise AssertionError(f"timeout: {len(got)} of {n} results after {cyc} clocks")
            if not presenting and nxt < n and rnd() < valid_p:
                s["ray_id_i"].value = nxt
                s["ray_u0_i"].value = u0[nxt]
                s["ray_v0_i"].value = v0[nxt]
                s["ray_du_i"].value = du[nxt]
                s["ray_dv_i"].value = dv[nxt]
                ray_valid.value = 1
                presenting = True
            fire_in = presenting and int(ray_ready.value)
            ready_now = int(rnd() < ready_p)
            res_ready.value = ready_now
            if ready_now and int(res_valid.value):
                rid = int(res_id.value)
                rec = tuple(int(x.value) for x in res_sig)
                if rid in got or rid >= n:
                    dups.append(rid)
                got[rid] = rec
            await FallingEdge(self.clk)
            cyc += 1
            if fire_in:
                nxt += 1
                presenting = False
                ray_valid.value = 0
        assert nxt == n and not presenting
        self.sent = nxt
        ray_valid.value = 0
        # Nothing more may come out.
        res_ready.value = 1
        for _ in range(40):
            await FallingEdge(self.clk)
            if int(res_valid.value):
                dups.append(int(res_id.value))
        res_ready.value = 0
        return got, cyc, dups

    async def settle(self, max_cycles=20000, base: dict[str, int] | None = None
                     ) -> dict[str, int]:
        """Wait until the unit is idle and every line read has returned (bytes = lines *
        LINE_BYTES since ``base``, the statistics at the start); the statistics then."""
        b = base or {"mem_bytes": 0, "mem_lines": 0}
        for _ in range(max_cycles):
            await FallingEdge(self.clk)
            st = self.stats()
            nbytes = (st["mem_bytes"] - b["mem_bytes"]) % (1 << CNT_BITS["mem_bytes"])
            lines = (st["mem_lines"] - b["mem_lines"]) % (1 << CNT_BITS["mem_lines"])
            if int(self.s["idle_o"].value) and nbytes == lines * LINE_BYTES:
                return st
        raise AssertionError(f"not idle / reads outstanding: {self.stats()}")


def compare(name: str, got: dict[int, tuple], exp: traverse_words.ExpectedWords, cap: int,
            log, err_expect: dict[int, int] | None = None) -> int:
    """Mismatches against the model.  ``err_expect``: ray -> iterations before its bad read (the
    rays that must come back with res_err); None: no ray may."""
    err_expect = err_expect or {}
    bad = []
    for i in range(len(exp.hit)):
        if i not in got:
            bad.append(f"ray {i}: no result")
            continue
        t, u, v, hit, inv, capped, err, iters = got[i]
        why = []
        if i in err_expect:
            if not err or hit or inv or capped or iters != err_expect[i]:
                why.append(f"expected err after {err_expect[i]} iterations, got err={err} "
                           f"hit={hit} invalid={inv} capped={capped} iterations={iters}")
        else:
            e_hit, e_inv, e_it = bool(exp.hit[i]), bool(exp.invalid[i]), int(exp.iterations[i])
            if err:
                why.append("err")
            if bool(hit) != e_hit:
                why.append(f"hit {hit} != {int(e_hit)}")
            if bool(inv) != e_inv:
                why.append(f"invalid {inv} != {int(e_inv)}")
            if iters != e_it:
                why.append(f"iterations {iters} != {e_it}")
            if capped and (hit or iters != cap):
                why.append(f"capped with hit={hit} iterations={iters} (cap {cap})")
            if e_hit and hit:
                for nm, g, e in (("t", t, exp.t[i]), ("u", u, exp.u[i]), ("v", v, exp.v[i])):
                    if g != int(e):
                        why.append(f"{nm} 0x{g:06x} != 0x{int(e):06x}")
        if why:
            bad.append(f"ray {i}: " + ", ".join(why))
    for b in bad[:10]:
        log.error("%s: %s", name, b)
    return len(bad)


# ------------------------------------------------------------------------------------------ rays

def camera_rays(rng: np.random.Generator, w: int, h: int, view: str | float, img: int,
                n: int | None = None) -> Rays:
    """Camera rays of an img x img image (pixel order), optionally n of them at random."""
    r = camera.Camera.for_view(view, w, h, img, img).rays().rays
    if n is not None and n < len(r):
        r = r.subset(np.sort(rng.choice(len(r), n, replace=False)))
    return r


def cat(*rs: Rays) -> Rays:
    return Rays(*(np.concatenate([getattr(r, f) for r in rs]) for f in ("u0", "v0", "du", "dv")))


def scene_pyr(name: str, hh: int, ww: int, bits: int) -> heightmap.Pyramid:
    return heightmap.build(scenes.height(name, (hh, ww)), bits)


def cases(h: Harness, rng: np.random.Generator) -> list[Case]:
    """The map / ray / method / stress combinations (every method code at least once)."""
    out = []

    def add(name, pyr, rays, methods, **kw):
        out.append(Case(name, pyr, h.place(pyr), rays, tuple(methods), **kw))

    pyr = heightmap.build(height_field(rng, 2, 2, 0), 8)
    add("2x2 random u8", pyr, cat(adversarial_rays(rng, 2, 2, scale(64)),
                                  camera_rays(rng, 2, 2, "oblique", 8)),
        EXACT_METHODS, valid_p=1.0, ready_p=0.5, lat=(0, 8))
    pyr = scene_pyr("stones", 37, 61, 8)
    add("37x61 stones u8", pyr, cat(camera_rays(rng, 61, 37, "oblique", 24),
                                    camera_rays(rng, 61, 37, "grazing", 24),
                                    adversarial_rays(rng, 61, 37, scale(200))),
        ("park", "oh", "tevs", "drobot"), valid_p=0.7, ready_p=0.8, lat=(0, 30))
    pyr = scene_pyr("four-shapes", 64, 64, 16)
    add("64x64 four-shapes u16", pyr, cat(camera_rays(rng, 64, 64, "grazing", 32),
                                          adversarial_rays(rng, 64, 64, scale(200))),
        ("park-xor", "coherent", "selective", "park-gpu"), valid_p=1.0, ready_p=0.3,
        ar_pause=0.5, r_pause=0.5, lat=(0, 40))
    pyr = heightmap.build(height_field(rng, 100, 128, 2), 8)
    add("100x128 random spikes u8", pyr, adversarial_rays(rng, 128, 100, scale(300)),
        ("start-level", "multi-down", "park"), valid_p=0.9, ready_p=0.9, lat=(5, 60))
    pyr = scene_pyr("rocks", 256, 256, 8)
    add("256x256 rocks u8", pyr, camera_rays(rng, 256, 256, "oblique", 64, scale(1200)),
        ("park", "park-xor", "oh"), valid_p=1.0, ready_p=0.9, ar_pause=0.1, r_pause=0.1,
        lat=(0, 20))
    # the same map and rays, no stress at all (memory answers at once, streams never wait)
    c = out[-1]
    out.append(Case(c.name + " no stress", c.pyr, c.base, c.rays.subset(np.arange(scale(600))),
                    ("park",), valid_p=1.0, ready_p=1.0, ar_pause=0.0, r_pause=0.0, lat=(0, 0)))
    pyr = scene_pyr("saints", 1024, 1024, 8)
    add("1024x1024 saints u8", pyr, cat(camera_rays(rng, 1024, 1024, "grazing", 48, scale(250)),
                                        adversarial_rays(rng, 1024, 1024, scale(100))),
        ("park", "drobot"), valid_p=0.9, ready_p=0.7, lat=(0, 30))
    return out


# ----------------------------------------------------------------------------------------- tests

async def run_case(h: Harness, case: Case, method: str, log, err_expect=None,
                   res: traverse.TraceResult | None = None, st: dict | None = None,
                   preset: dict[str, int] | None = None) -> dict:
    """One case and method: run, compare, check the statistics; returns a summary dict.

    ``preset``: counter values deposited after the configuration (:meth:`Harness.preset`); the
    statistics are then checked as differences modulo the counters' widths."""
    cfg = traverse_words.config(case.pyr, method, base=case.base)
    await h.configure(cfg, case)
    if res is None:
        st = {}
        res = traverse.trace(case.pyr, case.rays, method, "f24", stats=st)
    exp = traverse_words.expected_words(res)
    if preset:
        await FallingEdge(h.clk)
        h.preset(preset)
        await FallingEdge(h.clk)
    before = h.stats()
    if preset:
        for k, v in preset.items():
            assert before[k] == v, f"counter {k} reads {before[k]} after a deposit of {v}"
    n = len(case.rays)
    got, cyc, dups = await h.run(traverse_words.ray_words(case.rays), case.valid_p, case.ready_p,
                                 max_cycles=400 * n + 60 * int(res.iterations.sum()) + 20000)
    after = await h.settle(base=before)
    d = {k: (after[k] - before[k]) % (1 << CNT_BITS[k]) for k in after}
    name = f"{case.name} {method}"
    nbad = compare(name, got, exp, cfg.iter_cap, log, err_expect)
    sbad = []
    if dups:
        sbad.append(f"ray ids returned twice / unknown: {dups[:10]}")
    want = {"rays_in": n, "rays_out": n}
    if err_expect is None:
        want.update(iters=int(res.iterations.sum()), descents=st.get("down", 0),
                    crossings=st.get("cross", 0), level_ups=st.get("up", 0))
    else:
        want.update(iters=sum(r[7] for r in got.values()))
    for k, v in want.items():
        if d[k] != v:
            sbad.append(f"stat {k} {d[k]} != {v}")
    hits, misses = d["cache_hits"], d["cache_misses"]
    lines, nbytes = d["mem_lines"], d["mem_bytes"]
    # (each redo of locate's exit check reads once more, a hit or a miss)
    reloc = st.get("relocate", 0) if err_expect is None else hits - d["iters"]
    if not d["iters"] <= hits <= d["iters"] + reloc:
        sbad.append(f"cache hits {hits} not in iterations {d['iters']} + [0, {reloc}] "
                    "relocations")
    if hits + misses != d["lookups"]:
        sbad.append(f"cache hits + misses {hits + misses} != lookups {d['lookups']}")
    if nbytes != lines * LINE_BYTES:
        sbad.append(f"cache bytes {nbytes} != lines {lines} * {LINE_BYTES}")
    if h.ram.outside:
        sbad.append(f"reads outside the images: {[hex(a) for a in h.ram.outside[:5]]}")
        h.ram.outside.clear()
    iters = max(d["iters"], 1)
    out = {"name": name, "rays": n, "iters": d["iters"], "lookups": d["lookups"],
           "hit_rate": hits / max(hits + misses, 1), "lines": lines, "busy": d["cycles"],
           "clocks": cyc, "lines_per_it": lines / iters, "cpi_busy": d["cycles"] / iters,
           "cpi_wall": cyc / iters,
           "mism": nbad, "sbad": sbad,
           "errs": sum(r[6] for r in got.values()), "hits": int(sum(r[3] for r in got.values()))}
    msg = (f"TRAVERSE_SYSTEM {name:<38} {n:5d} rays {d['iters']:6d} it  hit rate "
           f"{out['hit_rate']:.3f} ({hits}/{hits + misses}), {lines:5d} lines "
           f"({out['lines_per_it']:.3f}/it), "
           f"{out['cpi_busy']:.2f} busy clk/it, {out['cpi_wall']:.2f} wall clk/it, "
           f"{nbad} mismatches" + ((" " + "; ".join(sbad)) if sbad else ""))
    log.info(msg)
    print(msg)
    report.record("traverse_system", "rays vs model f24" if err_expect is None
                  else "rays vs model f24 with SLVERR lines", n, nbad + bool(sbad))
    PERF.parent.mkdir(parents=True, exist_ok=True)   # a test run alone (make waves CASE=...)
    with open(PERF, "a") as f:
        f.write(json.dumps({k: out[k] for k in ("name", "rays", "iters", "lookups", "hit_rate",
                                                 "lines", "lines_per_it", "busy", "clocks", "cpi_busy",
                                                 "cpi_wall", "mism")}) + "\n")
    return out


@cocotb.test()
async def traverse_system_bit_exact(dut):
    """Random, adversarial and camera rays on maps of 2x2 .. 1024x1024, several methods each."""
    s = seed()
    rng = np.random.default_rng(s)
    PERF.parent.mkdir(parents=True, exist_ok=True)
    PERF.unlink(missing_ok=True)
    h = Harness(dut, random.Random(s))
    await h.reset()
    t0 = time.time()
    all_cases = cases(h, rng)
    total = mism = 0
    failures = []
    summaries = []
    for case in all_cases:
        for method in case.methods:
            o = await run_case(h, case, method, dut._log)
            summaries.append(o)
            total += o["rays"]
            mism += o["mism"]
            if o["mism"] or o["sbad"]:
                failures.append(o["name"])
    it = sum(o["iters"] for o in summaries)
    busy = sum(o["busy"] for o in summaries)
    wall = sum(o["clocks"] for o in summaries)
    msg = (f"TRAVERSE_SYSTEM total: {total} rays, {it} iterations, {len(summaries)} runs, "
           f"{busy / max(it, 1):.2f} busy clk/it, {wall / max(it, 1):.2f} wall clk/it, "
           f"{mism} mismatches, {time.time() - t0:.1f} s")
    dut._log.info(msg)
    print(msg)
    assert not failures, f"mismatches in: {failures}"


@cocotb.test()
async def traverse_system_slverr(dut):
    """Some cache lines of the pyramid answer SLVERR: exactly the rays whose model path reads
    them come back with res_err (after the iterations before that read); the others as the
    model."""
    s = seed()
    rng = np.random.default_rng(s + 1)
    h = Harness(dut, random.Random(s + 1))
    await h.reset()
    hh = ww = 64
    pyr = scene_pyr("stones", hh, ww, 8)
    base = h.place(pyr)
    offs = pyr.level_offsets()
    bpt = pyr.bits // 8
    # bad lines: two level-0 rows in the middle, a few level-0 lines elsewhere, one level-2 line
    bad_lines = set()
    for row in (30, 31):
        for x in range(0, ww * bpt, LINE_BYTES):
            bad_lines.add((base + offs[0] + row * pyr.size * bpt + x) // LINE_BYTES)
    for _ in range(4):
        a = base + offs[0] + int(rng.integers(hh * pyr.size * bpt))
        bad_lines.add(a // LINE_BYTES)
    bad_lines.add((base + offs[2] + 5 * (pyr.size >> 2) * bpt) // LINE_BYTES)
    h.ram.err_ranges = [(la * LINE_BYTES, (la + 1) * LINE_BYTES) for la in sorted(bad_lines)]
    rays = cat(camera_rays(rng, ww, hh, "oblique", 24), adversarial_rays(rng, ww, hh, scale(250)))
    total = mism = errs_total = 0
    failures = []
    for method in ("park", "oh", "drobot"):
        res = traverse.trace(pyr, rays, method, "f24")
        # per ray: the model's iteration path; the first read of a bad line
        err_expect = {}
        for i in range(len(rays)):
            if res.invalid[i] or res.iterations[i] == 0:
                continue
            rec: list[dict] = []
            traverse.trace(pyr, rays.subset([i]), method, "f24", record=rec)
            assert len(rec) == res.iterations[i]
            for r in rec:
                k = r["level"]
                a = base + offs[k] + (r["cy"] * (pyr.size >> k) + r["cx"]) * bpt
                if a // LINE_BYTES in bad_lines:
                    err_expect[i] = r["iteration"] - 1
                    break
        case = Case(f"{hh}x{ww} stones u8 SLVERR", pyr, base, rays, (method,), valid_p=0.9,
                    ready_p=0.6, lat=(0, 30))
        o = await run_case(h, case, method, dut._log, err_expect=err_expect, res=res)
        n_err = len(err_expect)
        if not 0 < n_err < len(rays) - 8:
            o["sbad"].append(f"{n_err} of {len(rays)} rays read a bad line: test not selective")
        if o["errs"] != n_err:
            o["sbad"].append(f"{o['errs']} rays with err, model says {n_err}")
        msg = (f"TRAVERSE_SYSTEM SLVERR {method}: {len(rays)} rays, {n_err} read a bad line "
               f"(model), {o['errs']} err results, {o['mism']} mismatches, "
               f"{h.ram.err_beats} SLVERR beats so far")
        dut._log.info(msg)
        print(msg)
        total += len(rays)
        mism += o["mism"]
        errs_total += n_err
        if o["mism"] or o["sbad"]:
            failures.append((o["name"], o["sbad"]))
    assert errs_total > 0 and h.ram.err_beats > 0
    assert not failures, f"failures: {failures}"


@cocotb.test()
async def traverse_system_reset_mid_batch(dut):
    """Resets of 1 to 5 clocks in the middle of batches (rays in setup, in the loop and in the
    result FIFO, line reads outstanding, results waiting on back-pressure): afterwards the unit
    is idle with every counter at zero, nothing comes out (the beats of reads issued before the
    reset still arrive and must be dropped), and the next batch is exact."""
    s = seed()
    rng = np.random.default_rng(s + 4)
    prng = random.Random(s + 4)
    h = Harness(dut, prng)
    await h.reset()
    d = h.dut
    pyr = scene_pyr("stones", 64, 64, 8)
    base = h.place(pyr)
    counters = ("cycles", "rays_in", "rays_out", "iters", "lookups", "crossings", "level_ups",
                "descents", "cache_hits", "cache_misses", "mem_bytes", "mem_lines")
    in_flight = []
    for trial in range(4):
        rays = camera_rays(rng, 64, 64, ("grazing", "oblique")[trial % 2], 20)
        case = Case(f"64x64 stones u8 before reset {trial}", pyr, base, rays, ("park",),
                    lat=(0, 60))
        await h.configure(traverse_words.config(pyr, "park", base=base), case)
        stop = int(rng.integers(30, 300))
        got, _, _ = await h.run(traverse_words.ray_words(rays), 0.9, 0.3, max_cycles=stop + 1,
                                stop=stop)
        in_flight.append(h.sent - len(got))
        # reset while the batch is in flight
        d.rst_ni.value = 0
        d.ray_valid_i.value = 0
        d.res_ready_i.value = 1
        await ClockCycles(h.clk, int(rng.integers(1, 6)))
        await FallingEdge(h.clk)
        d.rst_ni.value = 1
        for clk in range(300):          # stale R beats of the old reads arrive in this time
            await FallingEdge(h.clk)
            assert int(d.res_valid_o.value) == 0, f"trial {trial}: a result {clk} clocks after reset"
            assert int(h.s["idle_o"].value) == 1, f"trial {trial}: not idle after reset"
        st = h.stats()
        assert all(st[k] == 0 for k in counters), f"trial {trial}: counters after reset {st}"
        d.res_ready_i.value = 0
        # the next batch, new rays on the same map: exact
        nxt = Case(f"64x64 stones u8 after reset {trial}", pyr, base,
                   camera_rays(rng, 64, 64, "oblique", 16), ("park",), lat=(0, 60))
        o = await run_case(h, nxt, "park", dut._log)
        assert not o["mism"] and not o["sbad"], f"after reset {trial}: {o['mism']} mismatches; " \
                                                f"{o['sbad']}"
    assert max(in_flight) > 0, f"no reset hit rays in flight: {in_flight}"
    print(f"TRAVERSE_SYSTEM reset mid-batch: 4 resets with {in_flight} rays in flight; idle and "
          "zeroed after each, the next batches exact")


@cocotb.test()
async def traverse_system_counters_wrap(dut):
    """Every statistics counter counts modulo 2^48: deposited 1 to 3 counts below the wrap, a
    batch of camera rays carries each of them past it, and the differences (modulo 2^48) must
    still equal the model's counts (run_case's checks)."""
    s = seed()
    rng = np.random.default_rng(s + 2)
    h = Harness(dut, random.Random(s + 2))
    await h.reset()
    pyr = scene_pyr("rocks", 32, 32, 8)
    base = h.place(pyr)
    rays = camera_rays(rng, 32, 32, "oblique", 16)
    case = Case("32x32 rocks u8, counters at 2^48 - 3", pyr, base, rays, ("park",))
    preset = {k: (1 << CNT_BITS[k]) - 1 - (j % 3) for j, k in enumerate(CNT_BITS)}
    o = await run_case(h, case, "park", dut._log, preset=preset)
    after = h.stats()
    unwrapped = [k for k in preset if after[k] >= preset[k]]
    assert not o["mism"] and not o["sbad"], f"{o['mism']} mismatches; {o['sbad']}"
    assert not unwrapped, f"counters that did not pass 2^48 in this batch: {unwrapped}"
    print(f"TRAVERSE_SYSTEM counters wrap: all {len(preset)} counters passed 2^48 and still "
          "agree with the model")


def incoherent_rays(rng: np.random.Generator, size: int, n: int) -> Rays:
    """``n`` rays from uniform positions on a ``size`` x ``size`` map in uniform directions, with
    a horizontal run uniform in [0, size / 2] (scripts/bench/bench_rtl.py --incoherent's rays)."""
    ang = rng.uniform(0.0, 2.0 * np.pi, n)
    run = rng.uniform(0.0, size / 2, n)
    return Rays(rng.uniform(0.0, size, n), rng.uniform(0.0, size, n),
                run * np.cos(ang), run * np.sin(ang))


async def watch_park(dut, tally: dict[str, int]) -> None:
    """Count, at every falling edge, the park queue's events in the ring (traverse_loop's
    park / unpark, the queue's count; traverse_unit's result FIFO full flag)."""
    lp = dut.u_unit.u_loop
    depth = len(lp.pk_v)
    last = 1 << (len(lp.v_q) - 1)   # v_q's bit of the ring's tail
    while True:
        await FallingEdge(dut.clk_i)
        if not int(dut.rst_ni.value):
            continue
        cnt = int(lp.pk_cnt.value)
        park, unpark = int(lp.park.value), int(lp.unpark.value)
        tally["parks"] += park
        tally["unparks"] += unpark
        tally["max_parked"] = max(tally["max_parked"], cnt)
        tally["full"] += cnt == depth
        # a missed ray at the tail that stays in the ring because the queue is full
        if (cnt == depth and not park and not unpark and int(lp.v_q.value) & last
                and not int(lp.done19_q.value) and int(lp.g_park.miss19_q.value)):
            tally["full_stay"] += 1
        tally["backpressure"] += bool(cnt and int(dut.u_unit.rf_full.value))
        tally["depth"] = depth


#: The build with PARK = 1 (test_traverse_system_park) runs only the park queue's test; the
#: default build (PARK = 0, no park queue) skips it.
PARK_BUILD = os.environ.get("TRAVERSE_PARK") == "1"


@cocotb.test(skip=not PARK_BUILD)
async def traverse_system_incoherent_park(dut):
    """Incoherent rays (random positions and directions, like a ray tracer's secondary rays) on
    a 256x256 map, twice: with a slow memory (40 .. 80 clocks per line, AR / R pauses), and with
    the result stream taken in 0.4% of the clocks (the result FIFO fills up).  Most lookups miss,
    so missed rays park, the park queue fills up (missed rays then stay in the ring), parked rays
    wait while the result FIFO is full; every parked ray comes back, every result as the
    model's."""
    s = seed()
    rng = np.random.default_rng(s + 7)
    h = Harness(dut, random.Random(s + 7))
    await h.reset()
    pyr = scene_pyr("rocks", 256, 256, 8)
    base = h.place(pyr)
    runs = [Case("256x256 rocks u8 incoherent, slow memory", pyr, base,
                 incoherent_rays(rng, 256, scale(300)), ("park",), valid_p=1.0, ready_p=0.5,
                 ar_pause=0.3, r_pause=0.3, lat=(40, 80)),
            Case("256x256 rocks u8 incoherent, results stalled", pyr, base,
                 incoherent_rays(rng, 256, scale(300)), ("park-xor",), valid_p=1.0,
                 ready_p=0.004, ar_pause=0.0, r_pause=0.0, lat=(10, 30))]
    tally = dict.fromkeys(("parks", "unparks", "max_parked", "full", "full_stay",
                           "backpressure", "depth"), 0)
    mon = cocotb.start_soon(watch_park(dut, tally))
    bad = []
    for case in runs:
        for method in case.methods:
            o = await run_case(h, case, method, dut._log)
            if o["mism"] or o["sbad"]:
                bad.append(f"{o['name']}: {o['mism']} mismatches; {o['sbad']}")
    mon.cancel()
    msg = (f"TRAVERSE_SYSTEM park queue: {tally['parks']} parked, {tally['unparks']} back, "
           f"at most {tally['max_parked']} of {tally['depth']} parked, full {tally['full']} "
           f"clocks ({tally['full_stay']} missed rays stayed in the ring), "
           f"{tally['backpressure']} clocks parked rays with the result FIFO full")
    dut._log.info(msg)
    print(msg)
    assert not bad, "; ".join(bad)
    assert tally["parks"] > 0 and tally["parks"] == tally["unparks"], msg
    assert tally["max_parked"] == tally["depth"] and tally["full_stay"] > 0, msg
    assert tally["backpressure"] > 0, msg


def test_traverse_system():
    # A 4 KiB cache (the defaults are 32 KiB): these batches then evict and refill lines often.
    runner.run("traverse_system", "test_traverse_system", HERE, parameters={"SETS": 64, "WAYS": 2})


def test_traverse_system_park():
    # The ring with its park queue (PARK = 1; off by default), the same 4 KiB cache.  A queue of
    # 8 entries (the default is 16): the batches then fill it while its head has not waited
    # PARK_WAIT clocks, so a missed ray must stay in the ring (full_stay).
    runner.run("traverse_system", "test_traverse_system", HERE,
               parameters={"SETS": 64, "WAYS": 2, "PARK": 1, "PARK_DEPTH": 8},
               extra_env={"TRAVERSE_PARK": "1"}, testcase="traverse_system_incoherent_park")
