# SPDX-License-Identifier: Apache-2.0
"""tex_cache: every response against the memory's bytes, in request order.

Memory: cocotbext-axi's AxiRamRead (sparse) holding random RGBA textures with their MIP chains
(model.texture.build + memory_image) at different bases: a 256x256 colour texture, a 256x256
normal map and a 100x75 texture (widths that are not powers of two).  Its read process is
replaced (``TexRam``) by a pipelined one: every burst gets its own random latency (from the AR
handshake to its first beat), the bursts return in order or, with ``reorder``, as they become
ready (same-ID order kept); the AR and R channels take cocotbext-axi pause generators; beats
overlapping chosen byte ranges answer SLVERR; a read outside the images is recorded (and fails
the test).  The memory is never reset: reads in flight at a cache reset still return.

Requests (tb/tex_cache/quads.py): camera-like walks (perspective views in 8x8 tiles, MIP levels
from the footprint, a colour and a normal-map quad per pixel), random quads (random levels and
positions, clamped edges, repeats) and four unrelated addresses; random valid gaps and random
rsp_ready back-pressure.

Checked: every response against the head of the queue of accepted requests (tag = sequence
number, so nothing is lost, duplicated or reordered), its texels against the memory (unless its
err flag is expected), rsp_err_o = 1 exactly for the quads with a line that answers SLVERR; no
response left over; the statistics (requests, line lookups = model.tex_cache.passes, line misses =
AR handshakes, bytes = misses * LINE_BYTES); the directory, clock by clock on every stream:
each pass entering the request FIFO must look up the lines model.tex_cache.passes gives and hit,
miss and choose its way (the hit way or the victim) in every sub-cache exactly as
model.tex_cache.TexCacheTimedModel does, fed with the clocks of the RTL's head reads (reference
releases) and error fills; the hit / miss counters equal that model's; the RTL's SVA (Verilator --assert), among them no
eviction of a referenced line and a simulation-only check that each slot read holds its line.

Measured (``realistic_throughput``): quads per clock and hit rates on the camera stream with a
fixed latency of 20 clocks, no pauses, no back-pressure (TC_VIEWS views of 64x64 pixels).
Lines go to build/sim/tex_cache/perf.jsonl.

Environment: SEED, TC_SCALE (stream-length factor; default SCALES below, TB_LONG=1 LONG_SCALES),
TC_VIEWS (camera views for the measurement, default 3 x TC_SCALE), TC_LATS (latencies measured,
default "20"), WAVES=1.
"""
from __future__ import annotations

import json
import logging
import os
import random
from collections import Counter, deque
from pathlib import Path

import cocotb
import numpy as np
import pytest
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge
from cocotbext.axi import AxiRamRead, AxiReadBus

from model.height_cache import clog2
from model.tex_cache import (Blocked, TexCacheConfig, TexCacheModel, TexCacheTimedModel, passes,
                             window_fits)
from tb.common import report, runner

import quads as Q

HERE = Path(__file__).resolve().parent
PERF = runner.BUILD / "tex_cache" / "perf.jsonl"
CONFIGS = {
    "default": TexCacheConfig(),
    # 2 KiB, 64-byte lines over a 32-bit bus read in 4 windows of 4 words, 8-pass FIFO, 4 MSHRs:
    # pinned ways, MSHR waits, window splits
    "small": TexCacheConfig(data_w=32, line_bytes=64, sets=4, ways=2, mshrs=4, fifo_depth=8,
                            id_w=4, tag_w=6, win_words=4),
    # the default cache with 8-word windows (4 beats per window, the select from 36 words)
    "wide": TexCacheConfig(win_words=8),
}
BASES = (0x1000_0000, 0x1040_0000, 0x2000_0000)
#: The RTL's simulation-only coverage points (sim_<name> in the bound tex_cache_assert, u_assert),
#: counted per clock.
COVER = ("merge", "victim_wait", "mshr_wait", "fifo_full", "split", "stale_beat", "err_fill",
         "err_pass", "victim_redirect", "win_split", "overlap")


#: The RTL's internal signals the directory check reads (tex_cache's names; one place to re-point
#: them should the module be split): the pass entering the FIFO (e_fire) with its sub-caches
#: (lk_v), lines (lk_la), misses (lk_alloc) and ways (lk_way, the hit way or the victim); the
#: head's read (h_pop); a line completing (w_fill_q), with an error (w_bad_q), its sub-cache and
#: line address (w_sub_q, w_la_q).
PROBES = {"fire": "e_fire", "used": "lk_v", "la": "lk_la", "alloc": "lk_alloc", "way": "lk_way",
          "pop": "h_pop", "fill": "w_fill_q", "bad": "w_bad_q", "fsub": "w_sub_q",
          "fla": "w_la_q"}


def probe(dut, name: str):
    """The handle of PROBES[name] (a hierarchical path under the DUT, dots between levels)."""
    h = dut
    for part in PROBES[name].split("."):
        h = getattr(h, part)
    return h


#: The statistics outputs (stat_<name>_o) and the counter register behind each.
STAT_REGS = {"requests": "st_req_q", "quad_hits": "st_qhit_q", "lookups": "st_lk_q",
             "line_misses": "st_miss_q", "texel_hits": "st_thit_q", "bytes": "st_bytes_q"}


def config() -> TexCacheConfig:
    return TexCacheConfig(**json.loads(os.environ.get("TC_CFG", "{}")))


