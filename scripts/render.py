#!/usr/bin/env python3
"""Render a displacement-mapped quad through the golden model (trace, MIP-mapped texture, shading).

  render.py [--scene NAME | --heightmap FILE [--texture FILE] [--normal-map FILE]]
            [--angle front|oblique|grazing|DEGREES] [--method NAME] [--engine f64|f24]
            [--size N] [--map-size N] [--out PNG] [--stats JSON] [--jobs J] [--no-mip]

Writes the image (PNG through OpenImageIO) and a JSON of statistics.  Without --texture a user
height map is coloured by a height ramp (``height_ramp``); without --normal-map its normals come
from the heights (``model.scenes.normal_map``).  Bad input: one line naming the problem, exit 2.
"""
from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from model import camera, heightmap, scenes, shade, texture, traverse  # noqa: E402
from model.cli import Parser, Progress, fail  # noqa: E402

PROG = "render.py"
MAX_SIZE = 8192
MAX_MAP = 8192
DEFAULT_JOBS = max(1, min(os.cpu_count() or 1, 8))
PROGRESS_MIN_PIXELS = 1 << 17
#: The approximate methods of CONVENTIONS (model.approx, imported only when one is asked for).
APPROX_NAMES = ("parallax", "parallax-iter", "binary", "relief", "pom", "distance")

#: Stops of the height ramp of user height maps without a texture: (height, R, G, B).
RAMP = np.array([(0.00, 0.20, 0.16, 0.12), (0.30, 0.42, 0.36, 0.24), (0.55, 0.46, 0.52, 0.30),
                 (0.80, 0.62, 0.60, 0.56), (1.00, 0.95, 0.95, 0.97)])


def height_ramp(h: np.ndarray) -> np.ndarray:
    """The procedural texture of a height map: a piecewise-linear colour ramp over the height
    (dark soil, earth, moss, rock, snow), float32 (H, W, 3) in [0, 1]."""
    out = np.stack([np.interp(h, RAMP[:, 0], RAMP[:, c]) for c in (1, 2, 3)], axis=-1)
    return out.astype(np.float32)


def positive_int(what: str, text: str, hi: int) -> int:
    try:
        v = int(text, 10)
    except ValueError:
        fail(PROG, f"{what} must be a positive integer, got {text!r}")
    if v < 1 or v > hi:
        fail(PROG, f"{what} must be in 1..{hi}, got {v}")
    return v


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


def load_map_image(what: str, path: Path) -> np.ndarray:
    try:
        return texture.load_image(path)
    except texture.TextureError as e:
        fail(PROG, f"{what}: {e}")


