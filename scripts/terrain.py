#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Terrain from a DEM: tessellation + parallax mapping against the exact render (Gonzalez, Perez,
Orduna 2016, Fig. 11), and the same DEM ray-cast by the pyramidal traversal (f64, f24, RTL).

  terrain.py (--dem FILE | --synthetic N) [--height-scale S] [--texture FILE] [--stretch]
             [--nodata V] [--bits 8|16] [--angle front|oblique|grazing|DEGREES] [--size N]
             [--cells 64,32,...] [--binary-span F] [--method NAME] [--rtl] [--out DIR] [--quiet]

--dem: any image OpenImageIO reads (16-bit PNG, TIFF / GeoTIFF, EXR, ...) or a .npy array; by
default integer images are divided by their type's maximum and float ones clamped to [0, 1] (the
project's rule); --stretch maps the DEM's own [min, max] onto [0, 1] instead (use it for DEMs in
metres; --nodata V marks void samples).  --height-scale: the relief in texels (relief in metres /
sample spacing in metres; default 8 % of the larger side, the project's depth rule).
--synthetic N: a fractal N x N terrain (model.terrain.synthetic_dem), saved as DIR/dem.png.

Writes DIR/terrain.json ({"mse": {method: [...]}, "triangles": [...], ...}, one entry per mesh
cell size, and "pyramidal": iterations per ray on each engine, RTL clocks with --rtl),
DIR/reference.png, DIR/<method>_cell<K>.png, DIR/pyramidal_f24.png and the plot
DIR/terrain_mse.png (their Fig. 11 a and b).  Bad input: one line naming the problem, exit 2.
"""
from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
from model import camera, terrain, texture, traverse
from model.cli import Parser, Progress, fail

PROG = "terrain.py"
MAX_IMAGE = 4096
MAX_SYNTHETIC = 8192


def parse_angle(text: str) -> str | float:
    if text in camera.VIEWS:
        return text
    try:
        e = float(text)
    except ValueError:
        fail(PROG, f"unknown angle {text!r} (front, oblique, grazing or an elevation in degrees)")
    if not 0.0 < e <= 90.0:
        fail(PROG, f"elevation must be in (0, 90] degrees, got {text!r}")
    return e


def parse_int(what: str, text: str, lo: int, hi: int) -> int:
    try:
        v = int(text, 10)
    except ValueError:
        fail(PROG, f"{what} must be an integer, got {text!r}")
    if not lo <= v <= hi:
        fail(PROG, f"{what} must be in {lo}..{hi}, got {v}")
    return v


def parse_float(what: str, text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        fail(PROG, f"{what} must be a number, got {text!r}")
    if not (np.isfinite(v) and v > 0):
        fail(PROG, f"{what} must be a positive number, got {text!r}")
    return v


def write_png(path: Path, img: np.ndarray) -> None:
    """8-bit RGB or 16-bit grey PNG through OpenImageIO."""
    import OpenImageIO as oiio

    if img.ndim == 2:
        img = img[..., None]          # OpenImageIO wants (H, W, C)
    hh, ww, ch = img.shape
    fmt = oiio.UINT16 if img.dtype == np.uint16 else oiio.UINT8
    out = oiio.ImageOutput.create(str(path))
    if out is None:
        fail(PROG, f"cannot write {path}: {oiio.geterror()}".splitlines()[0])
    try:
        if not out.open(str(path), oiio.ImageSpec(ww, hh, ch, fmt)):
            fail(PROG, f"cannot write {path}: {out.geterror()}".splitlines()[0])
        if not out.write_image(np.ascontiguousarray(img)):
            fail(PROG, f"cannot write {path}: {out.geterror()}".splitlines()[0])
    finally:
        out.close()


def plot(path: Path, res: terrain.StudyResult, title: str) -> None:
    """Fig. 11: a) MSE against triangles; b) each method's MSE against tessellation's."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.4))
    marks = dict(zip(terrain.METHODS, "osD^v"))
    colours = dict(zip(terrain.METHODS, ("C0", "C1", "C2", "C3", "C4")))
    for m in terrain.METHODS:
        a.plot(res.triangles, res.mse[m], marker=marks[m], color=colours[m], label=m)
    a.set_xscale("log")
    a.set_xlabel("triangles in the mesh")
    a.set_ylabel("MSE (8-bit RGB)")
    a.set_title("a) MSE against the full-resolution render")
    a.grid(True, which="both", alpha=0.3)
    a.legend()
    x = np.asarray(res.mse["tessellation"])
    imp = res.improvement()
    b.plot([0, x.max()], [0, x.max()], color="grey", lw=0.8, label="tessellation (slope 1)")
    for m in terrain.METHODS[1:]:
        b.plot(x, res.mse[m], marker=marks[m], ls="none", color=colours[m],
               label=f"{m} (1/slope {imp[m]:.2f})")
        b.plot([0, x.max()], [0, x.max() / imp[m]], lw=0.6, color=colours[m])
    b.set_xlabel("MSE of tessellation only")
    b.set_ylabel("MSE of tessellation + method")
    b.set_title("b) proportion of the MSEs")
    b.grid(True, alpha=0.3)
    b.legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    t_start = time.time()
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--dem", type=Path, help="elevation model: image (OpenImageIO) or .npy")
    src.add_argument("--synthetic", metavar="N", help="a fractal N x N terrain instead")
    ap.add_argument("--height-scale", metavar="S", help="relief in texels (default 8%% of the "
                    "larger side)")
    ap.add_argument("--texture", type=Path, help="colour texture (orthophoto) spanning the DEM")
    ap.add_argument("--stretch", action="store_true", help="map the DEM's [min, max] to [0, 1]")
    ap.add_argument("--nodata", metavar="V", help="void value of the DEM (with --stretch)")
    ap.add_argument("--bits", default="16", help="height storage: 8 or 16 (default 16)")
    ap.add_argument("--angle", default="oblique", help="front | oblique | grazing | elevation "
                    "in degrees (default oblique)")
    ap.add_argument("--size", default="256", help="image side in pixels (default 256)")
    ap.add_argument("--cells", help="mesh cell sizes in texels, comma-separated (default: "
                    "quarter of the larger side, halving down to 1)")
    ap.add_argument("--binary-span", default="1", help="binary search bracket: +- this many "
                    "mesh cells of arc length around the mesh hit (default 1)")
    ap.add_argument("--method", default="park", help="exact pyramidal method for the "
                    f"traversal part ({', '.join(traverse.EXACT_METHODS)}; default park)")
    ap.add_argument("--rtl", action="store_true", help="also trace on the RTL (Verilator)")
    ap.add_argument("--out", type=Path, default=Path("out/terrain"), help="output directory")
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    a = ap.parse_args(argv)

    bits = parse_int("--bits", a.bits, 8, 16)
    if bits not in (8, 16):
        fail(PROG, f"--bits must be 8 or 16, got {bits}")
    size = parse_int("--size", a.size, 8, MAX_IMAGE)
    span = parse_float("--binary-span", a.binary_span)
    angle = parse_angle(a.angle)
    if a.method not in traverse.EXACT_METHODS:
        fail(PROG, f"unknown method {a.method!r} (exact methods: "
                   f"{', '.join(traverse.EXACT_METHODS)})")
    nodata = None
    if a.nodata is not None:
        try:
            nodata = float(a.nodata)
        except ValueError:
            fail(PROG, f"--nodata must be a number, got {a.nodata!r}")
    try:
        a.out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        fail(PROG, f"cannot create {a.out}: {e.strerror}")

    if a.synthetic is not None:
        n = parse_int("--synthetic", a.synthetic, 2, MAX_SYNTHETIC)
        dem = terrain.synthetic_dem(n)
        dem_path = a.out / "dem.png"
        write_png(dem_path, np.rint(dem * 65535.0).astype(np.uint16))
        source: dict[str, Any] = {"synthetic": n, "file": str(dem_path)}
    else:
        dem_path = a.dem
        source = {"file": str(dem_path)}
    try:
        h, conv = terrain.load_dem(dem_path, stretch=a.stretch, nodata=nodata)
    except terrain.DemError as e:
        fail(PROG, f"--dem: {e}")
    source.update(conv)
    hh, ww = h.shape
    scale = camera.depth_scale(ww, hh) if a.height_scale is None else \
        parse_float("--height-scale", a.height_scale)
    tex = None
    if a.texture is not None:
        try:
            tex = texture.load_image(a.texture)
        except texture.TextureError as e:
            fail(PROG, f"--texture: {e}")
        if tex.shape[2] < 3:
            tex = np.repeat(tex[..., :1], 3, axis=2)
    if a.cells is None:
        cells = terrain.default_cells(ww, hh)
    else:
        cells = [parse_int("--cells", c.strip(), 1, max(ww, hh)) for c in a.cells.split(",")
                 if c.strip()]
        if not cells:
            fail(PROG, "--cells needs at least one cell size")
        cells = sorted(set(cells), reverse=True)

    ter = terrain.make_terrain(h, scale, tex, bits=bits)
    cam = camera.Camera.for_view(angle, ww, hh, size, size, depth_scale=scale)
    if not a.quiet:
        print(f"{PROG}: {ww}x{hh} DEM, height scale {scale:g} texels, {size}x{size} image, "
              f"{camera.elevation(angle):g} deg elevation, cells {cells}", file=sys.stderr)
    prog = Progress("mesh resolutions", len(cells), enabled=not a.quiet)
    res = terrain.run_study(ter, cam, cells, binary_span=span,
                            progress=lambda d, _t: prog.update(d))
    for name, img in res.images.items():
        write_png(a.out / f"{name}.png", img)

    if not a.quiet:
        print(f"{PROG}: pyramidal traversal ({a.method}) on f64, f24"
              f"{' and the RTL (builds the harness on first use)' if a.rtl else ''}",
              file=sys.stderr)
    rc = 0
    rtl_error = None
    if a.rtl:
        from tb.harness import traverse_system

        try:   # build (or find) the harness first, with its progress messages
            traverse_system.build("checked" if os.environ.get("RTL_ENGINE_CHECKED") == "1"
                                  else "fast", quiet=a.quiet)
            pyr = terrain.pyramidal(ter, cam, a.method, rtl=traverse_system.trace_rtl)
        except traverse_system.RtlEngineError as e:   # reported in the JSON and the exit status
            rtl_error = str(e).splitlines()[0]
            print(f"{PROG}: RTL engine failed: {rtl_error}", file=sys.stderr)
            rc = 1
    if not a.rtl or rtl_error is not None:
        pyr = terrain.pyramidal(ter, cam, a.method)
        if rtl_error is not None:
            pyr["rtl"] = {"error": rtl_error}
    write_png(a.out / "pyramidal_f24.png", pyr.pop("images")["f24"])

    doc = res.to_json()
    doc["pyramidal"] = pyr
    doc["settings"] = {"dem": source, "map": [hh, ww], "height_scale": scale, "bits": bits,
                       "elevation_deg": camera.elevation(angle),
                       "azimuth_deg": camera.AZIMUTH_DEG, "image": [size, size],
                       "binary_span_cells": span,
                       "texture": str(a.texture) if a.texture else "elevation ramp x hill shade"}
    doc["seconds_total"] = time.time() - t_start
    (a.out / "terrain.json").write_text(json.dumps(doc, indent=1) + "\n")
    plot(a.out / "terrain_mse.png", res,
         f"{source.get('file')}: {ww}x{hh}, height scale {scale:g}, "
         f"{camera.elevation(angle):g} deg, {size}x{size} pixels")
    if not a.quiet:
        w = max(len(m) for m in terrain.METHODS)
        print(f"{'triangles':>{w}} " + " ".join(f"{t:>9}" for t in res.triangles))
        for m in terrain.METHODS:
            print(f"{m:>{w}} " + " ".join(f"{x:9.1f}" for x in res.mse[m]))
        imp = res.improvement()
        print("MSE of tessellation / MSE of method (fit over resolutions): "
              + ", ".join(f"{m} {imp[m]:.2f}" for m in terrain.METHODS[1:]))
        line = (f"pyramidal {a.method}: {pyr['f64']['iterations_per_ray']:.2f} iterations/ray "
                f"(f64), {pyr['f24']['iterations_per_ray']:.2f} (f24)")
        if "cycles" in pyr.get("rtl", {}):
            r = pyr["rtl"]
            line += (f", RTL {r['cycles']} clocks = {r['cycles_per_iteration']:.3f} "
                     f"clocks/iteration, identical to f24: {r['identical_to_f24']}")
        print(line)
        print(f"{PROG}: wrote {a.out}/terrain.json, terrain_mse.png and "
              f"{len(res.images) + 1} images ({time.time() - t_start:.1f} s)")
    return rc


if __name__ == "__main__":
    sys.exit(main())