def seed() -> int:
    s = int(os.environ.get("SEED", random.randrange(1 << 31)))
    cocotb.log.info("SEED=%d", s)
    print(f"SEED={s}")
    return s


def scale(n: int) -> int:
    return max(50, int(n * float(os.environ.get("TC_SCALE", "1.0"))))


def pauses(rng: random.Random, p: float):
    while True:
        yield rng.random() < p


def overlaps(ranges, lo: int, hi: int) -> bool:
    return any(a < hi and lo < b for a, b in ranges)


class TexRam(AxiRamRead):
    """AxiRamRead with a pipelined, per-burst random latency (see the module docstring)."""

    def __init__(self, bus, clock, rng: random.Random, **kwargs):
        self.rng = rng
        self.clk = clock
        self.lat = (0, 0)
        self.reorder = False
        self.err_ranges: list[tuple[int, int]] = []
        self.regions: list[tuple[int, int]] = []
        self.outside: list[int] = []
        self.bursts: list[dict] = []      # accepted, not yet sent (AR order)
        self.sending = 0                  # bursts being sent
        self.cur_id = 0
        self.now = 0
        self.lat_seen: list[int] = []     # AR handshake to first beat offered, clocks
        self.err_beats = 0
        super().__init__(bus, clock, reset=None, **kwargs)
        self.ar_channel.queue_occupancy_limit = 64
        cocotb.start_soon(self._count())

    async def _count(self):
        while True:
            await RisingEdge(self.clk)
            self.now += 1

    def outstanding_ids(self) -> list[int]:
        return [b["id"] for b in self.bursts] + ([self.cur_id] if self.sending else [])

    async def _accept(self):
        while True:
            ar = await self.ar_channel.recv()
            self.bursts.append({"id": int(ar.arid), "addr": int(ar.araddr),
                                "len": int(ar.arlen) + 1, "size": int(ar.arsize),
                                "t0": self.now, "t": self.now + self.rng.randint(*self.lat)})

    def _pick(self):
        seen = set()
        best = None
        for b in self.bursts:
            if b["id"] in seen:
                continue
            seen.add(b["id"])
            if b["t"] <= self.now and (best is None or b["t"] < best["t"]):
                best = b
            if not self.reorder:
                break
        return best

    async def _process_read(self):
        cocotb.start_soon(self._accept())
        while True:
            b = self._pick()
            if b is None:
                await RisingEdge(self.clk)
                continue
            self.bursts.remove(b)
            self.sending, self.cur_id = 1, b["id"]
            self.lat_seen.append(self.now - b["t0"])
            n = 1 << b["size"]
            for k in range(b["len"]):
                a = b["addr"] + k * n
                r = self.r_channel._transaction_obj()
                r.rid, r.rlast, r.rresp = b["id"], int(k == b["len"] - 1), 0
                if not any(lo <= a and a + n <= hi for lo, hi in self.regions):
                    self.outside.append(a)
                if overlaps(self.err_ranges, a, a + n):
                    self.err_beats += 1
                    r.rresp, data = 2, bytes(n)           # SLVERR
                else:
                    data = await self._read(a, n)
                r.rdata = int.from_bytes(data, "little")
                await self.r_channel.send(r)
            self.sending = 0