def main(argv: list[str] | None = None) -> int:
    t_start = time.time()
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    src = ap.add_mutually_exclusive_group()
    src.add_argument("--scene", help=f"procedural scene: {', '.join(scenes.SCENES)} "
                     "(default rocks)")
    src.add_argument("--heightmap", type=Path, help="height map: image (OpenImageIO) or .npy")
    ap.add_argument("--texture", type=Path, help="colour texture for --heightmap (any size)")
    ap.add_argument("--normal-map", type=Path, help="tangent-space normal map for --heightmap, "
                    "encoded (n + 1) / 2 (any size)")
    ap.add_argument("--angle", default="oblique", help="front | oblique | grazing | elevation in "
                    "degrees (default oblique)")
    ap.add_argument("--method", default="park", help="exact: " + ", ".join(traverse.EXACT_METHODS)
                    + "; approximate (f64 only): " + ", ".join(APPROX_NAMES) + " (default park)")
    ap.add_argument("--engine", help="f64 | f24 (default f24; f64 for approximate methods); "
                    "rtl arrives with the pipeline RTL")
    ap.add_argument("--size", default="256", help="image N x N pixels (default 256)")
    ap.add_argument("--map-size", help="map N x N texels of a procedural scene (default 256)")
    ap.add_argument("--bits", type=int, default=8, choices=(8, 16), help="height storage (unorm)")
    ap.add_argument("--out", type=Path, default=Path("out/render_model.png"), help="output PNG")
    ap.add_argument("--stats", type=Path, default=Path("out/render_model_stats.json"),
                    help="output statistics JSON")
    ap.add_argument("--jobs", default=str(DEFAULT_JOBS), help="processes, by image tiles "
                    f"(default {DEFAULT_JOBS}: the CPUs); the image does not depend on it")
    ap.add_argument("--tile", default="256", help="tile size in pixels (default 256)")
    ap.add_argument("--no-mip", action="store_true", help="always texture level 0 (MIP off)")
    ap.add_argument("--quiet", action="store_true", help="no progress or summary output")
    args = ap.parse_args(argv)

    # ---- arguments ----------------------------------------------------------------------------
    approx = {} if args.method in traverse.METHODS else shade.approx_methods()
    if args.method not in traverse.METHODS and args.method not in approx:
        fail(PROG, f"unknown method {args.method!r} (exact: {', '.join(traverse.EXACT_METHODS)}; "
                   f"approximate: {', '.join(approx) or 'none'})")
    engine = args.engine or ("f64" if args.method in approx else "f24")
    if engine == "rtl":
        fail(PROG, "engine 'rtl' is not available yet: it arrives with the pipeline RTL "
                   "(make render); use f64 or f24")
    if engine not in ("f64", "f24"):
        fail(PROG, f"unknown engine {engine!r} (f64, f24, rtl)")
    if args.method in approx and engine != "f64":
        fail(PROG, f"approximate method {args.method!r} runs on the f64 engine only")
    size = positive_int("--size", args.size, MAX_SIZE)
    jobs = positive_int("--jobs", args.jobs, 256)
    tile = positive_int("--tile", args.tile, MAX_SIZE)
    angle = parse_angle(args.angle)
    if args.heightmap is None and (args.texture is not None or args.normal_map is not None):
        fail(PROG, "--texture and --normal-map go with --heightmap (a scene has its own)")
    if args.heightmap is not None and args.map_size is not None:
        fail(PROG, "--map-size applies to --scene only (a height map file has its own size)")
    for what, p in (("--out", args.out), ("--stats", args.stats)):
        if p.exists() and p.is_dir():
            fail(PROG, f"{what} is a directory: {p}")

    # ---- inputs -------------------------------------------------------------------------------
    if args.heightmap is None:
        name = args.scene or "rocks"
        if name not in scenes.SCENES:
            fail(PROG, f"unknown scene {name!r} (valid scenes: {', '.join(scenes.SCENES)})")
        msize = positive_int("--map-size", args.map_size or "256", MAX_MAP)
        sc = scenes.load_scene(name, msize)
        h, colour_img, depth = sc.heights, sc.texture, sc.depth_scale
        normal_codes = scenes.encode_normals(sc.normals)
        scene_name = name
    else:
        try:
            h = heightmap.load(args.heightmap)
        except heightmap.HeightMapError as e:
            fail(PROG, str(e).splitlines()[0])
        except Exception as e:  # OpenImageIO reports some problems as exceptions
            fail(PROG, f"cannot read {args.heightmap}: {e}".splitlines()[0])
        if h.shape[0] > MAX_MAP or h.shape[1] > MAX_MAP:
            fail(PROG, f"height map {args.heightmap} is {h.shape[1]} x {h.shape[0]}; "
                       f"the limit is {MAX_MAP} texels a side")
        depth = camera.depth_scale(h.shape[1], h.shape[0])
        colour_img = (load_map_image("--texture", args.texture) if args.texture is not None
                      else height_ramp(h))
        if args.normal_map is not None:
            nm = load_map_image("--normal-map", args.normal_map)
            if nm.shape[2] < 3:
                fail(PROG, f"--normal-map {args.normal_map} has {nm.shape[2]} channel(s), "
                           "needs 3 (encoded x, y, z)")
            normal_codes = np.rint(nm[..., :3] * 255.0).astype(np.uint8)
        else:
            normal_codes = scenes.encode_normals(scenes.normal_map(h, depth))
        scene_name = str(args.heightmap)
    pyr = heightmap.build(h, bits=args.bits)
    tex = texture.build(colour_img)
    ntex = texture.build(normal_codes)
    mw, mh = pyr.width, pyr.height
    try:
        cam = camera.Camera.for_view(angle, mw, mh, size, size, depth_scale=depth)
    except ValueError as e:
        fail(PROG, str(e))
    frame = shade.Frame(pyr=pyr, colour=tex, normals=ntex, depth_scale=depth,
                        log2pb_colour=cam.log2_pb(tex.width, tex.height),
                        log2pb_normal=cam.log2_pb(ntex.width, ntex.height),
                        method=args.method, engine=engine, mip=not args.no_mip)

    # ---- render -------------------------------------------------------------------------------
    prog = Progress(f"render {args.method}/{engine} {size}x{size}", 1,
                    enabled=not args.quiet and size * size >= PROGRESS_MIN_PIXELS)

    def on_progress(done: int, total: int) -> None:
        prog.total = max(total, 1)
        prog.update(done)

    t0 = time.time()
    img = shade.render(frame, cam, jobs=jobs, tile=tile, progress=on_progress)
    secs = time.time() - t0

    # ---- outputs ------------------------------------------------------------------------------
    for p in (args.out, args.stats):
        try:
            p.parent.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            fail(PROG, f"cannot create the directory of {p}: {e.strerror or e}")
    write_png(args.out, img.rgb)
    o = img.out
    covered = len(img.frags)
    hits = int(o.hit.sum())
    iters = int(o.iterations.sum())
    hist = np.bincount(o.level[o.hit], minlength=tex.n_levels)[:tex.n_levels]
    hist_n = np.bincount(o.level_normal[o.hit], minlength=ntex.n_levels)[:ntex.n_levels]
    stats = {
        "pixels": size * size, "image": [size, size], "covered_pixels": covered, "hits": hits,
        "misses": int((~o.hit & ~o.invalid).sum()), "invalid": int(o.invalid.sum()),
        "iterations": iters,
        "iterations_per_pixel": round(iters / covered, 4) if covered else 0.0,
        "iterations_per_hit": round(float(o.iterations[o.hit].mean()), 4) if hits else 0.0,
        "max_iterations": int(o.iterations.max(initial=0)),
        "seconds": round(secs, 3), "seconds_total": None,
        "pixels_per_second": round(covered / secs, 1) if secs > 0 else None,
        "method": args.method, "engine": engine, "scene": scene_name,
        "angle": angle, "elevation_deg": cam.elevation_deg,
        "map": [mh, mw], "height_bits": args.bits, "depth_scale": depth,
        "texture": [tex.height, tex.width], "texture_levels": tex.n_levels,
        "normal_map": [ntex.height, ntex.width], "mip": not args.no_mip,
        "mip_levels": [int(c) for c in hist],
        "mip_level_rates": [round(100.0 * int(c) / hits, 2) if hits else 0.0 for c in hist],
        "normal_mip_levels": [int(c) for c in hist_n],
        "texel_reads": 8 * hits, "jobs": jobs, "tile": tile,
        "out": str(args.out),
    }
    stats["seconds_total"] = round(time.time() - t_start, 3)
    try:
        args.stats.write_text(json.dumps(stats, indent=1) + "\n")
    except OSError as e:
        fail(PROG, f"cannot write {args.stats}: {e.strerror or e}")
    if not args.quiet:
        print(f"{PROG}: {args.out} ({size}x{size}, {scene_name}/{args.angle}, "
              f"{args.method}/{engine}{'' if frame.mip else ', no MIP'}): {covered} covered, "
              f"{hits} hits, {stats['iterations_per_pixel']} iterations/pixel, "
              f"{secs:.2f} s render, {stats['seconds_total']:.2f} s total")
    return 0


def write_png(path: Path, rgb: np.ndarray) -> None:
    import OpenImageIO as oiio

    hh, ww = rgb.shape[:2]
    out = oiio.ImageOutput.create(str(path))
    if out is None:
        fail(PROG, f"cannot write {path}: {oiio.geterror()}".splitlines()[0])
    try:
        if not out.open(str(path), oiio.ImageSpec(ww, hh, 3, oiio.UINT8)):
            fail(PROG, f"cannot write {path}: {out.geterror()}".splitlines()[0])
        if not out.write_image(np.ascontiguousarray(rgb)):
            fail(PROG, f"cannot write {path}: {out.geterror()}".splitlines()[0])
    finally:
        out.close()


if __name__ == "__main__":
    sys.exit(main())
