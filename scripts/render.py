#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Render a displacement-mapped quad through the golden model (trace, MIP-mapped texture, shading)
or through the pipeline RTL (Verilator) and the model, pixel for pixel compared.

  render.py [--scene NAME | --heightmap FILE [--texture FILE] [--normal-map FILE]]
            [--angle front|oblique|grazing|DEGREES] [--method NAME] [--engine f64|f24|rtl]
            [--size N] [--map-size N] [--out PNG] [--stats JSON] [--jobs J] [--no-mip]
            [--model-out PNG] [--latency L|MIN:MAX] [--rtl-tile N] [--rtl-blocks rows|morton]
            [--checked] [--clock-mhz F] [--top pipeline|system]

Writes the image (PNG through OpenImageIO) and a JSON of statistics.  Without --texture a user
height map is coloured by a height ramp (``height_ramp``); without --normal-map its normals come
from the heights (``model.scenes.normal_map``).  Bad input: one line naming the problem, exit 2.

``--engine rtl`` (what ``make render`` runs): the frame goes through ``rtl/pipe/dm_pipeline.sv``
in the Verilator harness (``tb.harness.dm_pipeline``; built once into build/harness/pipeline/, about a
minute) and through the model's f24 engine, the bit-accurate model of that datapath.  --out gets
the RTL's image (default out/render.png), --model-out the model's (default out/render_model.png),
--stats (default out/render_stats.json) the RTL's statistics with ``identical``: every covered
pixel's colour, hit, invalid flag and iteration count equal between RTL and model.  There
``pixels`` counts the pixels through the pipeline (one fragment per covered pixel; the image's
size is ``image_pixels``), ``cycles`` the clocks from the first fragment in to the last pixel out
(one pipeline, AXI read latency --latency on both memory ports), ``mem_bytes`` the bytes read on
both ports; Mpixels/s are given at --clock-mhz, by default at the project's routed clock
(``clock_mhz``, with ``clock_source``): the top's place-and-route fmax of a local
out/synth/report.json when there is one, else the committed docs/results/synth-ecp5.json (with no
routed result at all, the paper's 84 MHz, labelled as assumed); ``paper_clock_mhz`` and
``mpixels_per_second_at_paper_clock`` give the figure at the paper's 84 MHz beside it.  The
progress line (rewritten in place with ``\r``) is shown only when stderr is a terminal.
Exit status 1 when the RTL and the model differ (the count and the first pixels are printed).
Approximate methods have no RTL: --engine rtl with one is a user error (exit 2); render them on
the model with --engine f64.  ``--top system`` runs the frame through the system top
``rtl/top/pidm_top.sv`` instead (``tb.harness.pidm_system``: the harness plays the CPU, writing
the registers, and the memory behind its four AXI ports; the image is read back from the
framebuffer and the status buffer; ``cycles`` then counts from the CTRL.start write to the
interrupt).
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
from model import camera, heightmap, scenes, shade, texture, traverse
from model.cli import Parser, Progress, fail

PROG = "render.py"
MAX_SIZE = 8192
MAX_MAP = 8192
DEFAULT_JOBS = max(1, min(os.cpu_count() or 1, 8))
PROGRESS_MIN_PIXELS = 1 << 17
#: The approximate methods of CONVENTIONS (model.approx, imported only when one is asked for).
APPROX_NAMES = ("parallax", "parallax-iter", "binary", "relief", "pom", "distance")
#: Mismatching pixels listed when the RTL and the model differ.
SHOW_MISMATCHES = 5

#: Stops of the height ramp of user height maps without a texture: (height, R, G, B).
RAMP = np.array([(0.00, 0.20, 0.16, 0.12), (0.30, 0.42, 0.36, 0.24), (0.55, 0.46, 0.52, 0.30),
                 (0.80, 0.62, 0.60, 0.56), (1.00, 0.95, 0.95, 0.97)])


def progress_wanted(quiet: bool) -> bool:
    """A progress line only when not --quiet and stderr is a terminal (a ``\r``-rewritten line
    in a log file or a pipe is noise)."""
    return not quiet and sys.stderr.isatty()


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


def parse_latency(text: str) -> tuple[int, int]:
    """--latency: L or MIN:MAX clocks, 1 <= MIN <= MAX <= 100000."""
    parts = text.split(":")
    try:
        lo, hi = (int(parts[0]), int(parts[-1])) if len(parts) <= 2 else (0, -1)
    except ValueError:
        lo, hi = 0, -1
    if not 1 <= lo <= hi <= 100000:
        fail(PROG, f"--latency wants L or MIN:MAX clocks with 1 <= MIN <= MAX <= 100000, "
                   f"got {text!r}")
    return lo, hi


def rel(p: Path) -> str:
    """``p`` relative to the repository when it is inside it."""
    try:
        return str(p.resolve().relative_to(ROOT))
    except ValueError:
        return str(p)


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
    ap.add_argument("--engine", help="f64 | f24 | rtl (default f24; f64 for approximate "
                    "methods); rtl: the pipeline RTL in Verilator and the f24 model, compared")
    ap.add_argument("--size", default="256", help="image N x N pixels (default 256)")
    ap.add_argument("--map-size", help="map N x N texels of a procedural scene (default 256)")
    ap.add_argument("--bits", type=int, default=8, choices=(8, 16), help="height storage (unorm)")
    ap.add_argument("--out", type=Path, help="output PNG (default out/render_model.png; "
                    "with --engine rtl the RTL's image, default out/render.png)")
    ap.add_argument("--model-out", type=Path, help="with --engine rtl: the model's PNG "
                    "(default out/render_model.png)")
    ap.add_argument("--stats", type=Path, help="output statistics JSON (default "
                    "out/render_model_stats.json; with --engine rtl out/render_stats.json)")
    ap.add_argument("--jobs", default=str(DEFAULT_JOBS), help="processes, by image tiles "
                    f"(default {DEFAULT_JOBS}: the CPUs); the image does not depend on it")
    ap.add_argument("--tile", default="256", help="tile size in pixels (default 256)")
    ap.add_argument("--no-mip", action="store_true", help="always texture level 0 (MIP off)")
    ap.add_argument("--latency", default="20", help="--engine rtl: AXI read latency of both "
                    "memory ports, L or MIN:MAX clocks drawn per burst (default 20)")
    ap.add_argument("--rtl-tile", default="16", help="--engine rtl: fragments in N x N pixel "
                    "blocks, as a tiled rasteriser emits them (1: raster order; default 16)")
    ap.add_argument("--top", default="pipeline", choices=("pipeline", "system"),
                    help="--engine rtl: the pipeline top (default) or the system top pidm_top")
    ap.add_argument("--rtl-blocks", default="rows", choices=("rows", "morton"),
                    help="--engine rtl: order of the blocks: row by row (default) or along a "
                    "Z-order curve")
    ap.add_argument("--seed", default="0", help="--engine rtl: seed of random latencies")
    ap.add_argument("--rings", default="1", help="--engine rtl: traverse rings of the pipeline "
                    "(dm_pipeline N_RINGS: 1 or 2; default 1)")
    ap.add_argument("--checked", action="store_true", help="--engine rtl: the harness with the "
                    "RTL's assertions on (slower; RTL_ENGINE_CHECKED=1 does the same)")
    ap.add_argument("--clock-mhz", help="--engine rtl: quote Mpixels/s at this clock (default: "
                    "the routed fmax of out/synth/report.json, else of "
                    "docs/results/synth-ecp5.json)")
    ap.add_argument("--quiet", action="store_true", help="no progress or summary output")
    args = ap.parse_args(argv)

    # ---- arguments ----------------------------------------------------------------------------
    approx = {} if args.method in traverse.METHODS else shade.approx_methods()
    if args.method not in traverse.METHODS and args.method not in approx:
        fail(PROG, f"unknown method {args.method!r} (exact: {', '.join(traverse.EXACT_METHODS)}; "
                   f"approximate: {', '.join(approx) or 'none'})")
    engine = args.engine or ("f64" if args.method in approx else "f24")
    if engine not in ("f64", "f24", "rtl"):
        fail(PROG, f"unknown engine {engine!r} (f64, f24, rtl)")
    if args.method in approx and engine == "rtl":
        fail(PROG, f"approximate method {args.method!r} has no pipeline RTL (the RTL traverses "
                   f"with the exact methods only); render it on the model: --engine f64")
    if args.method in approx and engine != "f64":
        fail(PROG, f"approximate method {args.method!r} runs on the f64 engine only")
    rtl = engine == "rtl"
    size = positive_int("--size", args.size, MAX_SIZE)
    jobs = positive_int("--jobs", args.jobs, 256)
    tile = positive_int("--tile", args.tile, MAX_SIZE)
    rtl_tile = positive_int("--rtl-tile", args.rtl_tile, MAX_SIZE)
    latency = parse_latency(args.latency)
    try:
        seed = int(args.seed, 10)
        if seed < 0:
            raise ValueError
    except ValueError:
        fail(PROG, f"--seed must be a non-negative integer, got {args.seed!r}")
    try:
        rings = int(args.rings, 10)
    except ValueError:
        rings = 0
    if rings not in (1, 2):
        fail(PROG, f"--rings must be 1 or 2, got {args.rings!r}")
    if args.top == "system" and rings != 1:
        fail(PROG, "--rings goes with --top pipeline (the system harness has one ring)")
    clock: tuple[float, str] | None = None
    if args.clock_mhz is not None:
        try:
            mhz = float(args.clock_mhz)
        except ValueError:
            mhz = float("nan")
        if not 0 < mhz < 100000:
            fail(PROG, f"--clock-mhz must be a clock in MHz, got {args.clock_mhz!r}")
        clock = (mhz, "given with --clock-mhz")
    if not rtl:
        for opt, given in (("--model-out", args.model_out is not None),
                           ("--checked", args.checked), ("--clock-mhz", args.clock_mhz),
                           ("--top", args.top != "pipeline"), ("--rings", rings != 1)):
            if given:
                fail(PROG, f"{opt} goes with --engine rtl")
    angle = parse_angle(args.angle)
    if args.heightmap is None and (args.texture is not None or args.normal_map is not None):
        fail(PROG, "--texture and --normal-map go with --heightmap (a scene has its own)")
    if args.heightmap is not None and args.map_size is not None:
        fail(PROG, "--map-size applies to --scene only (a height map file has its own size)")
    out_png = args.out or Path("out/render.png" if rtl else "out/render_model.png")
    model_png = args.model_out or Path("out/render_model.png")
    stats_path = args.stats or Path("out/render_stats.json" if rtl else
                                    "out/render_model_stats.json")
    outputs = [("--out", out_png), ("--stats", stats_path)]
    if rtl:
        outputs.append(("--model-out", model_png))
        if model_png.resolve() == out_png.resolve():
            fail(PROG, f"--out and --model-out are the same file: {out_png}")
    for what, p in outputs:
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
                        method=args.method, engine="f24" if rtl else engine,
                        mip=not args.no_mip)
    build_secs = 0.0
    if rtl:
        from tb.harness import dm_pipeline
        try:
            dm_pipeline.check_limits(frame)
        except dm_pipeline.RtlLimitError as e:
            fail(PROG, f"the pipeline RTL cannot render this: {e}")
        built = build_harness(args.checked, args.quiet, rings, args.top)
        if built is None:
            return 1
        build_secs = built

    # ---- render -------------------------------------------------------------------------------
    model_engine = frame.engine
    prog = Progress(f"render {args.method}/{model_engine} {size}x{size}", 1,
                    enabled=progress_wanted(args.quiet) and size * size >= PROGRESS_MIN_PIXELS)

    def on_progress(done: int, total: int) -> None:
        prog.total = max(total, 1)
        prog.update(done)

    t0 = time.time()
    img = shade.render(frame, cam, jobs=jobs, tile=tile, progress=on_progress)
    secs = time.time() - t0

    # ---- outputs ------------------------------------------------------------------------------
    for _, p in outputs:
        try:
            p.parent.mkdir(parents=True, exist_ok=True)
        except OSError as e:
            fail(PROG, f"cannot create the directory of {p}: {e.strerror or e}")
    write_png(model_png if rtl else out_png, img.rgb)
    o = img.out
    covered = len(img.frags)
    hits = int(o.hit.sum())
    iters = int(o.iterations.sum())
    hist = np.bincount(o.level[o.hit], minlength=tex.n_levels)[:tex.n_levels]
    hist_n = np.bincount(o.level_normal[o.hit], minlength=ntex.n_levels)[:ntex.n_levels]
    stats: dict[str, Any] = {
        "pixels": size * size, "image": [size, size], "covered_pixels": covered, "hits": hits,
        "misses": int((~o.hit & ~o.invalid).sum()), "invalid": int(o.invalid.sum()),
        "iterations": iters,
        "iterations_per_pixel": round(iters / covered, 4) if covered else 0.0,
        "iterations_per_hit": round(float(o.iterations[o.hit].mean()), 4) if hits else 0.0,
        "max_iterations": int(o.iterations.max(initial=0)),
        "seconds": round(secs, 3), "seconds_total": None,
        "pixels_per_second": round(covered / secs, 1) if secs > 0 else None,
        "method": args.method, "engine": model_engine, "scene": scene_name,
        "angle": angle, "elevation_deg": cam.elevation_deg,
        "map": [mh, mw], "height_bits": args.bits, "depth_scale": depth,
        "texture": [tex.height, tex.width], "texture_levels": tex.n_levels,
        "normal_map": [ntex.height, ntex.width], "mip": not args.no_mip,
        "mip_levels": [int(c) for c in hist],
        "mip_level_rates": [round(100.0 * int(c) / hits, 2) if hits else 0.0 for c in hist],
        "normal_mip_levels": [int(c) for c in hist_n],
        "texel_reads": 8 * hits, "jobs": jobs, "tile": tile,
        "out": str(model_png if rtl else out_png),
    }
    if not rtl:
        stats["seconds_total"] = round(time.time() - t_start, 3)
        write_stats(stats_path, stats)
        if not args.quiet:
            print(f"{PROG}: {out_png} ({size}x{size}, {scene_name}/{args.angle}, "
                  f"{args.method}/{engine}{'' if frame.mip else ', no MIP'}): {covered} covered, "
                  f"{hits} hits, {stats['iterations_per_pixel']} iterations/pixel, "
                  f"{secs:.2f} s render, {stats['seconds_total']:.2f} s total")
        return 0
    if not args.quiet:
        print(f"{PROG}: model (f24): {model_png}: {covered} covered pixels, {hits} hits, "
              f"{stats['iterations_per_pixel']} iterations/pixel, {secs:.2f} s", flush=True)
    return render_rtl(args, frame, cam, img, stats, out_png, stats_path, latency=latency,
                      rtl_tile=rtl_tile, seed=seed, clock=clock, rings=rings,
                      build_secs=build_secs, t_start=t_start)


