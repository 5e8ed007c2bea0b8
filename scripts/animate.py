# SPDX-License-Identifier: Apache-2.0
"""make animate: a moving height field rendered end to end through the RTL, every frame checked.

Per frame k: the height field moves (``--motion ripples``: rings spreading over the scene's heights
from a point; ``dent``: a crater travelling across the map), level 0 is quantised (unorm8);
the hardware pyramid builder (``rtl/pyramid/pyr_build.sv``, ``tb/harness/pyr_run.py``) builds the
pyramid (frame 0 in full, later frames as a dirty-rectangle rebuild of the bounding box of the
texels that changed, on the memory holding the previous pyramid); the pyramid's bytes read back
must equal ``model.heightmap``'s pyramid of the new map, bit for bit; the pipeline RTL
(``tb/harness/dm_pipeline.py``) renders the frame reading the BUILT bytes as its height memory, and
every pixel (rgb, hit, invalid, iterations) must equal the model's f24 render of the new map.

The height cache: each frame's pipeline run starts from reset, so the cache holds nothing of the
previous frame's pyramid (it is invalidated whole between frames).

``--top system``: the frame loop through the system top ``rtl/top/pidm_top.sv``
(``tb/harness/pidm_system.py``, one harness run per frame on the memory the previous frame left):
the new level 0 is written over the height region, the pyramid is rebuilt by the builder inside
pidm_top through its registers (PYR, CTRL.pyr_start, the pyr_done interrupt: in full for frame 0,
then the dirty rectangle), and the frame is rendered (CTRL.start, frame_done); the build's end
invalidates the height cache.  The same checks and statistics (``render_cycles``: CTRL.start to the
interrupt).

Writes ``<out>/frame_NNN.png``, ``<out>/animation.gif`` (every frame, one GIF subimage each,
through OpenImageIO) and ``<out>/stats.json``: ``frames``, ``identical`` (every frame), and
``per_frame``: ``pyramid_cycles`` (the builder's clocks, 0 when nothing changed),
``pyramid_bound_cycles`` (``model.pyramid_bus``: the bus bound of a full rebuild of the map),
``render_cycles``, ``identical``, ``pyramid_identical``, ``pixels_differ``, ``dirty_rect``
([x0, y0, x1, y1] or null).  Exit status 0 when every frame is identical, 1 when one differs, 2 on a
usage error.
"""
from __future__ import annotations

import json
import sys
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402
import numpy.typing as npt  # noqa: E402

from model import camera, heightmap, pyramid_bus, scenes, shade, traverse  # noqa: E402
from model.cli import Parser, fail  # noqa: E402

PROG = "animate"
MOTIONS = ("ripples", "dent")
BITS = 8


def heights(base: npt.NDArray[np.float64], motion: str, k: int, frames: int
            ) -> npt.NDArray[np.float64]:
    """Frame ``k``'s heights in [0, 1]: ``base`` with the moving feature."""
    hh, ww = base.shape
    y, x = np.mgrid[0:hh, 0:ww].astype(np.float64)
    side = float(max(hh, ww))
    t = (k + 1) / frames
    if motion == "ripples":
        cx, cy = 0.35 * ww, 0.4 * hh
        r = np.hypot(x - cx, y - cy)
        front = 0.8 * side * t               # the leading ring's radius
        lam = max(side / 10.0, 2.0)          # wavelength
        wave = 0.18 * np.cos(2 * np.pi * (r - front) / lam) * np.exp(-r / (0.6 * side))
        h = base + np.where(r <= front, wave, 0.0)
    else:
        cx, cy = (0.15 + 0.7 * t) * ww, (0.25 + 0.5 * t) * hh
        d2 = ((x - cx) ** 2 + (y - cy) ** 2) / max(side / 16.0, 1.0) ** 2
        h = base * (1.0 - np.where(d2 < 4.0, 0.8 * np.exp(-d2), 0.0))   # cut off at 2 sigma
    return np.clip(h, 0.0, 1.0)