class Harness:
    def __init__(self, dut, rng: random.Random, nrng: np.random.Generator):
        # own generators for the handshakes and the memory: the streams a test draws from ``rng``
        # do not depend on how many clocks earlier runs took
        self.dut, self.rng = dut, random.Random(rng.randrange(1 << 62))
        self.cfg = config()
        dut.rst_ni.value = 0      # in reset from the first edge on
        dut.req_valid_i.value = 0
        cocotb.start_soon(Clock(dut.clk_i, 10, unit="ns").start(start_high=False))
        # the memory's own generator: the streams do not depend on how many draws it makes
        self.ram = TexRam(AxiReadBus.from_prefix(dut, "m_axi"), dut.clk_i,
                          random.Random(rng.randrange(1 << 62)), size=1 << 32)
        self.ram.log.setLevel(logging.ERROR)
        self.texs = [Q.Placed(Q.random_texture(nrng, 256, 256), BASES[0], "colour 256x256"),
                     Q.Placed(Q.random_texture(nrng, 256, 256), BASES[1], "normal 256x256"),
                     Q.Placed(Q.random_texture(nrng, 75, 100), BASES[2], "npot 100x75")]
        self.mem: dict[int, bytes] = {}
        for p in self.texs:
            img = p.tex.memory_image()
            self.ram.write(p.base, img)
            self.ram.regions.append((p.base, p.base + len(img)))
            self.mem[p.base] = img
        self.s = {n: getattr(dut, n) for n in (
            "rst_ni", "req_valid_i", "req_ready_o", "req_addr_i", "req_tag_i", "rsp_valid_o",
            "rsp_ready_i", "rsp_texel_o", "rsp_err_o", "rsp_tag_o", "clr_stats_i",
            "m_axi_arvalid", "m_axi_arready", "m_axi_arid")}
        for k in ("req_valid_i", "rsp_ready_i", "clr_stats_i", "req_addr_i", "req_tag_i"):
            self.s[k].value = 0
        self.s["rst_ni"].value = 0
        self.seq = 0             # sequence number of the next request
        self.bad: list[str] = []
        self.checked = 0         # responses compared
        self.flagged = 0         # responses with rsp_err_o
        self.cnt = {"requests": 0, "lookups": 0, "lines": 0}  # since the last clear / reset
        self.stat_base: dict[str, int] = {}  # the last preset (Harness.preset)
        self.epoch = None        # the RTL's epoch (from arid)
        self.inflight: Counter = Counter()  # line reads issued and not finished, by arid
        self.cov: Counter = Counter()       # clocks with each of the RTL's sim_* coverage points
        # the directory check (model.tex_cache.TexCacheTimedModel), every clock of every stream
        self.tm = TexCacheTimedModel(self.cfg)
        self.tm_passes: deque = deque()     # (pass, last) of accepted requests, not yet decided
        self.decided = 0                    # passes whose hit / miss / way were compared
        self.tm_bad = 0                     # decisions that differed
        cocotb.start_soon(self.monitor())

    # ---------------------------------------------------------------- expectations
    def word(self, a: int) -> int:
        for p in self.texs:
            if p.base <= a < p.base + p.size:
                o = a - p.base
                return int.from_bytes(self.mem[p.base][o:o + 4], "little")
        raise AssertionError(f"address {a:#x} outside the textures")

    def line_bad(self, a: int) -> bool:
        lb = self.cfg.line_bytes
        lo = a & ~(lb - 1)
        return overlaps(self.ram.err_ranges, lo, lo + lb)

    def set_errors(self, ranges) -> None:
        self.ram.err_ranges = list(ranges)

    def stats(self) -> dict[str, int]:
        d = self.dut
        raw = {k: int(getattr(d, f"stat_{k}_o").value) for k in STAT_REGS}
        # counts since the last preset (modulo the counters' 48 bits); plain values without one
        return {k: (v - self.stat_base.get(k, 0)) % (1 << 48) for k, v in raw.items()}

    def preset(self, values: dict[str, int]) -> None:
        """Deposit values into the statistics counter registers (names as :meth:`stats`); later
        :meth:`stats` reads count from there, modulo 2^48."""
        for k, v in values.items():
            getattr(self.dut, STAT_REGS[k]).value = v
        self.stat_base = dict(values)

    async def monitor(self) -> None:
        """At each rising edge (cocotbext-axi's sampling point: the values before the edge), the
        handshakes: requests and their lookups (model.tex_cache.passes), AR (the RTL's statistics
        count nothing in a clock with reset or clr_stats_i), R last beats; the RTL's epoch."""
        d = self.dut
        sig = [getattr(d, n) for n in ("rst_ni", "clr_stats_i", "req_valid_i", "req_ready_o",
                                       "req_addr_i", "m_axi_arvalid", "m_axi_arready",
                                       "m_axi_arid", "m_axi_rvalid", "m_axi_rlast", "m_axi_rid")]
        cov = {n: getattr(d.u_assert, f"sim_{n}") for n in COVER}  # (tex_cache_assert)
        pr = [probe(d, n) for n in ("fire", "pop", "fill")]
        pr_fire = [probe(d, n) for n in ("used", "la", "alloc", "way")]
        pr_fill = [probe(d, n) for n in ("bad", "fsub", "fla")]
        c = self.cfg
        prev_rst = 1
        while True:
            await RisingEdge(d.clk_i)
            rst, clr, rv, rr, ra, av, ar, aid, v, last, rid = (int(x.value) for x in sig)
            fire, pop, fill = (int(x.value) for x in pr)
            if not rst:
                self.tm.reset()
                self.tm_passes.clear()
            else:
                self.directory(clr, fire, pop, fill, pr_fire, pr_fill)
            for n, x in cov.items():
                self.cov[n] += int(x.value)
            if av and ar:
                self.inflight[aid] += 1
                self.epoch = aid >> c.midx_w
            if v and last:                      # rready is 1
                self.inflight[rid] -= 1
                if not self.inflight[rid]:
                    del self.inflight[rid]
            if not rst and prev_rst and self.epoch is not None:
                self.epoch = (self.epoch + 1) % (1 << c.epoch_w)
            prev_rst = rst
            if rst and rv and rr:
                q = [(ra >> (c.addr_w * t)) & ((1 << c.addr_w) - 1) for t in range(4)]
                ps = passes(q, c)
                self.tm_passes.extend((p, k == len(ps) - 1) for k, p in enumerate(ps))
            if not rst or clr:
                self.cnt = {k: 0 for k in self.cnt}
                continue
            if rv and rr:
                self.cnt["requests"] += 1
                self.cnt["lookups"] += sum(len(p.lines) for p in ps)
            if av and ar:
                self.cnt["lines"] += 1

    def directory(self, clr: int, fire: int, pop: int, fill: int, pr_fire, pr_fill) -> None:
        """One clock of the directory check: the pass entering the FIFO in this clock must look
        up the lines model.tex_cache.passes gives, in the same sub-caches, and hit, miss and
        choose its ways exactly as TexCacheTimedModel (reference counts included) says."""
        try:
            self._directory(clr, fire, pop, fill, pr_fire, pr_fill)
        except AssertionError as e:  # the model's own checks (reference underflow, ...)
            self.tm_bad += 1
            self.bad.append(f"directory: clock {self.now}: model: {e}")

    def _directory(self, clr: int, fire: int, pop: int, fill: int, pr_fire, pr_fill) -> None:
        tm = self.tm
        tm.step(bool(clr))
        if fire:
            used, la, alloc, way = (int(x.value) for x in pr_fire)
            c = self.cfg
            law = c.addr_w - c.off_w
            ww = clog2(c.ways) or 1
            if not self.tm_passes:
                self.bad.append(f"directory: clock {self.now}: a pass enters with none expected")
                return
            p, last = self.tm_passes.popleft()
            got_la = {k: (la >> (law * k)) & ((1 << law) - 1) for k in range(4) if used >> k & 1}
            if got_la != p.lines:
                self.tm_bad += 1
                self.bad.append(f"directory: clock {self.now}: pass {self.decided} looks up "
                                f"{ {k: hex(v) for k, v in got_la.items()} }, model "
                                f"{ {k: hex(v) for k, v in p.lines.items()} }")
            try:
                out = tm.decide(p, last)
            except Blocked as e:
                self.tm_bad += 1
                self.bad.append(f"directory: clock {self.now}: pass {self.decided}: model: {e}")
                return
            differs = False
            for lk in out:
                g_miss = (alloc >> lk.sub) & 1
                g_way = (way >> (ww * lk.sub)) & ((1 << ww) - 1)
                if g_miss != (not lk.hit) or g_way != lk.way:
                    differs = True
                    if self.tm_bad < 8:
                        self.bad.append(
                            f"directory: clock {self.now}: pass {self.decided} sub-cache "
                            f"{lk.sub} set {lk.set} line {lk.la:#x}: RTL "
                            f"{'miss' if g_miss else 'hit'} way {g_way}, model "
                            f"{'hit' if lk.hit else 'miss'} way {lk.way}")
            self.tm_bad += differs
            self.decided += 1
        if pop:
            tm.pop()
        if fill and int(pr_fill[0].value):
            tm.error(int(pr_fill[1].value), int(pr_fill[2].value))

    # ---------------------------------------------------------------- clocking
    async def reset(self, clocks=4) -> None:
        s = self.s
        s["rst_ni"].value = 0
        self.stat_base = {}                 # the counters restart from zero
        s["req_valid_i"].value = 0
        s["rsp_ready_i"].value = 0
        for _ in range(clocks):
            await FallingEdge(self.dut.clk_i)
        s["rst_ni"].value = 1
        await FallingEdge(self.dut.clk_i)   # the first clock out of reset: no request

    @property
    def now(self) -> int:
        return self.ram.now

    def reset_allowed(self) -> bool:
        """A reset must not bring the epoch back to that of a read still outstanding."""
        if self.epoch is None:
            return True
        c = self.cfg
        nxt = (self.epoch + 1) % (1 << c.epoch_w)
        return all((i >> c.midx_w) != nxt for i in self.inflight)

    async def run(self, stream, valid_p=1.0, ready_p=1.0, events=None, max_clocks=None,
                  what="") -> dict:
        """Send ``stream``, check every response; returns clocks and counts.  ``events(h)`` may
        return 'reset', 'clear' or None for each clock."""
        s = self.s
        clk = self.dut.clk_i
        c = self.cfg
        tag_mask = (1 << c.tag_w) - 1
        pending: deque = deque()     # accepted, not answered: (seq, quad, err expected)
        nxt = 0
        presenting = False
        rnd = self.rng.random
        req_valid, req_ready, req_addr, req_tag = (s[k] for k in (
            "req_valid_i", "req_ready_o", "req_addr_i", "req_tag_i"))
        rsp_valid, rsp_ready, rsp_texel, rsp_err, rsp_tag = (s[k] for k in (
            "rsp_valid_o", "rsp_ready_i", "rsp_texel_o", "rsp_err_o", "rsp_tag_o"))
        max_clocks = max_clocks or 200 * len(stream) + 50000
        first = last = None
        clocks = 0
        lost = resets = clears = 0
        answered = 0
        while nxt < len(stream) or pending or presenting:
            if clocks > max_clocks:
                raise AssertionError(f"{what}: timeout, {nxt} of {len(stream)} sent, "
                                     f"{len(pending)} unanswered")
            ev = events(self) if events else None
            if ev == "reset":
                lost += len(pending)
                pending.clear()
                presenting = False      # not accepted: presented again after the reset
                resets += 1
                await self.reset(self.rng.randint(1, 5))
                clocks += 1
                continue
            # this clock's request
            if not presenting and nxt < len(stream) and rnd() < valid_p:
                q = stream[nxt]
                req_addr.value = sum(a << (c.addr_w * t) for t, a in enumerate(q))
                req_tag.value = self.seq & tag_mask
                req_valid.value = 1
                presenting = True
            fire_req = presenting and int(req_ready.value)
            # this clock's response
            ready_now = int(rnd() < ready_p)
            rsp_ready.value = ready_now
            if ready_now and int(rsp_valid.value):
                self.check(pending, int(rsp_texel.value), int(rsp_err.value),
                           int(rsp_tag.value), tag_mask)
                answered += 1
                last = clocks
            clr = int(ev == "clear")
            s["clr_stats_i"].value = clr
            if clr:
                clears += 1
            await FallingEdge(clk)
            clocks += 1
            if fire_req:
                q = stream[nxt]
                errq = any(self.line_bad(a) for a in q)
                pending.append((self.seq, q, errq))
                if first is None:
                    first = clocks - 1
                self.seq += 1
                nxt += 1
                presenting = False
                req_valid.value = 0
            s["clr_stats_i"].value = 0
        # nothing more may come out
        rsp_ready.value = 1
        for _ in range(40):
            await FallingEdge(clk)
            if int(rsp_valid.value):
                self.bad.append(f"{what}: response without a request (tag {int(rsp_tag.value)})")
        rsp_ready.value = 0
        span = (last - first + 1) if first is not None and last is not None else 0
        return {"quads": len(stream), "answered": answered, "clocks": clocks, "span": span,
                "lost": lost, "resets": resets, "clears": clears}

    def check(self, pending: deque, texel: int, err: int, tag: int, tag_mask: int) -> None:
        self.checked += 1
        if not pending:
            self.bad.append(f"response (tag {tag}) with no request outstanding")
            return
        seq, q, errq = pending.popleft()
        if tag != seq & tag_mask:
            self.bad.append(f"request {seq}: response tag {tag}, expected {seq & tag_mask} "
                            "(lost, duplicated or reordered)")
            return
        if err != errq:
            self.bad.append(f"request {seq} {[hex(a) for a in q]}: rsp_err_o {err}, expected "
                            f"{int(errq)}")
            return
        self.flagged += err
        if not err:
            for t in range(4):
                got = (texel >> (32 * t)) & 0xFFFF_FFFF
                exp = self.word(q[t])
                if got != exp:
                    self.bad.append(f"request {seq} texel {t} at {q[t]:#x}: {got:#010x}, "
                                    f"memory {exp:#010x}")

    async def drain(self, max_clocks=20000) -> None:
        """Clock until no read is outstanding."""
        for _ in range(max_clocks):
            await FallingEdge(self.dut.clk_i)
            if not self.inflight and not self.ram.outstanding_ids() \
                    and not int(self.s["m_axi_arvalid"].value):
                break
        else:
            raise AssertionError("drain: reads still outstanding")
        for _ in range(8):
            await FallingEdge(self.dut.clk_i)

    def check_stats(self, what: str, exact_lookups=True) -> dict[str, int]:
        st = self.stats()
        lb = self.cfg.line_bytes
        probs = []
        if st["requests"] != self.cnt["requests"]:
            probs.append(f"requests {st['requests']} != {self.cnt['requests']}")
        if exact_lookups and st["lookups"] != self.cnt["lookups"]:
            probs.append(f"lookups {st['lookups']} != model {self.cnt['lookups']}")
        if st["line_misses"] != self.cnt["lines"]:
            probs.append(f"line misses {st['line_misses']} != AR handshakes {self.cnt['lines']}")
        if st["bytes"] != st["line_misses"] * lb:
            probs.append(f"bytes {st['bytes']} != line misses {st['line_misses']} x {lb}")
        # A hit quad is four texel hits; a texel that missed is one whose line lookup missed,
        # and every missed lookup serves at least one texel (when every request counted was
        # looked up in the same counting interval).
        texels_ok = (4 * st["quad_hits"] <= st["texel_hits"] <= 4 * st["requests"]
                     and st["line_misses"] <= 4 * st["requests"] - st["texel_hits"])
        if (not st["quad_hits"] <= st["requests"] or not st["line_misses"] <= st["lookups"]
                or (exact_lookups and not texels_ok)):
            probs.append(f"counts out of range {st}")
        probs += self.model_stats(st)
        if self.ram.outside:
            probs.append(f"reads outside the images: {[hex(a) for a in self.ram.outside[:4]]}")
        for p in probs:
            self.bad.append(f"{what}: statistics: {p}")
        return st

    def model_stats(self, st: dict[str, int]) -> list[str]:
        """The RTL's hit / miss counters against model.tex_cache.TexCacheTimedModel's (the same
        decisions, counted as the RTL counts them)."""
        return [f"{k} {st[k]} != model {self.tm.stats[k]}" for k in self.tm.stats
                if st[k] != self.tm.stats[k]]

    def finish(self, what: str, need: tuple[str, ...] = ()) -> None:
        """Record the counts; fail on any mismatch or a coverage point in ``need`` never hit."""
        if not self.decided:
            self.bad.append(f"{what}: the directory check saw no pass")
        for k in need:
            if not self.cov[k]:
                self.bad.append(f"{what}: coverage point sim_{k} never hit")
        report.record("tex_cache", "quads vs memory", self.checked, len(self.bad))
        msg = (f"VECTORS tex_cache {what}: {self.checked} responses checked ({self.flagged} "
               f"flagged), {self.decided} passes' hits, misses and ways compared with "
               f"model.tex_cache ({self.tm_bad} differ), {len(self.bad)} mismatches; coverage "
               "(clocks): "
               + ", ".join(f"{k} {self.cov[k]}" for k in COVER))
        self.dut._log.info(msg)
        print(msg)
        if self.bad:
            raise AssertionError(f"{len(self.bad)} mismatches, first: " + "; ".join(self.bad[:8]))


