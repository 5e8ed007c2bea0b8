#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Batch ray tracing through a height map (the interface of docs/conventions.md).

  trace.py --heightmap FILE --rays RAYS.npy --method NAME --engine f64|f24|rtl --out OUT.npz

RAYS.npy: float64 (N, 4): u0, v0, du, dv.  OUT.npz: t, u, v (NaN where no hit), hit, invalid,
iterations, and stats (a JSON string).  Bad input: one line naming the problem, exit status 2.
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from model import heightmap, traverse
from model.cli import Parser, Progress, fail
from model.rays import Rays, TraceResult

PROG = "trace.py"
CHUNK = 65536


def approx_methods() -> dict:
    try:
        from model import approx
    except ImportError:  # pragma: no cover - the approximate methods are part of the model
        return {}
    return approx.APPROX_METHODS


def load_rays(path: Path) -> Rays:
    if not path.is_file():
        fail(PROG, f"rays file not found: {path}")
    try:
        a = np.load(path, allow_pickle=False)
    except Exception as e:
        fail(PROG, f"cannot read rays file {path}: {type(e).__name__}: {e}".splitlines()[0])
    if not isinstance(a, np.ndarray):
        fail(PROG, f"rays file {path} holds no single array")
    if a.dtype != np.float64:
        fail(PROG, f"rays must be float64, {path} holds {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 4:
        fail(PROG, f"rays must have shape (N, 4), {path} holds {a.shape}")
    return Rays.from_array(a)


def trace_on_rtl(args, pyr, rays: Rays) -> int:
    """The whole batch through the Verilator harness (traverse unit + height cache + AXI memory)."""
    from tb.harness import traverse_system

    if not args.quiet:
        print("trace.py: building / running the Verilator harness ...", file=sys.stderr)
    res, stats = traverse_system.trace_rtl(pyr, rays, args.method)
    stats = {**stats, "engine": "rtl", "method": args.method}
    np.savez(args.out, **res.as_npz_dict(), stats=json.dumps(stats))
    if not args.quiet:
        print(json.dumps({k: stats[k] for k in ("rays", "cycles", "iterations",
                                                "height_cache_hits", "height_cache_misses",
                                                "mem_bytes") if k in stats}))
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--heightmap", required=True, type=Path, help="image (OpenImageIO) or .npy")
    ap.add_argument("--rays", required=True, type=Path, help="float64 (N, 4) .npy: u0, v0, du, dv")
    ap.add_argument("--method", required=True, help="exact: " + ", ".join(traverse.EXACT_METHODS) +
                    "; approximate (f64 only): parallax, parallax-iter, binary, relief, pom, distance")
    ap.add_argument("--engine", required=True, help="f64 | f24 | rtl")
    ap.add_argument("--out", required=True, type=Path, help="output .npz")
    ap.add_argument("--bits", type=int, default=8, choices=(8, 16), help="height storage (unorm)")
    ap.add_argument("--quiet", action="store_true", help="no progress output")
    args = ap.parse_args(argv)

    approx = approx_methods()
    if args.method not in traverse.METHODS and args.method not in approx:
        fail(PROG, f"unknown method {args.method!r} (exact: {', '.join(traverse.EXACT_METHODS)}; "
                   f"approximate: {', '.join(approx) or 'none'})")
    if args.engine not in ("f64", "f24", "rtl"):
        fail(PROG, f"unknown engine {args.engine!r} (f64, f24, rtl)")
    if args.method in approx and args.engine == "f24":
        fail(PROG, f"approximate method {args.method!r} runs on the f64 engine only")
    if args.method in approx and args.engine == "rtl":
        fail(PROG, f"approximate method {args.method!r} has no RTL (f64 engine only)")
    if not args.out.parent.exists():
        fail(PROG, f"output directory does not exist: {args.out.parent}")
    try:
        pyr = heightmap.build(heightmap.load(args.heightmap), bits=args.bits)
    except heightmap.HeightMapError as e:
        fail(PROG, str(e))
    rays = load_rays(args.rays)

    if args.engine == "rtl":
        return trace_on_rtl(args, pyr, rays)

    t0 = time.time()
    n = len(rays)
    out = TraceResult.empty(n)
    prog = Progress(f"trace {args.method}/{args.engine}", n, enabled=not args.quiet and n > CHUNK)
    for s in range(0, n, CHUNK):
        sub = rays.subset(slice(s, s + CHUNK))
        if args.method in approx:
            r = approx[args.method](pyr, sub)
        else:
            r = traverse.trace(pyr, sub, args.method, args.engine)
        for k, v in r.as_npz_dict().items():
            getattr(out, k)[s:s + len(sub)] = v
        prog.update(min(s + CHUNK, n))
    secs = time.time() - t0
    stats = {"rays": n, "hits": int(out.hit.sum()), "invalid": int(out.invalid.sum()),
             "iterations": int(out.iterations.sum()), "method": args.method,
             "engine": args.engine, "seconds": round(secs, 3),
             "rays_per_second": round(n / secs, 1) if secs > 0 else None,
             "map": [pyr.height, pyr.width], "levels": pyr.n + 1}
    np.savez(args.out, **out.as_npz_dict(), stats=json.dumps(stats))
    if not args.quiet:
        print(json.dumps(stats))
    return 0


if __name__ == "__main__":
    sys.exit(main())
