# SPDX-License-Identifier: Apache-2.0
"""traverse_start_level against model.traverse.start_node, bit for bit.

The module is a two-clock pipeline (setup stages T16 - T18): the vectors stream through it one per
enabled clock with random clock-enable gaps (tb.common.fp_unit.check_pipeline), and its outputs
(outside, start level k, start node cx / cy) are compared with the model's start decision for the
same start cell, end cell and configuration.  Maps from 1x1 to 32768x32768, square and not, every
method's start-level policy; random vectors (start cells in and one outside the padded map, end
points near the start, anywhere in the map, anywhere in the 20-bit index range) plus directed ones
(start and end on the map's corners and edges, the padded map's last cell, equal cells: level 0,
cells that only share the root: level n, the extreme indices).

Environment: SEED, VECTORS (random vectors, default 20,000 here: each takes a clock of the
pipeline, and the directed set adds about 17,000), WAVES=1.
"""
from __future__ import annotations

import os
from pathlib import Path

import cocotb
import numpy as np

from model import traverse
from model.traverse import EXACT_METHODS, METHODS
from tb.common import fp_unit, runner

HERE = Path(__file__).resolve().parent
IDX_W = 20      # traverse_pkg::IDX_W: the end point's floor (f24_to_index)
SIDX_W = 22     # traverse_pkg::sidx_t: the located start cell
#: (height, width) of the maps; n is the root level of the padded power-of-two square.
MAPS = [(1, 1), (1, 2), (2, 1), (2, 2), (3, 5), (7, 5), (16, 16), (37, 61), (64, 17), (100, 128),
        (256, 200), (1, 1000), (1024, 1024), (4097, 3), (16385, 16300), (32768, 1),
        (32768, 32768)]
OUTPUTS = ("outside_o", "k_o", "cx_o", "cy_o")
LATENCY = 2  # enabled clocks


def root_level(h: int, w: int) -> int:
    """model.heightmap.build's root level: N = 2^n >= max(W, H)."""
    return max(0, int(np.ceil(np.log2(max(h, w)))))