def checked_variant(checked: bool) -> bool:
    return checked or os.environ.get("RTL_ENGINE_CHECKED", "") == "1"


def build_harness(checked: bool, quiet: bool, rings: int = 1, top: str = "pipeline"
                  ) -> float | None:
    """Build the pipeline harness (``rings`` traverse rings), or the system harness, if it is
    not current; the seconds it took (None: it failed, the reason is printed)."""
    from tb.harness import dm_pipeline, pidm_system
    from tb.harness.build import RtlEngineError

    variant = dm_pipeline.default_variant(checked_variant(checked))
    try:
        if top == "system":
            if pidm_system.is_built(variant):
                return 0.0
            t0 = time.time()
            pidm_system.build(variant, quiet=quiet)
            return time.time() - t0
        if dm_pipeline.is_built(variant, rings):
            return 0.0
        t0 = time.time()
        dm_pipeline.build(variant, quiet=quiet, rings=rings)
        return time.time() - t0
    except RtlEngineError as e:
        sys.stderr.write(f"{PROG}: error: the RTL harness did not build: "
                         f"{str(e).splitlines()[0]}\n")
        return None


def render_rtl(args: Any, frame: shade.Frame, cam: camera.Camera, ref: shade.Image,
               model_stats: dict[str, Any], out_png: Path, stats_path: Path, *,
               latency: tuple[int, int], rtl_tile: int, seed: int,
               clock: tuple[float, str] | None, build_secs: float, t_start: float,
               rings: int = 1) -> int:
    """--engine rtl: the frame through the pipeline RTL, compared with the model's image."""
    from tb.harness import dm_pipeline, pidm_system
    from tb.harness.build import RtlEngineError

    checked = checked_variant(args.checked)
    rtl_mod: Any = pidm_system if args.top == "system" else dm_pipeline
    n = len(ref.frags)
    prog = Progress(f"render {frame.method}/rtl {cam.image_w}x{cam.image_h} (pixels)", n,
                    enabled=progress_wanted(args.quiet))
    try:
        img, st = rtl_mod.render_rtl(frame, cam, frags=ref.frags, tile=rtl_tile,
                                         blocks=args.rtl_blocks,
                                         latency=latency, seed=seed, checked=checked,
                                         rings=rings, progress=lambda d, t: prog.update(d))
    except RtlEngineError as e:
        sys.stderr.write(f"{PROG}: error: the RTL run failed: {' | '.join(str(e).splitlines())}\n")
        return 1
    write_png(out_png, img.rgb)
    bad = dm_pipeline.compare(img.out, ref.out)
    mhz, clock_src = clock if clock is not None else dm_pipeline.pipeline_clock(rings)
    cpp = st["cycles_per_pixel"]
    stats: dict[str, Any] = {
        "pixels": st["pixels"], "cycles": st["cycles"], "iterations": st["iterations"],
        "identical": len(bad) == 0, "mismatches": int(len(bad)),
        "height_cache_hit_rate": st["height_cache_hit_rate"],
        "texture_cache_hit_rate": st["texture_cache_hit_rate"],
        "texture_quad_hit_rate": st["texture_quad_hit_rate"],
        "mem_bytes": st["mem_bytes"], "height_mem_bytes": st["height_mem_bytes"],
        "texture_mem_bytes": st["texture_mem_bytes"],
        "cycles_per_pixel": round(cpp, 4),
        "iterations_per_pixel": round(st["iterations_per_pixel"], 4),
        "cycles_per_iteration": round(st["cycles_per_iteration"], 4),
        "bytes_per_pixel": round(st["bytes_per_pixel"], 4),
        "clock_mhz": mhz, "clock_source": clock_src,
        "mpixels_per_second": round(mhz / cpp, 3) if cpp > 0 else None,
        "paper_clock_mhz": dm_pipeline.PAPER_MHZ,
        "mpixels_per_second_at_paper_clock": (round(dm_pipeline.PAPER_MHZ / cpp, 3) if cpp > 0
                                              else None),
        "harness_wall_seconds": st["harness_wall_seconds"],
        "harness_clocks_per_second": st["clocks_per_second"],
        "build_seconds": round(build_secs, 1),
        "image": [cam.image_h, cam.image_w], "image_pixels": cam.image_w * cam.image_h,
        "covered_pixels": len(ref.frags), "hits": st["hits"], "invalid": st["invalid"],
        "errors": st["errors"], "axi_latency": list(latency), "fragment_tile": rtl_tile,
        "fragment_blocks": args.rtl_blocks, "top": args.top,
        "harness_variant": st["harness_variant"], "rings": rings,
        "method": frame.method, "engine": "rtl", "scene": model_stats["scene"],
        "angle": model_stats["angle"], "elevation_deg": model_stats["elevation_deg"],
        "map": model_stats["map"], "height_bits": model_stats["height_bits"],
        "depth_scale": model_stats["depth_scale"], "mip": model_stats["mip"],
        "out": str(out_png), "model_out": model_stats["out"],
        "rtl": st, "model": model_stats, "seconds_total": None,
    }
    stats["seconds_total"] = round(time.time() - t_start, 3)
    write_stats(stats_path, stats)
    if not args.quiet:
        print(f"{PROG}: RTL ({st['harness_variant']} harness): {out_png}: {st['pixels']} pixels, "
              f"{st['cycles']} clocks = {cpp:.2f} clocks/pixel, {st['iterations_per_pixel']:.2f} "
              f"iterations/pixel ({st['cycles_per_iteration']:.3f} clocks/iteration)")
        print(f"{PROG}: RTL caches: height {st['height_cache_hit_rate']:.2%} of lookups hit, "
              f"texture {st['texture_cache_hit_rate']:.2%} of texel reads hit "
              f"({st['texture_quad_hit_rate']:.2%} of 2x2 quads had all four); memory "
              f"{st['mem_bytes']} bytes = {st['bytes_per_pixel']:.2f} bytes/pixel "
              f"(heights {st['height_mem_bytes']}, textures {st['texture_mem_bytes']}; AXI "
              f"latency {latency[0] if latency[0] == latency[1] else latency} clocks)")
        print(f"{PROG}: {stats['mpixels_per_second']} Mpixels/s per pipeline at {mhz:g} MHz "
              f"({clock_src}); {stats['mpixels_per_second_at_paper_clock']} at the paper's "
              f"{dm_pipeline.PAPER_MHZ:g} MHz (Park et al.'s clock); harness "
              f"{st['harness_wall_seconds']:.2f} s wall "
              f"({st['clocks_per_second'] / 1e6:.3f} M clocks/s)"
              + (f", built in {build_secs:.0f} s" if build_secs else ""))
    if len(bad):
        f = ref.frags
        shown = "; ".join(
            f"(row {f.row[i]}, col {f.col[i]}): rtl rgb {tuple(int(c) for c in img.out.rgb[i])} "
            f"hit {int(img.out.hit[i])} inv {int(img.out.invalid[i])} it "
            f"{img.out.iterations[i]}, model rgb {tuple(int(c) for c in ref.out.rgb[i])} hit "
            f"{int(ref.out.hit[i])} inv {int(ref.out.invalid[i])} it {ref.out.iterations[i]}"
            for i in bad[:SHOW_MISMATCHES])
        sys.stderr.write(f"{PROG}: error: the RTL and the model differ in {len(bad)} of {n} "
                         f"pixels; first: {shown}\n")
        return 1
    if not args.quiet:
        print(f"{PROG}: identical: all {n} RTL pixels equal the model's f24 pixels bit for bit "
              f"(colour, hit, invalid, iterations); {stats_path}, {stats['seconds_total']:.1f} s "
              "total")
    return 0


def write_stats(path: Path, stats: dict[str, Any]) -> None:
    try:
        path.write_text(json.dumps(stats, indent=1) + "\n")
    except OSError as e:
        fail(PROG, f"cannot write {path}: {e.strerror or e}")


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
