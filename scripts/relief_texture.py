#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Relief texture mapping by pre-warping (Oliveira 2000): frames per second of the serial, the
pipelined-parallel and the split-image multi-worker variants, like Fonseca et al. 2006 Table 2.

  relief_texture.py [--out DIR] [--samples saints,stones,four-shapes] [--size N] [--image N]
                    [--frames F] [--repeats R] [--workers W] [--backends thread,process]
                    [--elevation DEG] [--quiet]

Each sample is a procedural scene as a relief texture (colour + depth); ``four-shapes`` has its
floor texels marked invalid (background), like Fonseca's sample 3.  A camera orbits the quad in
``--frames`` views; every variant renders the same frames (pre-warp + texture mapping) and the
images are compared: all variants must be identical.  Frames/s is frames over wall time (best
and median of --repeats interleaved runs, workers started before the clock), SD the standard
deviation of the per-frame rate within the best run.  ``async`` is Fonseca's own count for
their parallel approach: redraws of the latest finished pre-warp per second while a worker
pre-warps.

Writes DIR/relief_texture.json, DIR/relief_texture.md (the table), and per sample the colour
texture, one pre-warped texture, the relief-texture frame and the same view ray-cast exactly
(the project's pyramidal traversal) for comparison.  Bad input: one line, exit 2.
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
from model import heightmap, scenes, traverse
from model import relief_texture as rtm
from model.camera import Camera
from model.cli import Parser, fail

PROG = "relief_texture.py"
DEFAULT_SAMPLES = ("saints", "stones", "four-shapes")
#: Samples whose lowest texels are background (Fonseca's sample 3 has 46.5 % invalid texels).
INVALID_FLOOR = ("four-shapes",)


def parse_int(what: str, text: str, lo: int, hi: int) -> int:
    try:
        v = int(text, 10)
    except ValueError:
        fail(PROG, f"{what} must be an integer, got {text!r}")
    if not lo <= v <= hi:
        fail(PROG, f"{what} must be in {lo}..{hi}, got {v}")
    return v


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


def to8(c: np.ndarray) -> np.ndarray:
    return np.rint(np.clip(c, 0.0, 1.0) * 255.0).astype(np.uint8)


def raycast_image(rt: rtm.ReliefTexture, cam: Camera) -> np.ndarray:
    """The same view traced exactly through the box height field (park, f64), nearest texel."""
    pyr = heightmap.build(1.0 - rt.depth, 8)
    cr = cam.rays()
    res = traverse.trace(pyr, cr.rays, "park", "f64")
    ok = res.hit.copy()
    i = np.floor(np.where(ok, res.v, 0.0)).astype(np.int64)
    j = np.floor(np.where(ok, res.u, 0.0)).astype(np.int64)
    ok &= rt.valid[i, j]
    img = np.zeros((cam.image_h, cam.image_w, 3), np.uint8)
    img[cr.row, cr.col] = to8(np.where(ok[:, None], rt.colour[i, j], rtm.BACKGROUND))
    return img


def step_times(rt: rtm.ReliefTexture, views: list[rtm.View]) -> dict[str, float]:
    """Median milliseconds per frame of each step of the serial frame (one thread)."""
    t: dict[str, list[float]] = {"prewarp_rows": [], "prewarp_columns": [], "texture_map": []}
    for v in views:
        t0 = time.perf_counter()
        mid = rtm.prewarp_rows(rt, v.pw)
        t1 = time.perf_counter()
        pw = rtm.prewarp_columns(mid, v.pw)
        t2 = time.perf_counter()
        rtm.texture_map(pw, v)
        t3 = time.perf_counter()
        for k, d in zip(t, (t1 - t0, t2 - t1, t3 - t2)):
            t[k].append(1000.0 * d)
    return {k: float(np.median(x)) for k, x in t.items()}


def compare(a: np.ndarray, b: np.ndarray, cam: Camera) -> dict[str, float]:
    m = cam.fragments().mask
    d = np.abs(a[m].astype(np.int64) - b[m].astype(np.int64)).max(axis=1)
    e = a[m].astype(np.float64) - b[m].astype(np.float64)
    return {"identical_pixels": float(np.mean(d == 0)), "within_8_levels": float(np.mean(d <= 8)),
            "mse": float(np.mean(e * e))}


def main(argv: list[str] | None = None) -> int:
    t_start = time.time()
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=Path("out/relief_texture"))
    ap.add_argument("--samples", default=",".join(DEFAULT_SAMPLES),
                    help=f"scenes ({', '.join(scenes.SCENES)}), comma-separated")
    ap.add_argument("--size", default="256", help="relief texture side in texels (default 256)")
    ap.add_argument("--image", default="256", help="frame side in pixels (default 256)")
    ap.add_argument("--frames", default="60", help="frames per run (default 60)")
    ap.add_argument("--repeats", default="5", help="runs per variant (default 5)")
    ap.add_argument("--workers", default="2", help="split-image workers (default 2)")
    ap.add_argument("--backends", default="thread,process", help="thread, process or both")
    ap.add_argument("--elevation", default="45", help="camera elevation in degrees (default 45)")
    ap.add_argument("--quiet", action="store_true")
    a = ap.parse_args(argv)

    size = parse_int("--size", a.size, 2, 4096)
    image = parse_int("--image", a.image, 8, 4096)
    frames = parse_int("--frames", a.frames, 1, 100000)
    repeats = parse_int("--repeats", a.repeats, 1, 1000)
    workers = parse_int("--workers", a.workers, 1, 64)
    try:
        elev = float(a.elevation)
    except ValueError:
        fail(PROG, f"--elevation must be a number, got {a.elevation!r}")
    if not 0.0 < elev <= 90.0:
        fail(PROG, f"--elevation must be in (0, 90] degrees, got {a.elevation!r}")
    samples = [s.strip() for s in a.samples.split(",") if s.strip()]
    if not samples:
        fail(PROG, "--samples needs at least one scene")
    for s in samples:
        if s not in scenes.SCENES:
            fail(PROG, f"unknown sample {s!r} (scenes: {', '.join(scenes.SCENES)})")
    backends = [b.strip() for b in a.backends.split(",") if b.strip()]
    if not backends or any(b not in rtm.BACKENDS for b in backends):
        fail(PROG, f"--backends is a list of {', '.join(rtm.BACKENDS)}, got {a.backends!r}")
    try:
        a.out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        fail(PROG, f"cannot create {a.out}: {e.strerror}")

    def say(msg: str) -> None:
        if not a.quiet:
            print(msg, file=sys.stderr, flush=True)

    configs: list[tuple[str, str, int]] = [("serial", "-", 1)]
    for b in backends:
        configs += [("pipelined", b, 1), ("split", b, workers)]
    load0 = os.getloadavg()
    doc: dict[str, Any] = {
        "settings": {"size": size, "image": image, "frames": frames, "repeats": repeats,
                     "workers": workers, "backends": backends, "elevation_deg": elev,
                     "cpus": rtm.cpu_count(), "load_average_before": list(load0)},
        "samples": {}}
    for si, name in enumerate(samples):
        rt = rtm.scene_relief(name, size, invalid_floor=name in INVALID_FLOOR)
        views = rtm.orbit(rt, frames, image, elevation=elev)
        inv = int((~rt.valid).sum())
        say(f"{PROG}: sample {si + 1} {name}: {size}x{size}, {inv} invalid texels, "
            f"{frames} frames x {repeats} runs x {len(configs) + len(backends)} variants")
        runs: dict[str, list[rtm.FrameRun]] = {}
        images: list[rtm.FrameRun] = []
        for rep in range(repeats):          # interleaved, so load changes hit every variant
            for var, be, w in configs:
                key = var if var == "serial" else f"{var}-{be}"
                r = rtm.render_frames(rt, views, var, backend=be if be != "-" else "thread",
                                      workers=w, keep=rep == 0)
                runs.setdefault(key, []).append(r)
                if rep == 0:
                    images.append(r)
                say(f"  run {rep + 1}/{repeats} {key:18s} {r.fps:7.1f} frames/s")
        identical = rtm.frames_identical(images)
        asyncs = {b: rtm.render_async(rt, views, b) for b in backends}
        res: dict[str, Any] = {"resolution": [size, size], "invalid_texels": inv,
                               "invalid_share": inv / float(size * size),
                               "identical_images": identical, "variants": {}}
        for key, rs in runs.items():
            fps = np.array([r.fps for r in rs])
            med = rs[int(np.argsort(fps)[len(fps) // 2])]
            best = rs[int(np.argmax(fps))]
            res["variants"][key] = {"fps_best": float(best.fps), "fps_median": float(med.fps),
                                    "fps_sd": best.fps_sd(), "fps_runs": fps.tolist(),
                                    "workers": rs[0].workers}
        for b, ar in asyncs.items():
            res["variants"][f"async-{b}"] = {"draws_per_s": ar.draws_per_s,
                                             "warps_per_s": ar.warps_per_s, "draws": ar.draws,
                                             "warps": ar.warps, "seconds": ar.seconds}
        steps = step_times(rt, views)
        res["serial_step_ms"] = steps
        cam = views[0].cam
        frame = images[0].images[0]
        ray = raycast_image(rt, cam)
        res["vs_raycast"] = compare(frame, ray, cam)
        doc["samples"][name] = res
        write_png(a.out / f"{name}_texture.png", to8(rt.colour))
        pw0 = rtm.prewarp(rt, views[0].pw)
        write_png(a.out / f"{name}_prewarped.png",
                  to8(np.where(pw0.valid[..., None], pw0.colour, rtm.BACKGROUND)))
        write_png(a.out / f"{name}_frame0.png", frame)
        write_png(a.out / f"{name}_raycast.png", ray)
        say(f"  identical images across variants: {identical}; vs ray cast: "
            f"{100 * res['vs_raycast']['within_8_levels']:.1f}% of pixels within 8 levels")
        if not identical:
            print(f"{PROG}: variants differ on {name}", file=sys.stderr)
    doc["settings"]["load_average_after"] = list(os.getloadavg())
    doc["seconds"] = time.time() - t_start
    (a.out / "relief_texture.json").write_text(json.dumps(doc, indent=1) + "\n")
    md = table(doc)
    (a.out / "relief_texture.md").write_text(md)
    if not a.quiet:
        print(md, end="")
    return 0 if all(s["identical_images"] for s in doc["samples"].values()) else 1


def table(doc: dict[str, Any]) -> str:
    """Frames/s per sample and variant, as Fonseca's Table 2 (best and median run, SD within
    the best)."""
    names = list(doc["samples"])
    keys = [k for k in doc["samples"][names[0]]["variants"]]
    st = doc["settings"]
    lines = [f"Relief texture mapping, {st['size']}x{st['size']} textures, {st['image']}x"
             f"{st['image']} frames, {st['frames']} frames per run; FPS: best (median) of "
             f"{st['repeats']} runs, SD within the best run; {st['cpus']} CPUs, load average "
             f"{st['load_average_before'][0]:.1f} before, {st['load_average_after'][0]:.1f} after",
             "", "| variant | " + " | ".join(f"{n} FPS | SD" for n in names) + " |",
             "|---|" + "---|---|" * len(names)]
    for k in keys:
        cells = []
        for n in names:
            v = doc["samples"][n]["variants"][k]
            if "fps_best" in v:
                cells += [f"{v['fps_best']:.1f} ({v['fps_median']:.1f})", f"{v['fps_sd']:.1f}"]
            else:
                cells += [f"{v['draws_per_s']:.1f} ({v['warps_per_s']:.1f} pre-warps/s)", ""]
        lines.append(f"| {k} | " + " | ".join(cells) + " |")
    lines.append("")
    lines.append("invalid texels: " + ", ".join(
        f"{n} {100 * doc['samples'][n]['invalid_share']:.1f}%" for n in names)
        + "; identical images across variants: " + ", ".join(
        f"{n} {doc['samples'][n]['identical_images']}" for n in names))
    steps = [(n, d["serial_step_ms"]) for n, d in doc["samples"].items()]
    lines.append("serial frame, median ms: " + ", ".join(
        f"{n} {t['prewarp_rows']:.1f} + {t['prewarp_columns']:.1f} pre-warp + "
        f"{t['texture_map']:.1f} texture mapping" for n, t in steps))
    lines.append("relief texture vs exact ray cast (frame 0), pixels within 8 levels: " + ", ".join(
        f"{n} {100 * doc['samples'][n]['vs_raycast']['within_8_levels']:.1f}%" for n in names))
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
