#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""A clock-by-clock queue model of the one-ring pipeline's traversal, fed with the model's
per-pixel iteration counts and hit flags in the bench's fragment order: how many ring slots
pass the entry empty for a given input rate and buffer sizes (what-if figures for
docs/results/pipeline-bench.md; the RTL's own counts come from scripts/bench/ring_probe.py).

The model: a ray enters a buffer of --buffer rays (FIFO #0, traverse_setup and its FIFO) at most
every --gap clocks (the view unit's and setup's rate) while fewer than --slots pixels are
inside; the ring has --depth slots, one passing the entry per clock; a slot that is empty, or
whose ray has just made its last pass and leaves, takes the buffer's head; a ray makes as many
passes as it has iterations (every height lookup hits: the cache's missed lookups are not
modelled); a finished ray leaves into a result FIFO of --res-depth (else it goes round again);
a hit leaves that FIFO at most every 4th clock and holds its slot id --back-end clocks more, a
miss leaves at once.  Prints clocks / iterations and the empty and held slot passes per
iteration.
"""
from __future__ import annotations

import sys
from collections import deque
from pathlib import Path

import numpy as np
import numpy.typing as npt

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from model import camera, scenes, shade  # noqa: E402
from model.cli import Parser, fail  # noqa: E402
from tb.harness import dm_pipeline, sv_params  # noqa: E402

PROG = "ring_queue.py"
LOOP_DEPTH = sv_params.value("traverse_pkg", "LOOP_DEPTH")  # the ring's stages


def frame_rays(scene: str, view: str, map_side: int, image: int,
               jobs: int) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.bool_]]:
    """Iterations and hit flags per pixel, in the pipeline harness's fragment order."""
    frame, cam = dm_pipeline.scene_frame(scene, map_side, view, image, "park", True)
    ref = shade.render(frame, cam, jobs=jobs)
    f, _ = shade.pixel_inputs(cam, ref.frags)
    order = camera.tile_order(f.row, f.col, cam.image_w, dm_pipeline.DEFAULT_TILE,
                              dm_pipeline.DEFAULT_BLOCKS)
    return (np.asarray(ref.out.iterations, dtype=np.int64)[order],
            np.asarray(ref.out.hit, dtype=bool)[order])


def simulate(iters: npt.NDArray[np.int64], hits: npt.NDArray[np.bool_], *, gap: int,
             buffer: int, depth: int, res_depth: int, slots: int,
             back_end: int) -> tuple[int, int, int]:
    """(clocks, empty slot passes, held slot passes) of the queue model in the module doc."""
    n = len(iters)
    rem = [0] * depth
    occ = [False] * depth
    fin = [False] * depth
    hit = [False] * depth
    buf: deque[tuple[int, bool]] = deque()
    res: deque[bool] = deque()
    be: deque[int] = deque()
    nxt = t = out = empty = held = inside = 0
    i = 0
    last_hit = -4
    while out < n:
        while be and be[0] <= t:
            be.popleft()
            out += 1
            inside -= 1
        if i < n and t >= nxt and len(buf) < buffer and inside < slots:
            if iters[i] == 0:  # setup finished it (the RTL's bypass): straight to the results
                res.append(bool(hits[i]))
            else:
                buf.append((int(iters[i]), bool(hits[i])))
            i += 1
            nxt = t + gap
            inside += 1
        if res:
            if not res[0]:
                res.popleft()
                out += 1
                inside -= 1
            elif t - last_hit >= 4:
                res.popleft()
                last_hit = t
                be.append(t + back_end)
        p = t % depth
        if occ[p] and fin[p]:
            if len(res) < res_depth:
                res.append(hit[p])
                occ[p] = False
            else:
                held += 1
        if occ[p]:
            if not fin[p]:
                rem[p] -= 1
                fin[p] = rem[p] == 0
        elif buf:
            r, h = buf.popleft()
            occ[p], rem[p], hit[p], fin[p] = True, r - 1, h, r == 1
        else:
            empty += 1
        t += 1
    return t, empty, held


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--frames", default="bump:oblique,bump:grazing,rocks:oblique",
                    help="comma-separated scene:view pairs")
    ap.add_argument("--map", type=int, default=256, help="height map side (default 256)")
    ap.add_argument("--image", type=int, default=512, help="image side (default 512)")
    ap.add_argument("--gap", default="4", help="clocks between rays, comma-separated (default 4)")
    ap.add_argument("--buffer", default="48",
                    help="rays between the input and the ring, comma-separated (default 48: "
                         "FIFO #0 16 + setup and its FIFO 32)")
    ap.add_argument("--depth", type=int, default=LOOP_DEPTH,
                    help=f"ring stages (default traverse_pkg::LOOP_DEPTH, {LOOP_DEPTH})")
    ap.add_argument("--res-depth", type=int, default=16, help="result FIFO (default 16)")
    ap.add_argument("--slots", type=int, default=128, help="pixels inside (default 128)")
    ap.add_argument("--back-end", type=int, default=150,
                    help="clocks a hit holds its slot after the result FIFO (default 150)")
    ap.add_argument("--jobs", type=int, default=1, help="model render processes (default 1)")
    a = ap.parse_args(argv)
    try:
        gaps = [int(x) for x in a.gap.split(",")]
        buffers = [int(x) for x in a.buffer.split(",")]
    except ValueError:
        fail(PROG, "--gap and --buffer take comma-separated integers")
    if min(gaps) < 1 or min(buffers) < 1 or a.depth < 1 or a.res_depth < 1 or a.slots < 1:
        fail(PROG, "--gap, --buffer, --depth, --res-depth and --slots must be positive")
    frames = []
    for f in a.frames.split(","):
        s, sep, v = f.strip().partition(":")
        if not sep or s not in scenes.SCENES or v not in camera.VIEWS:
            fail(PROG, f"--frames: {f!r} is not scene:view")
        frames.append((s, v))
    for s, v in frames:
        iters, hits = frame_rays(s, v, a.map, a.image, a.jobs)
        total = max(int(iters.sum()), 1)
        print(f"{s} {v}: {len(iters):,} pixels, {total:,} iterations, {int(hits.sum()):,} hits, "
              f"{float((iters < 4).mean()):.1%} of the pixels under 4 iterations", flush=True)
        for g in gaps:
            for b in buffers:
                t, e, h = simulate(iters, hits, gap=g, buffer=b, depth=a.depth,
                                   res_depth=a.res_depth, slots=a.slots, back_end=a.back_end)
                print(f"  gap {g}, buffer {b}: clocks {t:,}, clocks/iteration {t / total:.4f}, "
                      f"empty {e / total:.4f}/iter, held {h / total:.4f}/iter", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