def vectors(rng: np.random.Generator, count: int) -> dict[str, np.ndarray]:
    """Random and directed vectors over MAPS: the module's inputs."""
    cols: dict[str, list[np.ndarray]] = {k: [] for k in (
        "n_i", "width_i", "height_i", "start_level_i", "c0x_i", "c0y_i", "ex_i", "ey_i")}

    def add(h: int, w: int, sl, c0x, c0y, ex, ey) -> None:
        m = len(c0x)
        cols["n_i"].append(np.full(m, root_level(h, w)))
        cols["width_i"].append(np.full(m, w))
        cols["height_i"].append(np.full(m, h))
        cols["start_level_i"].append(np.broadcast_to(np.asarray(sl, dtype=np.int64), (m,)))
        for k, v in (("c0x_i", c0x), ("c0y_i", c0y), ("ex_i", ex), ("ey_i", ey)):
            cols[k].append(np.asarray(v, dtype=np.int64))

    # The start-level policy of every method (a per-vector random method for the random part).
    sl_of = np.array([int(METHODS[m].start_level) for m in EXACT_METHODS])
    per_map = max(1, count // len(MAPS))
    for h, w in MAPS:
        big = 1 << root_level(h, w)
        # directed: start cells on every corner / edge of the map and of the padded map, each
        # with end cells equal to it (level 0), on the map's far corners and edges, on the padded
        # map's last cell, and at the ends of the index range (clipped)
        cand_x = np.unique([-1, 0, w // 2, w - 1, w, big - 1, big])
        cand_y = np.unique([-1, 0, h // 2, h - 1, h, big - 1, big])
        lo, hi = -(1 << (IDX_W - 1)), (1 << (IDX_W - 1)) - 1
        sx, sy = (a.ravel() for a in np.meshgrid(cand_x, cand_y, indexing="ij"))
        ends = [(sx, sy), (np.full_like(sx, w - 1), np.full_like(sy, h - 1)),
                (np.zeros_like(sx), np.zeros_like(sy)), (np.full_like(sx, w - 1), sy),
                (sx, np.full_like(sy, h - 1)),
                (np.full_like(sx, big - 1), np.full_like(sy, big - 1)),
                (np.full_like(sx, lo), np.full_like(sy, lo)), (np.full_like(sx, hi), sy),
                (sx, np.full_like(sy, hi)), (np.full_like(sx, 2 * big), np.full_like(sy, w))]
        c0x, c0y = np.tile(sx, len(ends)), np.tile(sy, len(ends))
        ex = np.concatenate([e[0] for e in ends])
        ey = np.concatenate([e[1] for e in ends])
        for sl in (0, 1):
            add(h, w, sl, c0x, c0y, ex, ey)
        # random: start mostly in the map, else in [-1, N]; end equal to the start, near it,
        # anywhere around the map or anywhere in the index range
        m = per_map
        pad = rng.random(m) < 0.3
        c0x = np.where(pad, rng.integers(-1, big + 1, m), rng.integers(0, w, m))
        c0y = np.where(pad, rng.integers(-1, big + 1, m), rng.integers(0, h, m))
        kind = rng.integers(0, 4, m)
        span = 1 << rng.integers(0, root_level(h, w) + 1, m)
        near_x = c0x + rng.integers(-span, span + 1)
        near_y = c0y + rng.integers(-span, span + 1)
        ex = np.select([kind == 0, kind == 1, kind == 2],
                       [c0x, near_x, rng.integers(-big, 2 * big + 1, m)],
                       rng.integers(-(1 << (IDX_W - 1)), 1 << (IDX_W - 1), m))
        ey = np.select([kind == 0, kind == 1, kind == 2],
                       [c0y, near_y, rng.integers(-big, 2 * big + 1, m)],
                       rng.integers(-(1 << (IDX_W - 1)), 1 << (IDX_W - 1), m))
        # a few starts anywhere in the 22-bit cell range (the module clips any value)
        wild = rng.random(m) < 0.03
        c0x[wild] = rng.integers(-(1 << (SIDX_W - 1)), 1 << (SIDX_W - 1), int(wild.sum()))
        add(h, w, sl_of[rng.integers(0, len(sl_of), m)], c0x, c0y, ex, ey)
    return {k: np.concatenate(v) for k, v in cols.items()}


def expected(v: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """model.traverse.start_node, per configuration (it takes the map and policy as scalars)."""
    out = {k: np.zeros(len(v["n_i"]), dtype=np.int64) for k in OUTPUTS}
    cfg = np.stack([v["n_i"], v["width_i"], v["height_i"], v["start_level_i"]], axis=1)
    for n, w, h, sl in np.unique(cfg, axis=0):
        sel = np.all(cfg == (n, w, h, sl), axis=1)
        outside, k, cx, cy = traverse.start_node(v["c0x_i"][sel], v["c0y_i"][sel], v["ex_i"][sel],
                                                 v["ey_i"][sel], int(w), int(h), int(n), bool(sl))
        out["outside_o"][sel] = outside
        out["k_o"][sel] = k
        out["cx_o"][sel] = cx & 0xFFFF
        out["cy_o"][sel] = cy & 0xFFFF
    return out


@cocotb.test()
async def start_level_random_and_directed(dut):
    rng = np.random.default_rng(fp_unit.seed())
    v = vectors(rng, int(os.environ.get("VECTORS", "20000")))
    exp = expected(v)
    # Ports take the vectors' two's-complement bits (signed cells masked to their widths).
    masked = {k: x & ((1 << len(getattr(dut, k))) - 1) for k, x in v.items()}
    # check_pipeline raises on any mismatch (the first ten reported) after the whole stream.
    n = await fp_unit.check_pipeline(dut, LATENCY, masked, exp, rng,
                                     describe=lambda i: str({k: int(x[i]) for k, x in v.items()}),
                                     label="RTL vs model.traverse.start_node")
    levels = np.bincount(exp["k_o"], minlength=16)
    dut._log.info("start levels reached (model): %s", levels.tolist())
    dut._log.info("VECTORS traverse_start_level: %d, 0 mismatches", n)


def test_traverse_start_level():
    runner.run("traverse_start_level", "test_traverse_start_level", HERE)