def write_png(path: Path, rgb: npt.NDArray[np.uint8]) -> None:
    """One RGB frame as PNG (OpenImageIO)."""
    import OpenImageIO as oiio

    out = oiio.ImageOutput.create(str(path))
    hh, ww = rgb.shape[:2]
    if out is None or not out.open(str(path), oiio.ImageSpec(ww, hh, 3, oiio.UINT8)):
        raise OSError(f"cannot write {path}: {oiio.geterror()}".splitlines()[0])
    out.write_image(np.ascontiguousarray(rgb))
    out.close()


def write_gif(path: Path, frames: list[npt.NDArray[np.uint8]], fps: int) -> None:
    """The frames as one animated GIF (one subimage per frame, OpenImageIO)."""
    import OpenImageIO as oiio

    out = oiio.ImageOutput.create(str(path))
    if out is None or not out.supports("multiimage"):
        raise OSError(f"OpenImageIO cannot write a multi-image {path.suffix}")
    specs = []
    for f in frames:
        s = oiio.ImageSpec(f.shape[1], f.shape[0], 3, oiio.UINT8)
        s.attribute("FramesPerSecond", oiio.TypeDesc("rational"), (fps, 1))
        specs.append(s)
    if not out.open(str(path), specs):
        raise OSError(f"cannot write {path}: {oiio.geterror()}".splitlines()[0])
    for i, f in enumerate(frames):
        if i and not out.open(str(path), specs[i], "AppendSubimage"):
            raise OSError(f"cannot append to {path}: {oiio.geterror()}".splitlines()[0])
        out.write_image(np.ascontiguousarray(f))
    out.close()


def run_system(a: Any, log: Any, frame0: shade.Frame, cam: camera.Camera,
               maps: list[npt.NDArray[np.uint16]]
               ) -> tuple[list[dict[str, Any]], list[npt.NDArray[np.uint8]]]:
    """The frame loop through pidm_top (``--top system``): per frame the new level 0 over the
    height memory, a build through the registers, the frame; (per-frame statistics, images)."""
    from tb.harness import dm_pipeline, pidm_system, pyr_run

    bound = pyramid_bus.full_rebuild(a.map_size, a.map_size, BITS,
                                     pidm_system.PARAMS["DATA_W"]).clocks
    per_frame: list[dict[str, Any]] = []
    rgbs: list[npt.NDArray[np.uint8]] = []
    memory: bytearray | None = None
    prev: npt.NDArray[np.uint16] | None = None
    for k, codes in enumerate(maps):
        pyr = heightmap.build(codes, BITS)
        want = pyr.memory_image()
        if memory is None:
            memory = bytearray(len(want))          # the pyramid's levels start as zeros
            rect: tuple[int, int, int, int] | None = (0, 0, pyr.width - 1, pyr.height - 1)
        else:
            rect = pyr_run.dirty_rect(prev, codes) if prev is not None else None
        lv0 = pyr.levels[0].astype("<u1").tobytes()
        memory[:len(lv0)] = lv0
        frame = replace(frame0, pyr=pyr)
        img, st, built = pidm_system.build_and_render(frame, cam, bytes(memory), rect,
                                                      build_pyramid=rect is not None)
        memory = bytearray(built)
        prev = codes
        pyr_ok = built == want
        ref = shade.render(frame, cam)
        bad = len(dm_pipeline.compare(img.out, ref.out))
        rgbs.append(img.rgb)
        write_png(a.out / f"frame_{k:03d}.png", img.rgb)
        per_frame.append({
            "pyramid_cycles": int(st["pyramid_cycles"]), "pyramid_bound_cycles": bound,
            "render_cycles": int(st["cycles"]), "identical": bool(pyr_ok and bad == 0),
            "pyramid_identical": bool(pyr_ok), "pixels_differ": bad,
            "dirty_rect": list(rect) if rect is not None else None})
        log(f"frame {k}: dirty {rect}, pyramid {st['pyramid_cycles']} clocks (full-rebuild "
            f"bound {bound}), pyramid {'identical' if pyr_ok else 'DIFFERS'}; render "
            f"{st['cycles']} clocks, {bad} pixels differ")
    return per_frame, rgbs