def summary(h: Harness, r: dict, st: dict, what: str, model: dict | None = None) -> dict:
    out = {"what": what, "cfg": h.cfg.__dict__, "quads": r["quads"], "span": r["span"],
           "quads_per_clock": r["quads"] / max(r["span"], 1),
           "quad_hit_rate": st["quad_hits"] / max(st["requests"], 1),
           "texel_hit_rate": st["texel_hits"] / max(4 * st["requests"], 1),
           "line_hit_rate": 1 - st["line_misses"] / max(st["lookups"], 1),
           "lines_per_quad": st["line_misses"] / max(st["requests"], 1),
           "lookups_per_quad": st["lookups"] / max(st["requests"], 1),
           "bytes": st["bytes"]}
    if h.ram.lat_seen:
        out["mem_latency_mean"] = sum(h.ram.lat_seen) / len(h.ram.lat_seen)
    if model:
        out["model_quad_hit_rate"] = model["quad_hits"] / max(model["requests"], 1)
        out["model_passes_per_quad"] = model["passes"] / max(model["requests"], 1)
    msg = (f"TEX_CACHE {what}: {r['quads']} quads in {r['span']} clocks = "
           f"{out['quads_per_clock']:.3f} quads/clock; quad hit rate {out['quad_hit_rate']:.3f}, "
           f"texel hit rate {out['texel_hit_rate']:.3f}, "
           f"line hit rate {out['line_hit_rate']:.3f}, {out['lines_per_quad']:.3f} line reads "
           f"per quad, {out['lookups_per_quad']:.2f} lookups per quad"
           + (f"; model: quad hit rate {out['model_quad_hit_rate']:.3f}, "
              f"{out['model_passes_per_quad']:.3f} passes per quad" if model else "")
           + (f"; memory latency seen {out['mem_latency_mean']:.1f}" if h.ram.lat_seen else ""))
    h.dut._log.info(msg)
    print(msg)
    PERF.parent.mkdir(parents=True, exist_ok=True)
    with open(PERF, "a") as f:
        f.write(json.dumps(out) + "\n")
    return out


