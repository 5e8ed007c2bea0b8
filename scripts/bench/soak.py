#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Long random soak of the RTL against the f24 engine, with memory faults and back-pressure.

  soak.py [--rays 1000000] [--seed S] [--batch-rays 4000] [--fragments 10000] [--out out/soak]

Rays: ``--rays`` random rays in batches through the traverse-unit harness
(``tb/harness/traverse_harness.cpp``: ``traverse_system`` = traverse unit + height cache + an AXI4
memory model; :func:`tb.harness.traverse_system.run_batch`), each batch compared with
``model.traverse.trace(pyr, rays, method, "f24")``.  Every batch draws, from ``(seed, batch)``:

- a map: sides from 1 to ``--max-side`` (1024) each, not square, not powers of two, 1x1 and strips
  included; unorm8 or unorm16; heights rough, flat (0, 1 or between), sparse spikes, a
  procedural scene, ramps or a checkerboard;
- an exact method (the batches go round all of them), the pyramid at a random base address;
- rays: random (lengths from 0 to several map sides), adversarial (on texel edges and corners,
  axis-parallel, vertical, diagonal through corners, integer slopes, grazing up to 5 map sides,
  the map's edges), bad numbers in any field (NaN, +-Inf, +-0, float64 subnormals, values below
  f24's smallest normal, huge and overflowing values), starts outside the map, tiny slopes, and
  camera rays on scene maps;
- the AXI memory model: read latency MIN:MAX with MAX from 1 to 500 clocks (the memory model's
  and the AXI protocol's minimum is 1: a read beat cannot come in the clock of its address
  handshake), random arready stalls, rvalid bubbles, ray-stream gaps and result back-pressure;
  sometimes a warm re-run (the harness checks both runs agree);
- faults in ``--faults`` (a quarter) of the batches, every method getting its share: SLVERR
  ranges (single lines, byte ranges, bands of level-0 rows, a whole level, the root) or DECERR
  (the pyramid stored with level 0 last -- the per-level offsets are configuration -- and the
  memory cut at a 4 KiB page inside level 0, so the rows beyond answer DECERR), half and half.

Checks per batch: every ray id back exactly once (the harness checks it and exits non-zero
otherwise; the output is checked again here: one record per ray, in order); the unit's
rays_in = rays_out = rays, its iteration counter = the sum of the per-ray iterations, its cache
hits that plus at most one per redo of locate's exit check (the model's ``relocate``).  A ray
whose model path reads a bad line (the line of any read, computed from the model's own sequence
of nodes; a redo's read of an estimate is not one, and the ring ignores its answer) must come
back with the err flag, no hit, not invalid, and the iterations before that read; every other ray
must equal the f24 engine bit for bit: hit, invalid, iterations and, where it hits, the t, u, v
words; no err flag.  Batches without faults also compare the
unit's descent / crossing / level-up counters with the model's.

Fragments (``--fragments``, default 10000; 0 skips): small frames through the whole pipeline
harness (``dm_pipeline``, :func:`tb.harness.dm_pipeline.run_pixels`) with random AXI latency 1..500
on each port, back-pressure, bad numbers in some fragments (NaN / Inf / zero view vectors and TBN
rows, entry points outside the map) and faults: SLVERR on height lines (exactly the pixels whose
ray reads one come back with err, no hit, the miss colour, the iterations before the read) or on
the texture memory (exactly the hits come back with err, hit and iterations as the model's);
everything else equal to ``model.shade.render_pixels`` (f24) bit for bit (colour, hit, invalid,
iterations).

Writes ``OUT/soak.json`` (counts per method, category, fault kind; functional coverage of the
methods x level transitions x outcomes x cache events; wall time) and prints a progress line per
batch.  Exit status: 0 no mismatch; 1 any mismatch or harness failure (the first ones are
printed with the arguments that reproduce their batch: ``--seed S --only-batch K``); 2 a usage
error (one line).
"""
from __future__ import annotations

import json
import math
import re
import sys
import time
from collections import Counter, defaultdict, deque
from concurrent.futures import Future, ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator, Sequence

import numpy as np
import numpy.typing as npt

ROOT = Path(__file__).resolve().parents[2]
from model import f24, heightmap, scenes, traverse
from model.cli import Parser, fail
from model.heightmap import Pyramid
from model.rays import Rays, TraceResult
from tb.harness import traverse_system, traverse_words

PROG = "soak.py"
F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]
B = npt.NDArray[np.bool_]

#: The largest latency the soak draws (issue 7: 0 to 500; the memory model's minimum is 1).
MAX_LATENCY = 500
PAGE = 4096


def _line_bytes() -> int:
    """traverse_system's cache line (its LINE_BYTES default; the harness keeps the default)."""
    src = (ROOT / "rtl" / "traverse" / "traverse_system.sv").read_text()
    m = re.search(r"parameter\s+int\s+unsigned\s+LINE_BYTES\s*=\s*(\d+)", src)
    if not m:
        raise RuntimeError("cannot find LINE_BYTES in rtl/traverse/traverse_system.sv")
    return int(m.group(1))


LINE_BYTES = _line_bytes()


# ---- maps ----------------------------------------------------------------------------------------

def map_size(rng: np.random.Generator, max_side: int) -> tuple[int, int]:
    """(height, width): the largest map, one side the largest, tiny maps, strips, or two
    log-uniform sides (half of them at least 64, so that the pyramid outgrows the 32 KiB
    height cache)."""
    lg = math.log2(max_side)

    def side(lo: float) -> int:
        return int(round(2 ** rng.uniform(min(lo, lg), lg)))

    r = rng.random()
    if r < 0.12:
        return max_side, max_side
    if r < 0.2:
        return (max_side, side(0)) if rng.random() < 0.5 else (side(0), max_side)
    if r < 0.25:
        return int(rng.integers(1, 5)), int(rng.integers(1, 5))
    if r < 0.33:
        long = side(0)
        return (1, long) if rng.random() < 0.5 else (long, 1)
    h, w = (side(6 if rng.random() < 0.5 else 0) for _ in range(2))
    if rng.random() < 0.2:  # a power of two on one side
        h = 1 << int(rng.integers(0, int(lg) + 1))
    return max(1, min(h, max_side)), max(1, min(w, max_side))


HEIGHT_KINDS = ("rough", "flat", "spiky", "scene", "ramp", "checker", "zero", "one")


def height_field(rng: np.random.Generator, h: int, w: int, kind: str) -> tuple[F64, str]:
    """Heights in [0, 1] of one kind; returns the field and a short description."""
    if kind == "rough":
        p = float(rng.uniform(0.3, 6))
        return rng.random((h, w)) ** p, f"rough^{p:.1f}"
    if kind == "flat":
        c = float(rng.choice([0.5, float(rng.random())]))
        return np.full((h, w), c), f"flat {c:.3f}"
    if kind == "spiky":
        d = float(10 ** rng.uniform(-3, -1))
        return (rng.random((h, w)) < d).astype(float) * rng.uniform(0.5, 1), f"spikes {d:.4f}"
    if kind == "scene":
        name = str(rng.choice(scenes.SCENES))
        return scenes.height(name, (h, w)), f"scene {name}"
    if kind == "ramp":
        yy, xx = np.mgrid[0:h, 0:w]
        a, b = rng.uniform(-1, 1, 2)
        r = a * xx / max(w, 1) + b * yy / max(h, 1)
        return (r - r.min()) / max(float(np.ptp(r)), 1e-12), "ramp"
    if kind == "checker":
        s = int(rng.integers(1, 9))
        yy, xx = np.mgrid[0:h, 0:w]
        return (((yy // s) + (xx // s)) % 2).astype(float), f"checker {s}"
    if kind == "zero":
        return np.zeros((h, w)), "zero"
    return np.ones((h, w)), "one"


# ---- rays ----------------------------------------------------------------------------------------

RAY_KINDS = ("random", "adversarial", "bad-number", "outside", "tiny-slope", "camera")
#: Special values put into ray fields by the bad-number rays.
SPECIALS = np.array([np.nan, np.inf, -np.inf, 0.0, -0.0, 5e-324, -1e-310, 2.0 ** -62,
                     2.0 ** -63, 1e-20, -1e-25, 1.8e19, 1e20, -1e20, 1e300, -1e300, 3.4e38])


def random_rays(rng: np.random.Generator, w: int, h: int, n: int) -> Rays:
    """Starts in the map, any direction, lengths from 0 to three map sides."""
    side = max(w, h)
    ang = rng.uniform(0, 2 * np.pi, n)
    scale = rng.choice([0.5, 4.0, max(side / 4, 1.0), 3.0 * side], n)
    ln = scale * rng.random(n)
    return Rays(rng.uniform(0, w, n), rng.uniform(0, h, n), ln * np.cos(ang), ln * np.sin(ang))


def adversarial_rays(rng: np.random.Generator, w: int, h: int, n: int) -> Rays:
    """Rays on texel edges and corners, axis-parallel, vertical, diagonal, integer slopes,
    grazing, and along the map's edges (tests/test_traverse.py's cases, drawn per ray)."""
    r = random_rays(rng, w, h, n)
    u0, v0, du, dv = r.u0, r.v0, r.du, r.dv
    side = max(w, h)
    kind = rng.integers(0, 10, n)
    fl = np.isin(kind, (0, 2, 6, 7))
    u0[fl] = np.floor(u0[fl])
    fl = np.isin(kind, (1, 2, 6, 7))
    v0[fl] = np.floor(v0[fl])
    du[kind == 3] = 0
    dv[kind == 4] = 0
    du[kind == 5] = dv[kind == 5] = 0
    dv[kind == 6] = du[kind == 6]
    dv[kind == 7] = -du[kind == 7]
    k = kind == 8
    du[k], dv[k] = np.round(du[k]), np.round(dv[k])
    g = kind == 9
    du[g] = rng.choice([-1, 1], int(g.sum())) * rng.uniform(1, 5, int(g.sum())) * side
    dv[g] = rng.uniform(-1, 1, int(g.sum())) * side
    e = rng.random(n) < 0.05  # exactly on the map's edges
    u0[e] = rng.choice([0.0, float(np.nextafter(w, 0)), float(w) - 1e-9, 0.5], int(e.sum()))
    return Rays(u0, v0, du, dv)


def bad_number_rays(rng: np.random.Generator, w: int, h: int, n: int) -> Rays:
    """Adversarial rays with one to four fields replaced by special values."""
    r = adversarial_rays(rng, w, h, n)
    fields = [r.u0, r.v0, r.du, r.dv]
    nf = rng.integers(1, 5, n)
    for i in range(4):
        pick = rng.random(n) < nf / 4
        fields[i][pick] = rng.choice(SPECIALS, int(pick.sum()))
    return r


def outside_rays(rng: np.random.Generator, w: int, h: int, n: int) -> Rays:
    """Starts just outside, on the far edges or far away (invalid by the contract)."""
    r = random_rays(rng, w, h, n)
    off = rng.choice([-1e-6, -2.0 ** -20, -0.5, -1e6, 0.0, 1e-6, 0.5, 1e6], n)
    on_u = rng.random(n) < 0.5
    lo = off < 0
    u0, v0 = r.u0, r.v0
    u0[on_u & lo] = off[on_u & lo]
    u0[on_u & ~lo] = w + off[on_u & ~lo]
    v0[~on_u & lo] = off[~on_u & lo]
    v0[~on_u & ~lo] = h + off[~on_u & ~lo]
    return r


def tiny_slope_rays(rng: np.random.Generator, w: int, h: int, n: int) -> Rays:
    """Nearly vertical rays (|d| from 1e-9 to 1e-2) and rays along one whole row or column."""
    r = random_rays(rng, w, h, n)
    ln = 10 ** rng.uniform(-9, -2, n)
    ang = rng.uniform(0, 2 * np.pi, n)
    r.du[:], r.dv[:] = ln * np.cos(ang), ln * np.sin(ang)
    row = rng.random(n) < 0.3
    r.du[row] = rng.choice([-1, 1], int(row.sum())) * (w + 1)
    r.dv[row] = 0
    return r


def camera_rays(rng: np.random.Generator, w: int, h: int, n: int) -> Rays:
    """Rays of the project's camera (model.camera) at a random view, n of them at random."""
    from model import camera

    view = float(rng.uniform(5, 89)) if rng.random() < 0.5 else str(rng.choice(list(camera.VIEWS)))
    img = int(rng.integers(16, 97))
    r = camera.Camera.for_view(view, w, h, img, img).rays().rays
    if len(r) == 0:
        return random_rays(rng, w, h, n)
    return r.subset(rng.integers(0, len(r), n))


def make_rays(rng: np.random.Generator, w: int, h: int, n: int,
              camera_ok: bool) -> tuple[Rays, npt.NDArray[np.int8]]:
    """The batch's rays, shuffled, with each ray's kind (index in RAY_KINDS)."""
    share = np.array([0.43, 0.25, 0.10, 0.06, 0.06, 0.08 if camera_ok else 0.0])
    counts = rng.multinomial(n, share / share.sum())
    gens = (random_rays, adversarial_rays, bad_number_rays, outside_rays, tiny_slope_rays,
            camera_rays)
    parts = [g(rng, w, h, int(c)) for g, c in zip(gens, counts)]
    kinds = np.repeat(np.arange(len(gens), dtype=np.int8), counts)
    order = rng.permutation(n)
    cat = [np.concatenate([getattr(p, f) for p in parts])[order] for f in ("u0", "v0", "du", "dv")]
    return Rays(*(np.ascontiguousarray(c, dtype=np.float64) for c in cat)), kinds[order]


# ---- memory layouts and faults ------------------------------------------------------------------

class LevelZeroLast(Pyramid):
    """The same pyramid stored with level 0 after the others (the per-level offsets are
    configuration registers), its memory image optionally cut after ``limit`` bytes."""

    def __init__(self, pyr: Pyramid, limit: int | None = None) -> None:
        super().__init__(pyr.codes, pyr.bits, pyr.levels)
        self.limit = limit

    def level_offsets(self, align: int = 64) -> list[int]:
        bpt = self.bits // 8
        sizes = [-(-((self.size >> k) ** 2 * bpt) // align) * align for k in range(self.n + 1)]
        offs = [0] * (self.n + 1)
        o = 0
        for k in range(self.n, 0, -1):
            offs[k] = o
            o += sizes[k]
        offs[0] = o
        return offs

    def full_bytes(self, align: int = 64) -> int:
        bpt = self.bits // 8
        return self.level_offsets(align)[0] + -(-(self.size ** 2 * bpt) // align) * align

    def memory_image(self, align: int = 64) -> bytes:
        offs = self.level_offsets(align)
        dt = np.dtype("<u1") if self.bits == 8 else np.dtype("<u2")
        buf = bytearray(self.full_bytes(align))
        for k, lv in enumerate(self.levels):
            raw = lv.astype(dt).tobytes()
            buf[offs[k]:offs[k] + len(raw)] = raw
        return bytes(buf if self.limit is None else buf[:self.limit])


@dataclass
class Faults:
    """A batch's memory faults: SLVERR byte ranges and the memory's extent (DECERR outside)."""

    kind: str = "none"  # none | slverr | decerr
    ranges: list[tuple[int, int]] = field(default_factory=list)  # [lo, hi) answering SLVERR
    mem_lo: int = 0     # the memory model's byte range (axi_mem.h: the image's 4 KiB pages)
    mem_hi: int = 1 << 64
    what: list[str] = field(default_factory=list)

    def bad_lines(self, line_addr: I64) -> B:
        """Lines (by byte address) whose read answers an error."""
        lo = line_addr
        hi = line_addr + LINE_BYTES
        bad = (lo < self.mem_lo) | (hi > self.mem_hi)
        for a, b in self.ranges:
            bad |= (lo < b) & (a < hi)
        return bad


def decerr_possible(pyr: Pyramid) -> bool:
    """A cut at a 4 KiB page inside level 0 needs a level 0 of at least two pages."""
    return pyr.size ** 2 * (pyr.bits // 8) >= 2 * PAGE


def plan_faults(rng: np.random.Generator, pyr: Pyramid, base: int,
                kind: str) -> tuple[Pyramid, int, Faults]:
    """The pyramid as the RTL sees it (layout), its base address and the faults of a batch.

    ``kind``: "none"; "slverr" (random SLVERR ranges); "decerr" (level 0 stored last and the
    memory cut at a page inside it; SLVERR instead when level 0 is under two pages)."""
    bpt = pyr.bits // 8
    if kind == "decerr" and decerr_possible(pyr):  # DECERR: memory cut inside level 0
        lay = LevelZeroLast(pyr)
        base = traverse_system.DEFAULT_BASE  # page aligned
        off0 = lay.level_offsets()[0]
        # cut inside the rows of the map (the padding is never read)
        used = pyr.height * pyr.size * bpt
        cut = off0 + int(rng.uniform(0.2, 0.95) * used)
        cut = -(-cut // PAGE) * PAGE
        if cut >= lay.full_bytes():
            cut = (lay.full_bytes() // PAGE - 1) * PAGE
        lay.limit = cut
        f = Faults("decerr", [], base & ~(PAGE - 1), (base + cut + PAGE - 1) & ~(PAGE - 1),
                   [f"DECERR from byte {cut} of {lay.full_bytes()} (level 0 at {off0})"])
        return lay, base, f
    if kind == "none":
        img = len(pyr.memory_image())
        return pyr, base, Faults("none", [], base & ~(PAGE - 1),
                                 (base + img + PAGE - 1) & ~(PAGE - 1))
    img = len(pyr.memory_image())
    offs = pyr.level_offsets()
    f = Faults("slverr", [], base & ~(PAGE - 1), (base + img + PAGE - 1) & ~(PAGE - 1))
    for _ in range(int(rng.integers(1, 5))):
        c = rng.random()
        if c < 0.4:  # single lines at random texels of random levels
            k = int(rng.integers(0, pyr.n + 1))
            side = pyr.size >> k
            y = int(rng.integers(0, max(1, min(side, -(-pyr.height // (1 << k))))))
            x = int(rng.integers(0, max(1, min(side, -(-pyr.width // (1 << k))))))
            a = base + offs[k] + (y * side + x) * bpt
            lo = a // LINE_BYTES * LINE_BYTES
            f.ranges.append((lo, lo + LINE_BYTES))
            f.what.append(f"line at level {k} ({x}, {y})")
        elif c < 0.65:  # a band of level-0 rows
            y = int(rng.integers(0, pyr.height))
            rows = int(rng.integers(1, 4))
            lo = base + offs[0] + y * pyr.size * bpt
            f.ranges.append((lo, lo + rows * pyr.size * bpt))
            f.what.append(f"level-0 rows {y}..{y + rows - 1}")
        elif c < 0.85:  # an arbitrary byte range
            lo = base + int(rng.integers(0, img))
            f.ranges.append((lo, lo + int(rng.integers(1, 300))))
            f.what.append(f"bytes {f.ranges[-1][0] - base}..{f.ranges[-1][1] - base}")
        elif c < 0.95 and pyr.n >= 1:  # a whole level
            k = int(rng.integers(1, pyr.n + 1))
            side = pyr.size >> k
            lo = base + offs[k]
            f.ranges.append((lo, lo + side * side * bpt))
            f.what.append(f"level {k}")
        else:  # the root: every ray that reads fails at its first read
            lo = base + offs[pyr.n]
            f.ranges.append((lo, lo + bpt))
            f.what.append("root")
    return pyr, base, f


# ---- the model's reads ---------------------------------------------------------------------------

@contextmanager
def recorded_reads() -> Iterator[list[tuple[I64, I64, I64]]]:
    """Record the (level, cx, cy) arrays of every pass of :func:`model.traverse.trace`.

    The trace reads the height of its active rays once per pass through ``texel_offset``; the
    active rays of pass p (from 0) are, in ascending order, the rays whose iteration count is
    greater than p (a ray leaves after its last read).  :func:`first_bad_read` checks this.
    Not thread-safe: the model runs in the main thread only.
    """
    calls: list[tuple[I64, I64, I64]] = []
    orig = traverse.texel_offset

    def rec(level_off: Any, n: int, k: I64, cx: I64, cy: I64, texel_size: int = 1) -> I64:
        calls.append((np.array(k, dtype=np.int64), np.array(cx, dtype=np.int64),
                      np.array(cy, dtype=np.int64)))
        return orig(level_off, n, k, cx, cy, texel_size)

    traverse.texel_offset = rec  # type: ignore[assignment]
    try:
        yield calls
    finally:
        traverse.texel_offset = orig  # type: ignore[assignment]


def read_passes(reads: list[tuple[I64, I64, I64]], iterations: I64) -> Iterator[tuple[int, I64]]:
    """(pass, ray indices active in it), checking the recorder's premise."""
    if len(reads) != int(iterations.max(initial=0)):
        raise RuntimeError(f"read recorder: {len(reads)} passes, max iterations "
                           f"{int(iterations.max(initial=0))}")
    for p, (k, _, _) in enumerate(reads):
        act = np.nonzero(iterations > p)[0]
        if len(act) != len(k):
            raise RuntimeError(f"read recorder: pass {p} has {len(k)} reads, {len(act)} rays")
        yield p, act


def first_bad_read(lay: Pyramid, base: int, faults: Faults,
                   reads: list[tuple[I64, I64, I64]], iterations: I64) -> I64:
    """Per ray, the index of its first read of a bad line (-1: none)."""
    first = np.full(len(iterations), -1, dtype=np.int64)
    if faults.kind == "none":
        return first
    offs = np.asarray(lay.level_offsets(), dtype=np.int64)
    bpt = lay.bits // 8
    for p, act in read_passes(reads, iterations):
        k, cx, cy = reads[p]
        addr = base + traverse.texel_offset(offs, lay.n, k, cx, cy, bpt)
        bad = faults.bad_lines(addr // LINE_BYTES * LINE_BYTES)
        new = act[bad & (first[act] < 0)]
        first[new] = p
    return first


# ---- functional coverage -------------------------------------------------------------------------

TRANSITIONS = ("descend 1", "descend 2", "descend 3+", "cross", "cross + level up")
OUTCOMES = ("hit", "miss", "no read", "invalid", "err")


class Functional:
    """Methods x level transitions x outcomes x cache events, summed over the soak.

    Level transitions come from the model's path of each ray (the RTL matched the model's
    result and iteration count for the same ray; its own per-step path is not observed); the
    cache events and the descent / crossing / level-up counts are the RTL's own counters.
    """

    def __init__(self) -> None:
        self.trans: dict[str, Counter[str]] = defaultdict(Counter)
        self.levels: dict[str, Counter[int]] = defaultdict(Counter)
        self.outcomes: dict[str, Counter[str]] = defaultdict(Counter)
        self.rtl: dict[str, Counter[str]] = defaultdict(Counter)

    def add_paths(self, method: str, reads: list[tuple[I64, I64, I64]], iterations: I64) -> None:
        prev_k: I64 | None = None
        prev_act: I64 | None = None
        tr = self.trans[method]
        for p, act in read_passes(reads, iterations):
            k = reads[p][0]
            for lv, c in zip(*np.unique(k, return_counts=True)):
                self.levels[method][int(lv)] += int(c)
            if prev_k is not None and prev_act is not None:
                keep = iterations[prev_act] > p
                d = k - prev_k[keep]
                tr["descend 1"] += int((d == -1).sum())
                tr["descend 2"] += int((d == -2).sum())
                tr["descend 3+"] += int((d <= -3).sum())
                tr["cross"] += int((d == 0).sum())
                tr["cross + level up"] += int((d == 1).sum())
                if (d > 1).any():
                    raise RuntimeError("a level-up by more than one level")
            prev_k, prev_act = k, act

    def add_outcomes(self, method: str, res: TraceResult, err: B) -> None:
        o = self.outcomes[method]
        o["invalid"] += int(res.invalid.sum())
        o["err"] += int(err.sum())
        ok = ~res.invalid & ~err
        o["hit"] += int((res.hit & ok).sum())
        o["miss"] += int((~res.hit & ok & (res.iterations > 0)).sum())
        o["no read"] += int((ok & (res.iterations == 0)).sum())

    def add_rtl(self, method: str, st: dict[str, Any]) -> None:
        c = self.rtl[method]
        for k in ("lookups", "height_cache_hits", "height_cache_misses", "mem_lines", "descents",
                  "crossings", "level_ups", "errors", "axi_slverr_beats", "axi_decerr_beats"):
            c[k] += int(st.get(k, 0))

    def as_dict(self) -> dict[str, Any]:
        """Per method: counts, and the cells of the cross table that stayed at zero."""
        out: dict[str, Any] = {}
        for m in traverse.EXACT_METHODS:
            meth = traverse.METHODS[m]
            impossible = set()
            if meth.level_up == "none":
                impossible.add("cross + level up")
            if meth.level_up == "drobot":  # up on every crossing but at the root, which a
                impossible.add("cross")     # ray can only leave (a miss), never cross
            if meth.descent == "one":
                impossible |= {"descend 2", "descend 3+"}
            if meth.descent == "multi" and meth.descent_levels < 3:
                impossible.add("descend 3+")
            cells = {**{t: self.trans[m][t] for t in TRANSITIONS},
                     **{o: self.outcomes[m][o] for o in OUTCOMES},
                     "cache hit": self.rtl[m]["height_cache_hits"],
                     "cache miss (retry)": self.rtl[m]["height_cache_misses"],
                     "line fill": self.rtl[m]["mem_lines"],
                     "SLVERR beat": self.rtl[m]["axi_slverr_beats"],
                     "DECERR beat": self.rtl[m]["axi_decerr_beats"]}
            out[m] = {"cells": cells,
                      "reads_per_level": {str(k): v for k, v in sorted(self.levels[m].items())},
                      "rtl_counters": dict(self.rtl[m]),
                      "zero_cells": sorted(c for c, v in cells.items()
                                           if v == 0 and c not in impossible),
                      "impossible_cells": sorted(impossible)}
        return out


# ---- one batch -----------------------------------------------------------------------------------

@dataclass
class Batch:
    """A batch's inputs (everything drawn from (seed, index))."""

    index: int
    desc: str
    pyr: Pyramid        # the model's pyramid
    lay: Pyramid        # as the RTL sees it (layout, maybe a cut image)
    base: int
    rays: Rays
    kinds: npt.NDArray[np.int8]
    method: str
    knobs: dict[str, Any]
    faults: Faults


def fault_kind(seed: int, index: int, p_fault: float) -> str:
    """The fault kind of a batch: the methods take turns batch by batch, and all batches of one
    turn share a fault draw from a low-discrepancy sequence, so every method gets its share of
    SLVERR and DECERR batches (half and half of ``p_fault``)."""
    turn = (index + seed) // len(traverse.EXACT_METHODS)
    u = (turn * 0.6180339887498949 + (seed % 1000) * 0.001) % 1.0
    return "decerr" if u < p_fault / 2 else "slverr" if u < p_fault else "none"


def make_batch(seed: int, index: int, n: int, max_side: int, p_fault: float) -> Batch:
    rng = np.random.default_rng([seed, index])
    fk = fault_kind(seed, index, p_fault)
    for _ in range(20):  # a DECERR batch wants a level 0 of at least two pages
        h, w = map_size(rng, max_side)
        if fk != "decerr" or max(h, w) > 64 or max_side <= 64:
            break
    kind = str(rng.choice(HEIGHT_KINDS, p=[0.3, 0.08, 0.15, 0.2, 0.08, 0.07, 0.06, 0.06]))
    hf, hdesc = height_field(rng, h, w, kind)
    bits = 16 if rng.random() < 0.35 else 8
    pyr = heightmap.build(hf, bits)
    methods = traverse.EXACT_METHODS
    method = methods[(index + seed) % len(methods)]
    base = int(rng.choice([traverse_system.DEFAULT_BASE, 0, 0x1234_0000]))
    base += int(rng.integers(0, 4096)) // 2 * 2  # any even address (unorm16 texels aligned)
    lay, base, faults = plan_faults(rng, pyr, base, fk)
    rays, kinds = make_rays(rng, w, h, n, kind == "scene" and min(w, h) >= 8)
    u = rng.random()
    if u < 0.15:
        lat = int(rng.choice([1, 2, 20, 100, MAX_LATENCY]))
        lo, hi = lat, lat
    else:
        hi = int(rng.integers(1, 9)) if u < 0.45 else int(rng.integers(9, 101)) if u < 0.75 \
            else int(rng.integers(101, MAX_LATENCY + 1))
        lo = int(rng.integers(1, hi + 1))

    def prob() -> float:
        v = rng.random()
        return 0.0 if v < 0.4 else float(rng.uniform(0, 0.3)) if v < 0.8 else \
            float(rng.uniform(0.3, 0.9))

    knobs: dict[str, Any] = {"latency": (lo, hi), "seed": int(rng.integers(1 << 31)),
                             "ray_gap": prob(), "res_stall": prob(), "ar_stall": prob(),
                             "rvalid_gap": prob(), "warm": bool(rng.random() < 0.04)}
    desc = (f"{h}x{w} u{bits} {hdesc}, {method}, base 0x{base:x}, latency {lo}:{hi}, gaps "
            f"ray {knobs['ray_gap']:.2f} res {knobs['res_stall']:.2f} ar {knobs['ar_stall']:.2f} "
            f"r {knobs['rvalid_gap']:.2f}{', warm' if knobs['warm'] else ''}"
            + (f", {faults.kind}: {'; '.join(faults.what)}" if faults.kind != "none" else ""))
    return Batch(index, desc, pyr, lay, base, rays, kinds, method, knobs, faults)


def run_rtl(b: Batch, variant_checked: bool) -> tuple[npt.NDArray[Any] | None, dict[str, Any],
                                                       str | None, float]:
    """The batch through the harness (in a worker thread); (records, stats, error, seconds)."""
    t0 = time.monotonic()
    try:
        out, st = traverse_system.run_batch(b.lay, b.rays, b.method, base=b.base,
                                            err_ranges=b.faults.ranges, checked=variant_checked,
                                            **b.knobs)
        return out, st, None, time.monotonic() - t0
    except traverse_system.RtlEngineError as e:
        return None, {}, str(e).strip(), time.monotonic() - t0


@dataclass
class ModelResult:
    res: TraceResult
    words: traverse_words.ExpectedWords
    first_bad: I64
    stats: dict[str, int]
    seconds: float


def run_model(b: Batch, func: Functional) -> ModelResult:
    t0 = time.monotonic()
    st: dict[str, int] = {}
    with recorded_reads() as reads:
        res = traverse.trace(b.pyr, b.rays, b.method, "f24", stats=st)
    first = first_bad_read(b.lay, b.base, b.faults, reads, res.iterations)
    func.add_paths(b.method, reads, res.iterations)
    return ModelResult(res, traverse_words.expected_words(res), first, st, time.monotonic() - t0)


def ray_text(b: Batch, i: int) -> str:
    r = b.rays
    vals = (r.u0[i], r.v0[i], r.du[i], r.dv[i])
    words = [int(x[0]) for x in traverse_words.ray_words(r.subset([i]))]
    return (f"ray {i} ({RAY_KINDS[b.kinds[i]]}) u0,v0,du,dv = "
            + ", ".join(repr(float(v)) for v in vals)
            + " (f24 " + " ".join(f"{w:06x}" for w in words) + ")")


def compare(b: Batch, out: npt.NDArray[Any], st: dict[str, Any], m: ModelResult,
            func: Functional) -> tuple[list[str], dict[str, int]]:
    """Mismatches of one batch (text lines) and its counts."""
    n = len(b.rays)
    bad: list[str] = []
    if len(out) != n or not np.array_equal(out["id"], np.arange(n, dtype=np.uint32)):
        bad.append(f"ray ids: {len(out)} records, ids not exactly 0..{n - 1} once each")
        return bad, {"rays": n}
    flags = out["flags"]
    hit = (flags & traverse_system.FLAG_HIT) != 0
    inv = (flags & traverse_system.FLAG_INVALID) != 0
    capped = (flags & traverse_system.FLAG_CAPPED) != 0
    err = (flags & traverse_system.FLAG_ERR) != 0
    it = out["iterations"].astype(np.int64)
    e = m.words
    want_err = m.first_bad >= 0
    cap = traverse.iteration_cap(b.pyr)
    # rays that must fail: err, no hit, not invalid, the reads before the bad one
    ebad = want_err & (~err | hit | inv | capped | (it != m.first_bad))
    # the others: bit for bit
    same_words = ((out["t"] == e.t) & (out["u"] == e.u) & (out["v"] == e.v)) | ~e.hit
    obad = ~want_err & (err | (hit != e.hit) | (inv != e.invalid) | (it != e.iterations)
                        | ~same_words | (capped & (hit | (it != cap))))
    for i in np.nonzero(ebad | obad)[0][:20]:
        got = (f"rtl hit {int(hit[i])} invalid {int(inv[i])} err {int(err[i])} capped "
               f"{int(capped[i])} iterations {it[i]} t/u/v {out['t'][i]:06x} {out['u'][i]:06x} "
               f"{out['v'][i]:06x}")
        if want_err[i]:
            want = f"model: err after {m.first_bad[i]} reads"
        else:
            want = (f"model hit {int(e.hit[i])} invalid {int(e.invalid[i])} iterations "
                    f"{e.iterations[i]} t/u/v {int(e.t[i]):06x} {int(e.u[i]):06x} "
                    f"{int(e.v[i]):06x}" if e.hit[i] else
                    f"model hit 0 invalid {int(e.invalid[i])} iterations {e.iterations[i]}")
        bad.append(f"{ray_text(b, i)}: {got}; {want}")
    nbad_rays = int((ebad | obad).sum())
    if nbad_rays > 20:
        bad.append(f"... {nbad_rays - 20} more rays differ in this batch")
    # the unit's own counters
    want_st = {"rays_in": n, "rays_out": n, "stat_iterations": int(it.sum())}
    if b.faults.kind == "none":
        want_st.update(descents=m.stats.get("down", 0), crossings=m.stats.get("cross", 0),
                       level_ups=m.stats.get("up", 0))
    for k, v in want_st.items():
        if int(st.get(k, -1)) != v:
            bad.append(f"counter {k}: rtl {st.get(k)} != {v}")
    # every iteration's read hits; a redo of locate's exit check reads once more (a hit or a
    # miss), at most once per relocation the model counts (over whole paths, err rays' too)
    hits, reloc = int(st.get("height_cache_hits", -1)), m.stats.get("relocate", 0)
    if not int(it.sum()) <= hits <= int(it.sum()) + reloc:
        bad.append(f"counter height_cache_hits: rtl {hits} not in {int(it.sum())} + [0, {reloc}] "
                   "relocations")
    func.add_outcomes(b.method, m.res, err)
    func.add_rtl(b.method, st)
    counts = {"rays": n, "mismatched_rays": nbad_rays, "err_rays": int(err.sum()),
              "err_expected": int(want_err.sum()), "invalid": int(inv.sum()),
              "hits": int(hit.sum()), "capped": int(capped.sum()), "iterations": int(it.sum()),
              "cycles": int(st.get("cycles", 0)), "sim_clocks": int(st.get("sim_clocks", 0))}
    return bad, counts


# ---- the pipeline part ---------------------------------------------------------------------------

def pipeline_soak(seed: int, fragments: int, checked: bool, quiet: bool,
                  log: list[str]) -> dict[str, Any]:
    """Small frames through dm_pipeline with random latency, back-pressure, bad fragment numbers
    and faults, against model.shade.render_pixels (f24)."""
    from model import camera, shade, texture
    from tb.harness import dm_pipeline

    rng = np.random.default_rng([seed, 1 << 20])
    done = frames = bad_total = err_total = 0
    failures: list[str] = []
    t0 = time.monotonic()
    k = 0
    while done < fragments:
        k += 1
        name = str(rng.choice(scenes.SCENES))
        size = int(rng.integers(12, 65))
        img_side = int(rng.integers(12, 49))
        method = traverse.EXACT_METHODS[(k + seed) % len(traverse.EXACT_METHODS)]
        angle: str | float = str(rng.choice(list(camera.VIEWS))) if rng.random() < 0.6 else \
            float(rng.uniform(8, 88))
        bits = 16 if rng.random() < 0.3 else 8
        mip = bool(rng.random() < 0.7)
        sc = scenes.load_scene(name, size)
        pyr = heightmap.build(sc.heights, bits)
        tex = texture.build(sc.texture)
        ntex = texture.build(scenes.encode_normals(sc.normals))
        cam = camera.Camera.for_view(angle, size, size, img_side, img_side,
                                     depth_scale=sc.depth_scale)
        frame = shade.Frame(pyr=pyr, colour=tex, normals=ntex, depth_scale=sc.depth_scale,
                            log2pb_colour=cam.log2_pb(tex.width, tex.height),
                            log2pb_normal=cam.log2_pb(ntex.width, ntex.height), method=method,
                            engine="f24", mip=mip)
        _, inp = shade.pixel_inputs(cam)
        n = len(inp.u0)
        if n == 0:
            continue
        inp = inp.subset(rng.permutation(n))
        # bad numbers in some fragments
        nb = int(rng.integers(0, max(2, n // 20)))
        for i in rng.choice(n, min(nb, n), replace=False):
            c = rng.integers(0, 5)
            if c == 0:
                inp.view[i] = 0.0                                  # zero-length view vector
            elif c == 1:
                inp.view[i, int(rng.integers(0, 3))] = float(rng.choice([np.nan, np.inf, -np.inf]))
            elif c == 2:
                inp.tbn[i, :, int(rng.integers(0, 3))] = 0.0       # degenerate TBN column
            elif c == 3:
                inp.tbn[i, int(rng.integers(0, 3)), int(rng.integers(0, 3))] = \
                    float(rng.choice([np.nan, np.inf, 1e30]))
            else:
                inp.u0[i] = float(rng.choice([-0.5, size + 0.5, np.nan]))  # outside the map
        fi = dm_pipeline.frame_image(frame)
        words = dm_pipeline.fragment_words(inp)
        h_base, h_img = fi.cfg.height
        fault = str(rng.choice(["none", "height", "texture"], p=[0.5, 0.3, 0.2]))
        h_err: list[tuple[int, int]] = []
        t_err: list[tuple[int, int]] = []
        fz = Faults("none")
        if fault == "height":
            _, _, fz = plan_faults(rng, pyr, h_base, "slverr")
            h_err = list(fz.ranges)
        elif fault == "texture":
            t_err = [(fi.tex_base, fi.tex_base + len(fi.tex_image))]

        def lat() -> tuple[int, int]:
            hi = int(rng.choice([int(rng.integers(1, 10)), int(rng.integers(10, 101)),
                                 int(rng.integers(101, MAX_LATENCY + 1))]))
            return int(rng.integers(1, hi + 1)), hi

        knobs = {"h_latency": lat(), "t_latency": lat(), "seed": int(rng.integers(1 << 31)),
                 "frag_gap": float(rng.uniform(0, 0.5)), "px_stall": float(rng.uniform(0, 0.7)),
                 "ar_stall": float(rng.uniform(0, 0.5)), "rvalid_gap": float(rng.uniform(0, 0.4))}
        with recorded_reads() as reads:
            ref = shade.render_pixels(frame, inp)
        first = first_bad_read(pyr, h_base, fz, reads, ref.iterations)
        desc = (f"frame {k}: {name} {size}x{size} u{bits} {angle} {method} mip {int(mip)}, "
                f"{n} fragments ({nb} with bad numbers), {fault} faults, {knobs}")
        try:
            px, st = dm_pipeline.run_pixels(fi, words, h_err=h_err, t_err=t_err,
                                            checked=checked, **knobs)
        except traverse_system.RtlEngineError as e:
            failures.append(f"{desc}: harness failed: {str(e).strip().splitlines()[0]}")
            bad_total += n
            done += n
            frames += 1
            continue
        want_err = first >= 0 if fault == "height" else ref.hit.copy() if fault == "texture" \
            else np.zeros(n, bool)
        ok_rgb = (px.rgb == ref.rgb).all(axis=1)
        if fault == "height":
            e_bad = want_err & (~px.err | px.hit | (px.iterations != first)
                                | (px.rgb != np.array(shade.MISS_COLOUR, np.uint8)).any(axis=1))
        else:  # texture: the hit, its iterations as the model's, the err flag
            e_bad = want_err & (~px.err | ~px.hit | (px.iterations != ref.iterations))
        o_bad = ~want_err & (px.err | ~ok_rgb | (px.hit != ref.hit) | (px.invalid != ref.invalid)
                             | (px.iterations != ref.iterations))
        badi = np.nonzero(e_bad | o_bad)[0]
        for i in badi[:5]:
            failures.append(f"{desc}: fragment {i}: rtl rgb {tuple(px.rgb[i])} hit {int(px.hit[i])}"
                            f" invalid {int(px.invalid[i])} err {int(px.err[i])} iterations "
                            f"{px.iterations[i]}; model rgb {tuple(ref.rgb[i])} hit "
                            f"{int(ref.hit[i])} invalid {int(ref.invalid[i])} iterations "
                            f"{ref.iterations[i]}" + (f", err expected after {first[i]} reads"
                                                      if fault == "height" and want_err[i] else
                                                      ", err expected" if want_err[i] else ""))
        if int(st.get("pixels", -1)) != n:
            failures.append(f"{desc}: harness says {st.get('pixels')} pixels, sent {n}")
            bad_total += 1
        bad_total += len(badi)
        err_total += int(px.err.sum())
        done += n
        frames += 1
        line = (f"{PROG}: pipeline frame {frames}: {n} fragments ({nb} with bad numbers), "
                f"{'no' if fault == 'none' else fault} faults "
                f"({int(want_err.sum())} err expected, {int(px.err.sum())} flagged), latency h "
                f"{knobs['h_latency'][0]}:{knobs['h_latency'][1]} t {knobs['t_latency'][0]}:"
                f"{knobs['t_latency'][1]}, {len(badi)} mismatches; {done}/{fragments} fragments, "
                f"{time.monotonic() - t0:.0f} s")
        if not quiet:
            print(line, flush=True)
    log.extend(failures)
    return {"fragments": done, "frames": frames, "mismatches": bad_total, "err_pixels": err_total,
            "wall_seconds": round(time.monotonic() - t0, 1), "first_mismatches": failures[:20]}


# ---- main ----------------------------------------------------------------------------------------

def fmt_time(s: float) -> str:
    s = int(round(s))
    if s >= 3600:
        return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}"
    return f"{s // 60}:{s % 60:02d}"


def main(argv: Sequence[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--rays", type=int, default=1_000_000, help="rays in all (default 1,000,000)")
    ap.add_argument("--seed", type=int, default=None,
                    help="seed (default: from the clock; printed)")
    ap.add_argument("--batch-rays", type=int, default=4000, help="rays per batch (default 4000)")
    ap.add_argument("--max-side", type=int, default=1024,
                    help="largest map side, 1 .. 8192 (default 1024)")
    ap.add_argument("--faults", type=float, default=0.25,
                    help="share of batches with SLVERR / DECERR faults (default 0.25)")
    ap.add_argument("--fragments", type=int, default=10000,
                    help="fragments through the pipeline harness (default 10000; 0: none)")
    ap.add_argument("--variant", choices=("checked", "fast"), default="checked",
                    help="harness build: checked (the RTL's SVA on, default) or fast")
    ap.add_argument("--jobs", type=int, default=1,
                    help="harness runs in parallel with the model (default 1)")
    ap.add_argument("--only-batch", type=int, default=None,
                    help="run just this batch of the seed (reproduces a reported mismatch)")
    ap.add_argument("--out", type=Path, default=ROOT / "out" / "soak", help="output directory")
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    a = ap.parse_args(argv)
    if a.rays < 1:
        fail(PROG, f"--rays must be >= 1, got {a.rays}")
    if a.batch_rays < 1 or a.batch_rays >= 1 << 24:
        fail(PROG, f"--batch-rays must be in 1 .. {(1 << 24) - 1}, got {a.batch_rays}")
    if not 1 <= a.max_side <= 8192:  # the unit's 16-bit iteration cap holds maps to ~16000
        fail(PROG, f"--max-side must be in 1 .. 8192, got {a.max_side}")
    if not 0.0 <= a.faults <= 1.0:
        fail(PROG, f"--faults is a share in [0, 1], got {a.faults}")
    if a.fragments < 0:
        fail(PROG, f"--fragments must be >= 0, got {a.fragments}")
    if a.jobs < 1:
        fail(PROG, f"--jobs must be >= 1, got {a.jobs}")
    if a.seed is not None and a.seed < 0:
        fail(PROG, f"--seed must be >= 0, got {a.seed}")
    if a.out.exists() and not a.out.is_dir():
        fail(PROG, f"--out {a.out} exists and is not a directory")
    seed = a.seed if a.seed is not None else int(time.time() * 1000) % (1 << 31)
    nb = -(-a.rays // a.batch_rays)
    if a.only_batch is not None and not 0 <= a.only_batch < nb:
        fail(PROG, f"--only-batch must be in 0 .. {nb - 1} for these --rays / --batch-rays")
    checked = a.variant == "checked"
    repro = (f"--seed {seed} --rays {a.rays} --batch-rays {a.batch_rays} --max-side {a.max_side} "
             f"--faults {a.faults:g}")
    print(f"{PROG}: seed {seed} (reproduce: scripts/bench/soak.py {repro}); {a.rays} rays in {nb} "
          f"batches, maps up to "
          f"{a.max_side}x{a.max_side}, AXI latency 1..{MAX_LATENCY}, {a.variant} harness",
          flush=True)
    t_start = time.monotonic()
    t0 = time.monotonic()
    try:
        traverse_system.build(a.variant, quiet=a.quiet)
        if a.fragments:
            from tb.harness import dm_pipeline
            dm_pipeline.build(a.variant, quiet=a.quiet)
    except traverse_system.RtlEngineError as e:
        print(f"{PROG}: {str(e).splitlines()[0]}", file=sys.stderr)
        return 1
    build_s = time.monotonic() - t0

    func = Functional()
    totals: Counter[str] = Counter()
    per_method: dict[str, Counter[str]] = defaultdict(Counter)
    per_fault: dict[str, Counter[str]] = defaultdict(Counter)
    kinds_total: Counter[str] = Counter()
    maps: Counter[str] = Counter()   # batches per map size class
    lats: Counter[str] = Counter()   # batches per latency class
    failures: list[str] = []
    harness_failures = 0
    lat_seen = [MAX_LATENCY + 1, 0]
    t_model = t_rtl = 0.0
    batches = [a.only_batch] if a.only_batch is not None else list(range(nb))
    todo = sum(min(a.batch_rays, a.rays - i * a.batch_rays) for i in batches)
    done = 0
    t_loop = time.monotonic()
    inflight: deque[tuple[Batch, Future[Any], ModelResult]] = deque()

    def finish(b: Batch, fut: Future[Any], m: ModelResult) -> None:
        nonlocal done, harness_failures, t_rtl
        out, st, error, secs = fut.result()
        t_rtl += secs
        n = len(b.rays)
        if error is not None:
            harness_failures += 1
            bad = [f"harness failed: {error.splitlines()[0]}"]
            counts = {"rays": n, "mismatched_rays": n}
        else:
            assert out is not None
            bad, counts = compare(b, out, st, m, func)
        totals.update(counts)
        totals["batches"] += 1
        pm = per_method[b.method]
        pm.update({k: counts.get(k, 0) for k in ("rays", "mismatched_rays", "err_rays",
                                                 "iterations", "hits", "invalid")})
        pm["batches"] += 1
        pf = per_fault[b.faults.kind]
        pf.update({k: counts.get(k, 0) for k in ("rays", "mismatched_rays", "err_rays",
                                                 "err_expected")})
        pf["batches"] += 1
        pf["slverr_beats"] += int(st.get("axi_slverr_beats", 0))
        pf["decerr_beats"] += int(st.get("axi_decerr_beats", 0))
        for kk, c in zip(*np.unique(b.kinds, return_counts=True)):
            kinds_total[RAY_KINDS[kk]] += int(c)
        side = max(b.pyr.width, b.pyr.height)
        maps[next(f"max side <= {c}" for c in (4, 64, 256, 1023, 1 << 15) if side <= c)
             if side < a.max_side else f"max side {a.max_side}"] += 1
        hi = b.knobs["latency"][1]
        lats[next(f"max latency <= {c}" for c in (8, 100, MAX_LATENCY) if hi <= c)] += 1
        lat_seen[0] = min(lat_seen[0], b.knobs["latency"][0])
        lat_seen[1] = max(lat_seen[1], b.knobs["latency"][1])
        if bad:
            totals["bad_batches"] += 1
            head = f"batch {b.index} ({b.desc}; reproduce: {repro} --only-batch {b.index})"
            failures.append(head + ":\n    " + "\n    ".join(bad[:12]))
        done += n
        if not a.quiet:
            el = time.monotonic() - t_loop
            eta = el / max(done, 1) * (todo - done)
            print(f"{PROG}: batch {b.index + 1}/{nb} [{b.desc}] {n} rays, "
                  f"{counts.get('err_rays', 0)} err, {counts.get('mismatched_rays', 0)} "
                  f"mismatched{' HARNESS FAILED' if error else ''} | {done}/{todo} rays, "
                  f"{totals['mismatched_rays']} mismatched, {fmt_time(el)} elapsed, ETA "
                  f"{fmt_time(eta)}", flush=True)

    with ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for i in batches:
            n = min(a.batch_rays, a.rays - i * a.batch_rays)
            b = make_batch(seed, i, n, a.max_side, a.faults)
            fut = pool.submit(run_rtl, b, checked)
            tm = time.monotonic()
            m = run_model(b, func)
            t_model += time.monotonic() - tm
            inflight.append((b, fut, m))
            while len(inflight) >= a.jobs + 1 or (inflight and inflight[0][1].done()):
                finish(*inflight.popleft())
        while inflight:
            finish(*inflight.popleft())
    rays_wall = time.monotonic() - t_loop

    pipe_log: list[str] = []
    pipe: dict[str, Any] | None = None
    if a.fragments and a.only_batch is None:
        pipe = pipeline_soak(seed, a.fragments, checked, a.quiet, pipe_log)
    wall = time.monotonic() - t_start
    mism = int(totals["mismatched_rays"])
    pmism = int(pipe["mismatches"]) if pipe else 0
    fdict = func.as_dict()
    doc = {
        "seed": seed, "rays": int(totals["rays"]), "batches": int(totals["batches"]),
        "batch_rays": a.batch_rays, "max_side": a.max_side, "harness_variant": a.variant,
        "mismatched_rays": mism, "batches_with_mismatches": int(totals["bad_batches"]),
        "harness_failures": harness_failures, "err_rays": int(totals["err_rays"]),
        "err_rays_expected": int(totals["err_expected"]), "invalid_rays": int(totals["invalid"]),
        "hits": int(totals["hits"]), "capped_rays": int(totals["capped"]),
        "iterations": int(totals["iterations"]), "cycles": int(totals["cycles"]),
        "sim_clocks": int(totals["sim_clocks"]),
        "latency_min_used": lat_seen[0], "latency_max_used": lat_seen[1],
        "ray_kinds": dict(kinds_total), "batches_per_map_size": dict(sorted(maps.items())),
        "batches_per_latency": dict(sorted(lats.items())),
        "per_method": {k: dict(v) for k, v in sorted(per_method.items())},
        "per_fault_kind": {k: dict(v) for k, v in sorted(per_fault.items())},
        "functional": fdict,
        "pipeline": pipe,
        "wall_seconds": round(wall, 1), "rays_wall_seconds": round(rays_wall, 1),
        "build_seconds": round(build_s, 1), "model_seconds": round(t_model, 1),
        "harness_seconds": round(t_rtl, 1),
        "rays_per_second": round(totals["rays"] / max(rays_wall, 1e-9), 1),
        "first_mismatches": failures[:20],
        "command": " ".join(["scripts/bench/soak.py", *(argv if argv is not None else sys.argv[1:])]),
    }
    a.out.mkdir(parents=True, exist_ok=True)
    (a.out / "soak.json").write_text(json.dumps(doc, indent=1) + "\n")
    zero = {m: v["zero_cells"] for m, v in fdict.items() if v["zero_cells"]}
    print(f"{PROG}: {doc['rays']} rays in {doc['batches']} batches: {mism} mismatched, "
          f"{harness_failures} harness failures; {doc['err_rays']} rays flagged err "
          f"({doc['err_rays_expected']} expected), {doc['invalid_rays']} invalid, "
          f"{doc['capped_rays']} capped; AXI latency {lat_seen[0]}..{lat_seen[1]}; "
          f"{doc['sim_clocks']:,} clocks simulated; rays part {fmt_time(rays_wall)} "
          f"({doc['rays_per_second']:,.0f} rays/s; model {t_model:.0f} s, harness {t_rtl:.0f} s)")
    if pipe:
        print(f"{PROG}: pipeline: {pipe['fragments']} fragments in {pipe['frames']} frames, "
              f"{pmism} mismatches, {pipe['err_pixels']} err pixels, {pipe['wall_seconds']:.0f} s")
    if zero:
        print(f"{PROG}: functional cells never reached: "
              + "; ".join(f"{m}: {', '.join(z)}" for m, z in zero.items()))
    print(f"{PROG}: seed {seed}; wall time {fmt_time(wall)}; {a.out / 'soak.json'}")
    if failures or pipe_log:
        print(f"{PROG}: FAILED: first mismatches:", file=sys.stderr)
        for f in (failures[:5] + pipe_log[:5]):
            print("  " + f, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