def run(a: Any, log: Any) -> dict[str, Any]:
    """The animation: returns the statistics (stats.json's content)."""
    from tb.harness import dm_pipeline, pyr_run

    sc = scenes.load_scene(a.scene, a.map_size)
    frame0, cam = dm_pipeline.scene_frame(a.scene, a.map_size, a.angle, a.image, a.method)
    maps = [heightmap.quantize(heights(np.asarray(sc.heights, dtype=np.float64), a.motion, k,
                                       a.frames), BITS) for k in range(a.frames)]
    if a.top == "system":
        log(f"system top RTL: {a.frames} maps of {a.map_size} x {a.map_size}")
        per_frame, rgbs = run_system(a, log, frame0, cam, maps)
        return finish(a, log, per_frame, rgbs, "invalidated by each pyramid build's end "
                                               "(pidm_top resets dm_pipeline after a build)")
    log(f"pyramid builder RTL: {a.frames} maps of {a.map_size} x {a.map_size}")
    t0 = time.monotonic()
    built = pyr_run.run_builds(np.stack(maps), BITS, a.out / "work")
    log(f"pyramid builder RTL: done ({time.monotonic() - t0:.1f} s)")
    bound = pyramid_bus.full_rebuild(a.map_size, a.map_size, BITS,
                                     pyr_run.PYR_PARAMS["AXI_DATA_W"]).clocks
    per_frame: list[dict[str, Any]] = []
    rgbs: list[npt.NDArray[np.uint8]] = []
    for k, codes in enumerate(maps):
        pyr = heightmap.build(codes, BITS)
        pyr_ok = built.images[k] == pyr.memory_image()
        frame = replace(frame0, pyr=pyr)
        fi = dm_pipeline.frame_image(frame)
        fi = fi._replace(cfg=replace(fi.cfg, height=(fi.cfg.height[0], built.images[k])))
        ref = shade.render(frame, cam)
        f, inp = shade.pixel_inputs(cam, None)
        order = camera.tile_order(f.row, f.col, cam.image_w, dm_pipeline.DEFAULT_TILE,
                                  dm_pipeline.DEFAULT_BLOCKS)
        px, st = dm_pipeline.run_pixels(fi, dm_pipeline.fragment_words(inp.subset(order)))
        out = shade.PixelOutputs(np.empty_like(ref.out.rgb), np.zeros(len(f), bool),
                                 np.zeros(len(f), bool), np.zeros(len(f), np.int64),
                                 ref.out.level, ref.out.level_normal)
        out.rgb[order], out.hit[order], out.invalid[order], out.iterations[order] = (
            px.rgb, px.hit, px.invalid, px.iterations)
        bad = len(dm_pipeline.compare(out, ref.out))
        rgb = np.empty(f.mask.shape + (3,), dtype=np.uint8)
        rgb[:] = shade.BACKGROUND
        rgb[f.row, f.col] = out.rgb
        rgbs.append(rgb)
        write_png(a.out / f"frame_{k:03d}.png", rgb)
        rect = built.rects[k]
        per_frame.append({
            "pyramid_cycles": built.clocks[k], "pyramid_bound_cycles": bound,
            "render_cycles": int(st["cycles"]), "identical": bool(pyr_ok and bad == 0),
            "pyramid_identical": bool(pyr_ok), "pixels_differ": bad,
            "dirty_rect": list(rect) if rect is not None else None})
        log(f"frame {k}: dirty {rect}, pyramid {built.clocks[k]} clocks (full-rebuild bound "
            f"{bound}), pyramid {'identical' if pyr_ok else 'DIFFERS'}; render "
            f"{st['cycles']} clocks, {bad} pixels differ")
    return finish(a, log, per_frame, rgbs, "invalidated whole between frames (each frame's "
                                           "pipeline run starts from reset)")