def new_harness(dut) -> tuple[Harness, random.Random]:
    s = seed()
    rng = random.Random(s)
    return Harness(dut, rng, np.random.default_rng(s)), rng


@cocotb.test()
async def realistic_throughput(dut):
    """Camera stream (colour + normal map, both 256x256), latency 20, no pauses, no back-pressure,
    from an empty cache; then the same with a 100x75 colour texture (widths that are not powers of
    two).  TC_LATS (default "20") lists the latencies to measure."""
    h, rng = new_harness(dut)
    views = int(os.environ.get("TC_VIEWS", max(1, round(3 * float(os.environ.get("TC_SCALE",
                                                                                  "1"))))))
    lats = [int(x) for x in os.environ.get("TC_LATS", "20").split(",")]
    cases = [("camera 256x256 + 256x256", h.texs[:2]),
             ("camera 100x75 + 256x256", [h.texs[2], h.texs[0]])]
    streams = [Q.camera(rng, texs, views) for _, texs in cases]
    for (name, texs), stream in zip(cases, streams):
        dut._log.info("%s: quads per level: %s", name, Q.levels_used(texs, stream))
        model = TexCacheModel(h.cfg).run(stream)
        for lat in lats:
            h.ram.lat = (lat, lat)
            await h.reset()
            h.ram.lat_seen.clear()
            redirects = h.cov["victim_redirect"]
            r = await h.run(stream, what=name)
            await h.drain()
            st = h.check_stats(name)
            summary(h, r, st, f"{name}, latency {lat}", model)
            # (every decision was compared with model.tex_cache.TexCacheTimedModel clock by
            # clock, and the counters in check_stats; the model without references, for scale)
            dut._log.info("%s: %d clocks with a victim changed by a reference; model without "
                          "references: %d line misses, RTL %d", name,
                          h.cov["victim_redirect"] - redirects, model["line_misses"],
                          st["line_misses"])
    h.finish("realistic throughput")


