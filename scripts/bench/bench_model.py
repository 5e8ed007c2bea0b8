#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Model speed (make bench): traversal rays/s per engine, method and angle on a 256x256 scene.

Prints a table and writes JSON (default out/bench/model.json).  Each figure is the best of
--repeat runs of the same ray batch (one ray per covered pixel of a --image-size camera image).
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from model import camera, heightmap, scenes, traverse
from model.cli import Parser, fail


def main() -> int:
    ap = Parser(prog="bench_model.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="rocks")
    ap.add_argument("--size", type=int, default=256, help="map size (texels)")
    ap.add_argument("--image-size", type=int, default=256)
    ap.add_argument("--methods", default="oh,tevs,park,park-xor")
    ap.add_argument("--angles", default="front,oblique,grazing")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", type=Path, default=ROOT / "out" / "bench" / "model.json")
    args = ap.parse_args()
    if args.scene not in scenes.SCENES:
        fail("bench_model.py", f"unknown scene {args.scene!r}")
    for what, v, lo in (("--size", args.size, 2), ("--image-size", args.image_size, 1),
                        ("--repeat", args.repeat, 1)):
        if not lo <= v <= 8192:
            fail("bench_model.py", f"{what} must be in {lo}..8192, got {v}")
    angles = args.angles.split(",")
    bad_angles = [a for a in angles if a not in camera.VIEWS]
    if bad_angles:
        fail("bench_model.py", f"unknown angle(s) {', '.join(bad_angles)} (one of "
                               f"{', '.join(camera.VIEWS)})")
    methods = args.methods.split(",")
    bad = [m for m in methods if m not in traverse.METHODS]
    if bad:
        fail("bench_model.py", f"unknown method(s) {', '.join(bad)}")
    sc = scenes.load_scene(args.scene, args.size)
    pyr = heightmap.build(sc.heights)
    rows = []
    print(f"{'angle':8} {'method':10} {'engine':6} {'rays':>7} {'iter/ray':>9} {'rays/s':>10}")
    for angle in angles:
        rays = camera.Camera.for_view(angle, args.size, args.size, args.image_size,
                                      args.image_size).rays().rays
        for m in methods:
            for eng in ("f64", "f24"):
                best = float("inf")
                for _ in range(args.repeat):
                    t0 = time.perf_counter()
                    res = traverse.trace(pyr, rays, m, eng)
                    best = min(best, time.perf_counter() - t0)
                row = {"scene": args.scene, "angle": angle, "method": m, "engine": eng,
                       "rays": len(rays), "iterations_per_ray": float(res.iterations.mean()),
                       "rays_per_second": len(rays) / best}
                rows.append(row)
                print(f"{angle:8} {m:10} {eng:6} {len(rays):7d} {row['iterations_per_ray']:9.2f} "
                      f"{row['rays_per_second']:10,.0f}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