def finish(a: Any, log: Any, per_frame: list[dict[str, Any]],
           rgbs: list[npt.NDArray[np.uint8]], cache: str) -> dict[str, Any]:
    """The GIF and the statistics (stats.json's content)."""
    from tb.harness import pyr_run

    gif = a.out / "animation.gif"
    try:
        write_gif(gif, rgbs, a.fps)
        gif_name: str | None = gif.name
    except OSError as e:
        log(f"no animated image: {e}")
        gif_name = None
    return {"frames": a.frames, "identical": all(p["identical"] for p in per_frame),
            "scene": a.scene, "motion": a.motion, "map_size": a.map_size, "image": a.image,
            "angle": a.angle, "method": a.method, "bits": BITS,
            "bus_bits": pyr_run.PYR_PARAMS["AXI_DATA_W"], "animation": gif_name,
            "height_cache": cache,
            "per_frame": per_frame}


def main(argv: list[str] | None = None) -> int:
    """Parse the options, run the animation, write stats.json; 1 when a frame differs."""
    ap = Parser(prog=PROG, description="a moving height field through the pyramid builder and "
                                       "pipeline RTL, every frame compared with the model")
    ap.add_argument("--scene", default="rocks", choices=scenes.SCENES)
    ap.add_argument("--motion", default="ripples", choices=MOTIONS)
    ap.add_argument("--frames", type=int, default=8, help="frames (default 8)")
    ap.add_argument("--map-size", type=int, default=128, help="height map side (default 128)")
    ap.add_argument("--image", type=int, default=128, help="image side (default 128)")
    ap.add_argument("--angle", default="oblique", choices=tuple(camera.VIEWS))
    ap.add_argument("--method", default="park", choices=traverse.EXACT_METHODS)
    ap.add_argument("--fps", type=int, default=4, help="frames per second of the GIF")
    ap.add_argument("--top", default="pipeline", choices=("pipeline", "system"),
                    help="pipeline: the builder and dm_pipeline in two harnesses; system: "
                         "both inside pidm_top, driven through its registers")
    ap.add_argument("--out", type=Path, default=ROOT / "out" / "animate")
    a = ap.parse_args(argv)
    if not 1 <= a.frames <= 1000:
        fail(PROG, f"--frames must be in 1..1000, got {a.frames}")
    if not 2 <= a.map_size <= 1024:
        fail(PROG, f"--map-size must be in 2..1024, got {a.map_size}")
    if not 2 <= a.image <= 4096:
        fail(PROG, f"--image must be in 2..4096, got {a.image}")
    if not 1 <= a.fps <= 100:
        fail(PROG, f"--fps must be in 1..100, got {a.fps}")
    tty = sys.stderr.isatty()

    def log(msg: str) -> None:
        if tty:
            print(f"{PROG}: {msg}", file=sys.stderr, flush=True)

    try:
        a.out.mkdir(parents=True, exist_ok=True)
        stats = run(a, log)
    except (OSError, RuntimeError, ValueError) as e:
        fail(PROG, str(e).splitlines()[0] if str(e) else type(e).__name__)
    (a.out / "stats.json").write_text(json.dumps(stats, indent=2) + "\n")
    pf = stats["per_frame"]
    print(f"{PROG}: {stats['frames']} frames ({a.motion} on {a.scene}, map {a.map_size}, image "
          f"{a.image}): pyramid clocks {[p['pyramid_cycles'] for p in pf]} (full-rebuild bound "
          f"{pf[0]['pyramid_bound_cycles']}), render clocks {[p['render_cycles'] for p in pf]}; "
          f"{'every frame identical to the model' if stats['identical'] else 'FRAMES DIFFER'}; "
          f"{a.out}")
    return 0 if stats["identical"] else 1


if __name__ == "__main__":
    sys.exit(main())