async def stress(h: Harness, rng: random.Random, what: str, errors: bool, events=None,
                 lat=(0, 100), valid_p=0.85, ready_p=0.7, exact_lookups=True) -> None:
    h.ram.lat = lat
    h.ram.reorder = True
    h.ram.ar_channel.set_pause_generator(pauses(rng, 0.3))
    h.ram.r_channel.set_pause_generator(pauses(rng, 0.3))
    cam = Q.camera(rng, h.texs[:2], 1, 48, 48) + Q.camera(rng, [h.texs[2], h.texs[1]], 1, 32, 32)
    rq = Q.random_quads(rng, h.texs, scale(3000))
    ra = Q.random_addrs(rng, h.texs, scale(600))
    rl = Q.random_lines(rng, h.texs, scale(600), h.cfg.line_bytes)
    chunks = [cam[i:i + 64] for i in range(0, len(cam), 64)] + \
             [rq[i:i + 32] for i in range(0, len(rq), 32)] + \
             [x[i:i + 8] for x in (ra, rl) for i in range(0, len(x), 8)]
    rng.shuffle(chunks)
    stream = [q for ch in chunks for q in ch][:scale(len(cam) + len(rq) + len(ra) + len(rl))]
    if errors:
        lb = h.cfg.line_bytes
        used = sorted({a & ~(lb - 1) for q in stream for a in q})
        ranges = []
        for a in rng.sample(used, max(1, len(used) // 40)):
            k = rng.choice(["line", "beat", "byte"])
            off = rng.randrange(lb)
            ranges.append((a, a + lb) if k == "line" else
                          (a + off - off % h.cfg.beat_bytes,
                           a + off - off % h.cfg.beat_bytes + h.cfg.beat_bytes) if k == "beat"
                          else (a + off, a + off + 1))
        h.set_errors(ranges)
    r = await h.run(stream, valid_p=valid_p, ready_p=ready_p, events=events, what=what)
    await h.drain()
    if r["clears"]:   # a clear between a miss and its AR / beats: the counts do not pair up
        st = h.stats()
        h.bad += [f"{what}: statistics: {p}" for p in h.model_stats(st)]
    else:
        st = h.check_stats(what, exact_lookups=exact_lookups and not r["resets"])
    summary(h, r, st, what)
    nerr = sum(any(h.line_bad(a) for a in q) for q in stream)
    dut = h.dut
    dut._log.info("%s: %d quads, %d expected flagged, %d flagged; %d error beats; lost to resets "
                  "%d; resets %d; clears %d", what, len(stream), nerr, h.flagged, h.ram.err_beats,
                  r["lost"], r["resets"], r["clears"])
    if errors:
        assert nerr > 0 and h.flagged > 0 and h.ram.err_beats > 0
    return r


@cocotb.test()
async def random_stress(dut):
    """Camera walks, random quads, clamped edges, repeats and unrelated addresses; latency
    0..100 out of order, AR / R pauses, valid gaps, rsp_ready back-pressure."""
    h, rng = new_harness(dut)
    await h.reset()
    await stress(h, rng, "random stress", errors=False)
    # windows (more than one per line): a pass split by them, a read of the overlap word
    windows = ("win_split", "overlap") if h.cfg.window_words < h.cfg.line_bytes // 4 else ()
    h.finish("random stress", need=("merge", "split", "mshr_wait", "fifo_full") + windows)


@cocotb.test()
async def slverr(dut):
    """SLVERR on about 2.5% of the lines the stream reads (whole lines, single beats, bytes): those
    quads answer rsp_err_o, the others their texels; then the memory recovers and the same stream
    reads correctly (bad lines were not kept)."""
    h, rng = new_harness(dut)
    await h.reset()
    await stress(h, rng, "SLVERR", errors=True)
    h.set_errors([])
    flagged = h.flagged
    h.s["clr_stats_i"].value = 1
    await FallingEdge(dut.clk_i)
    h.s["clr_stats_i"].value = 0
    stream = Q.random_quads(rng, h.texs, scale(1500))
    r = await h.run(stream, valid_p=0.9, ready_p=0.8, what="after SLVERR")
    await h.drain()
    st = h.check_stats("after SLVERR")
    summary(h, r, st, "after SLVERR")
    assert h.flagged == flagged
    h.finish("SLVERR", need=("err_fill", "err_pass", "merge"))


@cocotb.test()
async def reset_in_flight(dut):
    """Resets (1-5 clocks) while reads are in flight (latency 30..100, the memory not reset: old
    beats keep arriving with old epochs) and statistics clears; every request accepted after a
    reset is answered correctly."""
    h, rng = new_harness(dut)
    await h.reset()
    plan = {"next": 400, "resets": 0, "held": 0}

    def events(hh: Harness):
        if hh.now >= plan["next"] and hh.inflight:
            if not hh.reset_allowed():
                plan["held"] += 1
                return None
            plan["resets"] += 1
            plan["next"] = hh.now + (rng.randint(3, 10) if rng.random() < 0.3
                                     else rng.randint(300, 1200))
            return "reset"
        if rng.random() < 0.002:
            return "clear"
        return None

    r = await stress(h, rng, "reset in flight", errors=True, events=events, lat=(30, 100),
                     exact_lookups=False)
    assert r["resets"] >= 3 and r["lost"] > 0, (r, plan)
    # after all that: a clean stream with exact statistics
    h.s["clr_stats_i"].value = 1
    await FallingEdge(dut.clk_i)
    h.s["clr_stats_i"].value = 0
    stream = Q.camera(rng, h.texs[:2], 1, 32, 32)
    r2 = await h.run(stream, valid_p=0.9, ready_p=0.9, what="after resets")
    await h.drain()
    st = h.check_stats("after resets")
    summary(h, r2, st, f"after {r['resets']} resets")
    h.finish("reset in flight", need=("stale_beat", "err_pass"))


@cocotb.test()
async def backpressure(dut):
    """Long response stalls (rsp_ready 10%): the FIFO fills, lines stay referenced for long, the
    entry waits for unreferenced victims and MSHRs."""
    h, rng = new_harness(dut)
    await h.reset()
    h.ram.lat = (0, 60)
    h.ram.reorder = True
    stream = Q.random_quads(rng, h.texs, scale(800)) + Q.random_addrs(rng, h.texs, scale(200))
    rng.shuffle(stream)
    # then more lines of one set than it has ways, while the FIFO is still full of passes that
    # reference lines: the lookup must wait for a victim (sim_victim_wait), whatever the seed
    stream += Q.set_conflicts(h.texs, h.cfg)
    r = await h.run(stream, valid_p=1.0, ready_p=0.1, what="back-pressure")
    await h.drain()
    st = h.check_stats("back-pressure")
    summary(h, r, st, "back-pressure (rsp_ready 10%)")
    h.finish("back-pressure", need=("victim_wait", "mshr_wait", "split"))


@cocotb.test()
async def counters_wrap(dut):
    """The statistics counters count modulo 2^48: deposited 1 to 3 counts below the wrap, a
    random stream carries each of them past it, and the counts since the deposit (modulo 2^48)
    must still satisfy check_stats (requests, lookups and line misses as the handshakes say,
    bytes = misses x line)."""
    h, rng = new_harness(dut)
    await h.reset()
    await FallingEdge(dut.clk_i)
    preset = {k: (1 << 48) - 1 - (j % 3) for j, k in enumerate(STAT_REGS)}
    h.preset(preset)
    await FallingEdge(dut.clk_i)
    assert all(v == 0 for v in h.stats().values()), f"deposit not taken: {h.stats()}"
    stream = Q.random_quads(rng, h.texs, scale(300))
    r = await h.run(stream, what="counters near 2^48")
    await h.drain()
    st = h.check_stats("counters near 2^48")
    raw = {k: int(getattr(dut, f"stat_{k}_o").value) for k in STAT_REGS}
    unwrapped = [k for k in preset if raw[k] >= preset[k]]
    if unwrapped:
        h.bad.append(f"counters that did not pass 2^48: {unwrapped} ({st})")
    summary(h, r, st, "counters near 2^48")
    h.finish("counters wrap")


def test_model_passes():
    """The organisation's claim, on model.tex_cache (what the RTL's lookup count is checked
    against): every quad of a power-of-two-wide level, clamped or not, is one pass (whatever the
    data RAM's window); any request's passes serve each texel once with one line and one window
    per sub-cache; widths that are not powers of two stay near one pass per quad."""
    rng = random.Random(5)
    nrng = np.random.default_rng(5)
    checked = 0
    for lb, ww in ((8, 8), (32, 8), (32, 2), (64, 4), (128, 8), (128, 2)):
        cfg = TexCacheConfig(line_bytes=lb, data_w=min(64, lb * 8, 32 * ww), win_words=ww)
        for w, h in ((1, 1), (2, 4), (4, 2), (8, 8), (16, 4), (64, 32), (256, 256), (1024, 8)):
            p = Q.Placed(Q.random_texture(nrng, h, w), 64 * rng.randrange(1 << 20), "pot")
            for lvl in range(p.tex.n_levels):
                lw, lh = p.tex.level_size(lvl)
                for _ in range(200):
                    q = p.quad(lvl, rng.randrange(-1, lh), rng.randrange(-1, lw))
                    assert len(passes(q, cfg)) == 1, (lb, w, h, lvl, [hex(a) for a in q])
                    checked += 1
        for _ in range(2000):
            q = [4 * rng.randrange(1 << 28) for _ in range(4)]
            if rng.random() < 0.3:
                q[1] = q[0] + rng.choice([0, 4, lb])
            if rng.random() < 0.3:  # four texels of one line: window splits
                q = [(q[0] & ~(lb - 1)) + 4 * rng.randrange(lb // 4) for _ in range(4)]
            seen = 0
            for ps in passes(q, cfg):
                assert ps.mask and not (ps.mask & seen)
                seen |= ps.mask
                for t in range(4):
                    if ps.mask >> t & 1:
                        assert ps.lines[ps.sub[t]] == q[t] >> cfg.off_w
                        assert window_fits((q[t] % lb) // 4, ps.win[ps.sub[t]], cfg)
            assert seen == 0xF
            checked += 1
    cfg = TexCacheConfig()
    for w, h in ((100, 75), (75, 100), (640, 480), (1920, 1080), (37, 61)):
        p = Q.Placed(Q.random_texture(nrng, h, w), 0x100000, "npot")
        n = tot = 0
        for lvl in range(p.tex.n_levels):
            lw, lh = p.tex.level_size(lvl)
            for _ in range(300):
                tot += len(passes(p.quad(lvl, rng.randrange(lh), rng.randrange(lw)), cfg))
                n += 1
        assert tot / n < 1.1, (w, h, tot / n)
        checked += n
    report.record("tex_cache", "model passes (organisation)", checked, 0)


#: Stream-length factor per configuration (TC_SCALE in the environment overrides it): the small
#: cache's 32-bit bus makes each quad cost several times more clocks.  make test runs SCALES,
#: make test-long (TB_LONG=1) twice as long streams.
SCALES = {"default": 0.5, "small": 0.25, "wide": 0.25}
LONG_SCALES = {"default": 1.0, "small": 0.5, "wide": 0.5}


def _run(name: str) -> None:
    # one seed for every test of the run (printed)
    seed = int(os.environ.get("SEED", random.randrange(1, 1 << 31)))
    print(f"tex_cache-{name}: SEED={seed}")
    cfg = CONFIGS[name]
    scales = LONG_SCALES if runner.long_stimulus() else SCALES
    runner.run("tex_cache", "test_tex_cache", HERE, parameters=cfg.params(),
               name=f"tex_cache-{name}",
               extra_env={"TC_CFG": json.dumps(cfg.__dict__), "SEED": str(seed),
                          "TC_SCALE": os.environ.get("TC_SCALE", str(scales[name]))})


def test_tex_cache():
    _run("default")


@pytest.mark.skipif(not runner.long_stimulus(), reason="2 KiB over a 32-bit bus, not the design's cache: make test-long (TB_LONG=1)")
def test_tex_cache_small():
    """2 KiB: 64-byte lines over a 32-bit bus, SETS=4, WAYS=2, 4 MSHRs, an 8-pass FIFO."""
    _run("small")


@pytest.mark.skipif(not runner.long_stimulus(), reason="WIN_WORDS 8, not the design's 2: make test-long (TB_LONG=1)")
def test_tex_cache_wide():
    """The default cache with WIN_WORDS = 8 (dm_pipeline uses 2, the module's default)."""
    _run("wide")


if __name__ == "__main__":
    pytest.main([__file__, "-q", "-s"])
