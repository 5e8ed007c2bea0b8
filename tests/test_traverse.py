# SPDX-License-Identifier: Apache-2.0
"""The exact pyramidal traversals against the texel-by-texel reference walk.

Every exact method, in both engines, on random and adversarial rays (axis-parallel, vertical,
along texel edges, through corners, grazing with |du|, |dv| up to several times the map size), on
maps from 2x2 to 1024x1024 and non-square ones: zero differences in hit, t, u, v (and invalid).
"""
from __future__ import annotations

import numpy as np
import pytest

from model import heightmap, traverse
from model.rays import Rays
from reference_walk import walk
from tb.common import report
from tb.common.traverse_stimulus import adversarial_rays, height_field

SIZES = [(1, 1), (2, 2), (3, 5), (8, 8), (37, 61), (64, 17), (128, 128), (256, 200), (1024, 1024)]


def same(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (a == b) | (np.isnan(a) & np.isnan(b))


@pytest.mark.parametrize("engine", ["f64", "f24"])
@pytest.mark.parametrize("size", SIZES, ids=[f"{h}x{w}" for h, w in SIZES])
def test_exact_methods_equal_walk(size: tuple[int, int], engine: str,
                                  rng: np.random.Generator) -> None:
    h, w = size
    n = 4000 if h * w < 1 << 16 else 2000
    total = 0
    for kind in range(3):
        pyr = heightmap.build(height_field(rng, h, w, kind))
        rays = adversarial_rays(rng, w, h, n)
        ref = walk(pyr, rays, engine)
        assert ref.invalid[-8:].all()
        if engine == "f64":  # (in f24, u0 = w - 1e-9 rounds to w: outside)
            assert not ref.invalid[:-8].any()
        for m in traverse.EXACT_METHODS:
            res = traverse.trace(pyr, rays, m, engine)
            bad = ~(same(res.t, ref.t) & same(res.u, ref.u) & same(res.v, ref.v) &
                    (res.hit == ref.hit) & (res.invalid == ref.invalid))
            total += len(rays)
            report.record("model.traverse", f"exact methods vs walk ({engine})", len(rays),
                          int(bad.sum()))
            assert not bad.any(), (m, kind, np.nonzero(bad)[0][:5])
            assert (res.iterations <= traverse.iteration_cap(pyr)).all()
            assert (res.iterations[res.invalid] == 0).all()
    print(f"{h}x{w} {engine}: {total} ray traces, 0 differences")


def test_every_valid_ray_in_the_map_at_t1_hits(rng: np.random.Generator) -> None:
    """The floor is solid: a ray still inside the map at t = 1 always hits, at t <= 1."""
    pyr = heightmap.build(rng.random((50, 70)) * 0.2)
    rays = adversarial_rays(rng, 70, 50, 4000)
    u1, v1 = rays.u0 + rays.du, rays.v0 + rays.dv
    inside = (u1 > 0.5) & (u1 < 69.5) & (v1 > 0.5) & (v1 < 49.5) & np.isfinite(u1 + v1)
    res = traverse.trace(pyr, rays, "park", "f64")
    assert res.hit[inside & ~res.invalid].all()
    assert (res.t[res.hit] <= 1).all() and (res.t[res.hit] >= 0).all()


def test_iteration_cap_is_never_reached_on_worst_rays() -> None:
    """Grazing rays over a flat floor cross every texel: the cap holds with room to spare."""
    w = h = 64
    pyr = heightmap.build(np.zeros((h, w)))
    n = 200
    rays = Rays(np.full(n, 0.5), np.linspace(0.5, 63.5, n), np.full(n, 1e4), np.linspace(-3e3, 3e3, n))
    cap = traverse.iteration_cap(pyr)
    for m in traverse.EXACT_METHODS:
        for eng in ("f64", "f24"):
            res = traverse.trace(pyr, rays, m, eng)
            assert res.iterations.max() < cap, (m, eng, res.iterations.max(), cap)


def test_f24_agrees_with_f64_on_hit_texel(rng: np.random.Generator) -> None:
    """The f24 engine finds the same hit texel as f64 for well above 99% of rays."""
    pyr = heightmap.build(rng.random((256, 256)) ** 2)
    rays = adversarial_rays(rng, 256, 256, 20000)
    a = traverse.trace(pyr, rays, "park", "f64")
    b = traverse.trace(pyr, rays, "park", "f24")
    both = a.hit & b.hit
    same_texel = (np.floor(a.u[both] - 1e-9 * np.sign(rays.du[both])) ==
                  np.floor(b.u[both] - 1e-9 * np.sign(rays.du[both])))
    agree = (np.count_nonzero(same_texel) + np.count_nonzero(~a.hit & ~b.hit)) / len(rays)
    print(f"f24 vs f64 hit agreement: {agree:.4%}")
    assert agree > 0.99


def test_method_iterations_order(rng: np.random.Generator) -> None:
    """The paper's claims in shape: park needs fewer iterations than oh and tevs."""
    pyr = heightmap.build(rng.random((256, 256)) ** 3)
    rays = adversarial_rays(rng, 256, 256, 8000)
    it = {m: traverse.trace(pyr, rays, m, "f64").iterations.mean() for m in traverse.EXACT_METHODS}
    assert it["park"] < it["oh"] and it["park"] < it["tevs"]
    assert it["start-level"] < it["oh"] and it["multi-down"] < it["oh"]


def test_step_record_follows_one_ray() -> None:
    pyr = heightmap.build(np.array([[0.0, 1.0], [0.0, 0.0]]))
    rec: list[dict] = []
    res = traverse.trace(pyr, Rays(np.array([0.5]), np.array([0.5]), np.array([2.0]),
                                   np.array([0.0])), "oh", "f64", record=rec)
    assert res.hit[0] and res.t[0] == 0.25  # enters texel (0, 1) at u = 1: t = 0.25
    assert len(rec) == res.iterations[0] and rec[-1]["action"] == "hit"
    assert rec[0]["level"] == 1


@pytest.mark.parametrize("bits", [8, 16])
def test_touched_texels_and_lines(rng: np.random.Generator, bits: int) -> None:
    """trace(touched=...) marks exactly the texels the per-ray step records read, and
    lines_touched counts the distinct cache lines of their byte addresses (the slow way)."""
    h, w = 23, 37
    pyr = heightmap.build(height_field(rng, h, w, 1), bits=bits)
    rays = adversarial_rays(rng, w, h, 60)
    touched = np.zeros(traverse.pyramid_texels(pyr), dtype=bool)
    res = traverse.trace(pyr, rays, "park", "f24", touched=touched)
    cells = set()
    for i in range(len(rays)):
        rec: list[dict] = []
        traverse.trace(pyr, rays.subset([i]), "park", "f24", record=rec)
        assert len(rec) == res.iterations[i]
        cells |= {(r["level"], r["cy"], r["cx"]) for r in rec}
    assert cells, "no ray read a texel"
    offs = np.cumsum([0] + [lv.size for lv in pyr.levels]).astype(np.int64)
    marked = {(k, int(f - offs[k]) // (pyr.size >> k), int(f - offs[k]) % (pyr.size >> k))
              for f in np.nonzero(touched)[0] for k in [int(np.searchsorted(offs, f, "right")) - 1]}
    assert marked == cells
    byte_offs, bpt = pyr.level_offsets(), bits // 8
    for line, base in ((32, 0), (64, 0x4000_0000), (32, 16)):
        want = {(base + byte_offs[k] + (cy * (pyr.size >> k) + cx) * bpt) // line
                for k, cy, cx in cells}
        assert traverse.lines_touched(pyr, touched, line, base) == len(want)


def _lowest_shared_level(ax, bx, ay, by, top: int) -> np.ndarray:
    """The lowest level <= top at which (ax, ay) and (bx, by) lie in one node, the slow way."""
    out = np.full(len(ax), top)
    for k in range(top, -1, -1):
        same = ((ax >> k) == (bx >> k)) & ((ay >> k) == (by >> k))
        out = np.where(same, k, out)
    return out


def test_factored_pieces_match_their_definitions(rng: np.random.Generator) -> None:
    """start_node, descent_level, crossing_step and texel_offset (the pieces of the trace loop the
    RTL's unit tests compare against) agree with their definitions computed the slow way."""
    n, w, h = 7, 100, 77
    big = 1 << n
    m = 20000
    # start: the lowest level where the clipped start and end cells share a node (a), else n
    c0x, c0y = rng.integers(-1, big + 1, m), rng.integers(-1, big + 1, m)
    ex, ey = c0x + rng.integers(-40, 41, m), c0y + rng.integers(-40, 41, m)
    outside, k, cx, cy = traverse.start_node(c0x, c0y, ex, ey, w, h, n, True)
    sx, sy = np.clip(c0x, 0, big - 1), np.clip(c0y, 0, big - 1)
    want = _lowest_shared_level(sx, np.clip(ex, 0, big - 1), sy, np.clip(ey, 0, big - 1), n)
    assert (k == want).all() and (cx == sx >> k).all() and (cy == sy >> k).all()
    assert (outside == ((c0x < 0) | (c0x >= w) | (c0y < 0) | (c0y >= h))).all()
    assert (traverse.start_node(c0x, c0y, None, None, w, h, n, False)[1] == n).all()
    # xor descent: the lowest node holding both ends inside this node, at most the multi level
    k = rng.integers(1, n + 1, m)
    cx, cy = rng.integers(0, big >> k), rng.integers(0, big >> k)
    crossed = rng.random(m) < 0.3
    ends = [(c << k) + rng.integers(-3, (1 << k) + 3) for c in (cx, cx, cy, cy)]
    clipped = [np.clip(e, c << k, ((c + 1) << k) - 1) for e, c in zip(ends, (cx, cx, cy, cy))]
    multi = k - np.where(crossed, 1, np.minimum(3, k))
    assert (traverse.descent_level("multi", 3, k, crossed) == multi).all()
    assert (traverse.descent_level("one", 3, k, crossed) == k - 1).all()
    nk = traverse.descent_level("xor", 3, k, crossed, cx, cy, ends[0], ends[2], ends[1], ends[3])
    want = np.minimum(_lowest_shared_level(*clipped, n), multi)
    assert (nk == np.maximum(want, 0)).all()
    # crossing: drobot always goes up below the root, to the parent of the neighbour
    step = rng.integers(-1, 2, m)
    k = rng.integers(0, n + 1, m)
    cx, cy = rng.integers(0, big >> k), rng.integers(0, big >> k)
    nk, nx, ny, up = traverse.crossing_step("drobot", n, k, cx, cy, step, 0 * step, crossed)
    assert (up == (k < n)).all() and (nk == k + up).all()
    assert (nx == np.where(up, (cx + step) >> 1, cx + step)).all()
    assert (ny == np.where(up, cy >> 1, cy)).all()
    # texel_offset: the byte offset of a node holds its code in the memory image
    for bits in (8, 16):
        pyr = heightmap.build(rng.integers(0, 1 << bits, (h, w)).astype(np.uint16), bits)
        img = np.frombuffer(pyr.memory_image(), dtype=np.uint8).astype(np.int64)
        k = rng.integers(0, n + 1, 4000)
        cx, cy = rng.integers(0, big >> k), rng.integers(0, big >> k)
        off = traverse.texel_offset(pyr.level_offsets(), n, k, cx, cy, bits // 8)
        code = img[off] if bits == 8 else img[off] | (img[off + 1] << 8)
        assert (code == [pyr.levels[a][c, b] for a, b, c in zip(k, cx, cy)]).all()
