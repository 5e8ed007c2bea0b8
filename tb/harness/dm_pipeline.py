# SPDX-License-Identifier: Apache-2.0
"""The whole pipeline RTL as a renderer: frames through ``rtl/pipe/dm_pipeline.sv`` (fragments ->
view unit -> traverse unit + height cache -> MIP level -> texture cache -> filter -> shading ->
pixels) in a Verilator C++ harness (``tb/harness/pipeline_harness.cpp``) with two AXI4 memory
models (heights, textures).

    img, stats = render_rtl(frame, cam)            # like model.shade.render(frame, cam)

``img`` is a :class:`model.shade.Image` laid out like the model's (rgb (H, W, 3) unorm8 with the
background where the quad does not cover the image; per covered pixel, in the fragments'
row-major order, rgb, hit, invalid and iterations from the RTL; the RTL does not output MIP
levels, so ``level`` and ``level_normal`` are -1).  ``stats`` holds the harness's statistics
(cycles from the first fragment in to the last pixel out, pixels, iterations, height- and
texture-cache hits, bytes read per port, simulated clocks per second, ...) plus per-pixel ratios.
Every RTL pixel must equal :func:`model.shade.render_pixels` with the ``f24`` engine
(:func:`compare` lists the differences).

Fragments enter in the order a tiled rasteriser emits them (``tile`` x ``tile`` pixel blocks,
:func:`model.camera.tile_order`; ``tile=1`` is raster order); the pixel id is the fragment's index
in that stream, and the harness writes the pixels back in stream order whatever order they left
the unit in (it checks that every id comes back exactly once).

Memory: the pyramid at :data:`tb.harness.pipeline_words.HEIGHT_BASE` on the height port; the colour
texture at :data:`tb.harness.pipeline_words.COLOUR_BASE` on the texture port and the normal map after it
on the next 4 KiB boundary.  :func:`check_limits` gives a one-line reason for a frame the RTL's
configuration ports cannot hold (map or texture sizes, iteration cap, address space).

The harness is built on demand by :func:`tb.harness.build.build` with the :data:`PIPELINE` spec into
``build/harness/pipeline/<variant>/``: ``fast`` (SVA assertions compiled out), ``checked``
(``--assert``; used when ``checked=True`` or ``RTL_ENGINE_CHECKED=1``, which the test suite sets)
or ``waves`` (FST tracing and assertions).  File formats: ``tb/harness/pipeline_harness.h``.
"""
from __future__ import annotations

import functools
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Callable, NamedTuple, Sequence

import numpy as np
import numpy.typing as npt

from model import f24, shade, traverse
from model.camera import Camera, Fragments, tile_order

from . import build as _build
from . import pipeline_words, traverse_words
from .build import (BUILD, COMMON_SOURCES, HARNESS_DIR, ROOT, VARIANTS, HarnessSpec,
                    RtlEngineError, read_records)

#: dm_pipeline parameters the harness is built with (passed as -G and as -DHARNESS_*).
PARAMS: dict[str, int] = {"PIX_W": 20, "H_ID_W": 4, "T_ID_W": 6, "AXI_DATA_W": 64}
#: Traverse rings (dm_pipeline's N_RINGS) the harness can be built with.
RINGS = (1, 2)


@functools.cache
def pipeline_spec(rings: int = 1) -> HarnessSpec:
    """The harness (tb/harness/pipeline_harness.cpp) for :func:`tb.harness.build.build`, with
    ``rings`` traverse rings (N_RINGS; 1 builds into build/harness/pipeline, n into
    build/harness/pipeline-r<n>)."""
    if rings not in RINGS:
        raise ValueError(f"rings must be one of {', '.join(map(str, RINGS))}, got {rings}")
    params = PARAMS if rings == 1 else {**PARAMS, "N_RINGS": rings}
    return HarnessSpec(
        name="pipeline" if rings == 1 else f"pipeline-r{rings}", top="dm_pipeline",
        rtl_dirs=("common", "fp", "traverse", "cache", "mip", "pipe"),
        sources=(HARNESS_DIR / "pipeline_harness.cpp", HARNESS_DIR / "pipeline_harness.h",
                 *COMMON_SOURCES),
        binary="pipeline_harness", params=params,
        build_dir=BUILD / ("pipeline" if rings == 1 else f"pipeline-r{rings}"),
        required=(ROOT / "rtl" / "pipe" / "dm_pipeline.sv",))


#: The one-ring harness.
PIPELINE = pipeline_spec(1)

#: The configuration ports in the input file's order with their widths (pipeline_harness.h
#: PIPH_CFG_PORTS; the harness checks every width).
CFG_PORTS: tuple[tuple[str, int], ...] = (
    ("cfg_method_i", 4), ("cfg_width_i", 16), ("cfg_height_i", 16), ("cfg_root_level_i", 4),
    ("cfg_bits16_i", 1), ("cfg_base_i", 32), ("cfg_root_code_i", 16),
    ("cfg_iter_cap_i", 16), ("cfg_depth_i", 24), ("cfg_mip_en_i", 1),
    ("cfg_levels_colour_i", 6), ("cfg_levels_normal_i", 6), ("cfg_shade_i", 192),
    ("cfg_miss_rgb_i", 24), ("cfg_tex_su_i", 48), ("cfg_tex_sv_i", 48),
    ("cfg_tex_base_i", 64))

#: Largest map and texture side the configuration ports hold (traverse_pkg::MAX_LEVELS: root
#: level <= MAX_LEVELS - 1; pipe_pkg::TEX_LEVELS MIP levels).
MAX_MAP_SIDE = 1 << (traverse_words.MAX_LEVELS - 1)
MAX_TEX_SIDE = 1 << (pipeline_words.TEX_LEVELS - 1)
#: Default AXI read latency of both ports (clocks from the address to the first beat).
DEFAULT_LATENCY = (20, 20)
#: Default fragment order: 8 x 8 pixel tiles, as a tiled rasteriser emits them.
DEFAULT_TILE = 16
#: Order of the tiles (model.camera.tile_order): row by row.  A Z-order curve ("morton") cuts the
#: texture traffic (rocks oblique 512x512: -30% texture bytes) but raises the height traffic
#: (+36%): the rays of a tile row read neighbouring bands of the height map.
DEFAULT_BLOCKS = "rows"

# ---- the file formats of tb/harness/pipeline_harness.h -----------------------------------------
IN_MAGIC = b"PIPHIN01"
IN_VERSION = 2
IN_HEADER_WORDS = 16
FRAG_WORDS = 16
OUT_MAGIC = b"PIPHOUT1"
OUT_RECORD = np.dtype([("id", "<u4"), ("rgb", "<u4"), ("flags", "<u4"), ("iterations", "<u4")])
FLAG_HIT, FLAG_INVALID, FLAG_ERR = 1, 2, 4

ProgressFn = Callable[[int, int], None]


class RtlLimitError(ValueError):
    """A frame the RTL cannot take (its configuration ports or address space are too small)."""


class RtlPixels(NamedTuple):
    """Per fragment (in the order given to :func:`run_pixels`): unorm8 ``rgb`` (N, 3), ``hit``,
    ``invalid``, ``err`` (an AXI read error touched the pixel) and ``iterations``."""

    rgb: npt.NDArray[np.uint8]
    hit: npt.NDArray[np.bool_]
    invalid: npt.NDArray[np.bool_]
    err: npt.NDArray[np.bool_]
    iterations: npt.NDArray[np.int64]


class FrameImage(NamedTuple):
    """What the driver writes before the fragments: the configuration (ports, triangle-table
    writes, height image and base) and the texture port's memory image and base."""

    cfg: pipeline_words.PipelineConfig
    tex_base: int
    tex_image: bytes


# ---- limits and memory layout ----------------------------------------------------------------

def check_limits(frame: shade.Frame) -> None:
    """Raise :class:`RtlLimitError` (one line) when the RTL cannot render ``frame``."""
    if frame.method not in traverse.EXACT_METHODS:
        raise RtlLimitError(f"method {frame.method!r} has no RTL (exact methods only: "
                            f"{', '.join(traverse.EXACT_METHODS)})")
    if frame.engine != "f24":
        raise RtlLimitError("the RTL pipeline computes the f24 engine")
    pyr = frame.pyr
    if max(pyr.width, pyr.height) > MAX_MAP_SIDE:
        raise RtlLimitError(f"height map {pyr.width} x {pyr.height}: the RTL takes at most "
                            f"{MAX_MAP_SIDE} texels a side")
    cap = traverse.iteration_cap(pyr)
    if cap >= 1 << 16:
        raise RtlLimitError(f"height map {pyr.width} x {pyr.height}: its iteration cap {cap} "
                            "does not fit the RTL's 16-bit iteration counter")
    if len(pyr.memory_image()) + pipeline_words.HEIGHT_BASE > 1 << 32:
        raise RtlLimitError("the height pyramid does not fit the 32-bit address space")
    for what, tex in (("texture", frame.colour), ("normal map", frame.normals)):
        if max(tex.width, tex.height) > MAX_TEX_SIDE or tex.n_levels > pipeline_words.TEX_LEVELS:
            raise RtlLimitError(f"{what} {tex.width} x {tex.height}: the RTL takes at most "
                                f"{MAX_TEX_SIDE} texels a side ({pipeline_words.TEX_LEVELS} MIP "
                                "levels)")
    end = _normal_base(frame) + frame.normals.memory_size()
    if end > 1 << 32:
        raise RtlLimitError("the texture and normal map do not fit the 32-bit address space")


def _normal_base(frame: shade.Frame) -> int:
    return pipeline_words.COLOUR_BASE + -(-frame.colour.memory_size() // 4096) * 4096


def frame_image(frame: shade.Frame) -> FrameImage:
    """The configuration and memory images of ``frame`` (:func:`check_limits` first)."""
    check_limits(frame)
    nb = _normal_base(frame)
    cfg = pipeline_words.config(frame, pipeline_words.HEIGHT_BASE, pipeline_words.COLOUR_BASE, nb)
    buf = bytearray(nb - pipeline_words.COLOUR_BASE + frame.normals.memory_size())
    for base, img in cfg.textures:
        off = base - pipeline_words.COLOUR_BASE
        buf[off:off + len(img)] = img
    return FrameImage(cfg, pipeline_words.COLOUR_BASE, bytes(buf))


def fragment_words(inp: shade.PixelInputs) -> npt.NDArray[np.uint32]:
    """(N, 16) u32 per fragment: u0, v0, Pl0, tri, TBN[9] (T 0..2, B 3..5, N 6..8), view[3], the
    f24 words of :func:`tb.harness.pipeline_words.fragment_words` (the model's quantisation)."""
    n = len(inp.u0)
    out = np.zeros((n, FRAG_WORDS), dtype="<u4")

    def w(x: npt.ArrayLike) -> npt.NDArray[np.uint32]:
        with np.errstate(invalid="ignore"):
            return f24.from_float(np.asarray(x, dtype=np.float64)).astype(np.uint32)

    out[:, 0], out[:, 1], out[:, 2] = w(inp.u0), w(inp.v0), w(inp.pl0)
    tri = np.asarray(inp.tri, dtype=np.int64)
    if n and (tri.min() < 0 or tri.max() >= 16):
        raise RtlLimitError("triangle ids must be 0 .. 15 (the triangle table's entries)")
    out[:, 3] = tri.astype(np.uint32)
    tbn = np.asarray(inp.tbn, dtype=np.float64)
    for c in range(3):          # columns T, B, N
        for i in range(3):
            out[:, 4 + 3 * c + i] = w(tbn[:, i, c])
    view = np.asarray(inp.view, dtype=np.float64)
    for i in range(3):
        out[:, 13 + i] = w(view[:, i])
    return out


# ---- input / output files ----------------------------------------------------------------------

def write_input(path: Path, fi: FrameImage, frags: npt.NDArray[np.uint32]) -> None:
    """Write the harness input (tb/harness/pipeline_harness.h): header, configuration ports,
    triangle-table writes, level-table writes, the two memory images, the fragments ((N, 16)
    u32, stream order)."""
    ports = fi.cfg.ports
    cfg_words: list[int] = []
    for name, bits in CFG_PORTS:
        v = int(ports[name])
        if v < 0 or v >> bits:
            raise ValueError(f"{name} = {v:#x} does not fit {bits} bits")
        cfg_words.append(bits)
        cfg_words += [(v >> (32 * k)) & 0xFFFFFFFF for k in range(-(-bits // 32))]
    h_base, h_img = fi.cfg.height
    frags = np.ascontiguousarray(frags, dtype="<u4")
    if frags.ndim != 2 or frags.shape[1] != FRAG_WORDS:
        raise ValueError(f"fragments are (N, {FRAG_WORDS}) words, got {frags.shape}")
    head = np.zeros(IN_HEADER_WORDS, dtype="<u4")
    head[0:2] = np.frombuffer(IN_MAGIC, dtype="<u4")
    head[2:14] = [IN_VERSION, 4 * IN_HEADER_WORDS, len(CFG_PORTS), len(cfg_words),
                  len(fi.cfg.tri_writes), len(frags), h_base, len(h_img), fi.tex_base,
                  len(fi.tex_image), FRAG_WORDS, len(fi.cfg.lvt_writes)]
    tri = np.array(fi.cfg.tri_writes, dtype="<u4").reshape(-1, 2)
    lvt = np.array(fi.cfg.lvt_writes, dtype="<u4").reshape(-1, 2)
    with open(path, "wb") as f:
        f.write(head.tobytes())
        f.write(np.array(cfg_words, dtype="<u4").tobytes())
        f.write(tri.tobytes())
        f.write(lvt.tobytes())
        for img in (h_img, fi.tex_image):
            f.write(img)
            f.write(bytes(-len(img) % 4))
        f.write(frags.tobytes())


def read_output(path: Path, n: int) -> npt.NDArray[Any]:
    """The harness output: one OUT_RECORD per fragment, in stream order."""
    return read_records(path, OUT_MAGIC, OUT_RECORD, n, "pipeline harness")


def to_pixels(out: npt.NDArray[Any]) -> RtlPixels:
    """Harness records -> per-fragment arrays."""
    rgb = np.stack([(out["rgb"] >> s) & 255 for s in (0, 8, 16)], axis=1).astype(np.uint8)
    fl = out["flags"]
    return RtlPixels(rgb, (fl & FLAG_HIT) != 0, (fl & FLAG_INVALID) != 0, (fl & FLAG_ERR) != 0,
                     out["iterations"].astype(np.int64))


# ---- build and run -------------------------------------------------------------------------------

def build(variant: str = "fast", *, force: bool = False, quiet: bool = True,
          rings: int = 1) -> Path:
    """Build the pipeline harness variant (``fast``, ``checked`` or ``waves``) with ``rings``
    traverse rings when its inputs changed (:func:`tb.harness.build.build`); returns the
    binary."""
    return _build.build(pipeline_spec(rings), variant, force=force, quiet=quiet)


def is_built(variant: str = "fast", rings: int = 1) -> bool:
    """True when the variant's binary is current."""
    return _build.is_built(pipeline_spec(rings), variant)


def default_variant(checked: bool | None = None, waves: bool = False) -> str:
    """``waves`` with a waveform, else ``checked`` when asked or ``RTL_ENGINE_CHECKED=1``."""
    if waves:
        return "waves"
    if checked is None:
        checked = os.environ.get("RTL_ENGINE_CHECKED", "") == "1"
    return "checked" if checked else "fast"


def _latency(latency: int | tuple[int, int]) -> str:
    lo, hi = (latency, latency) if isinstance(latency, (int, np.integer)) else latency
    lo, hi = int(lo), int(hi)
    if not 1 <= lo <= hi:
        raise ValueError(f"latency wants 1 <= min <= max, got {latency}")
    return f"{lo}:{hi}"


def run_pixels(fi: FrameImage, frags: npt.NDArray[np.uint32], *,
               latency: int | tuple[int, int] = DEFAULT_LATENCY,
               h_latency: int | tuple[int, int] | None = None,
               t_latency: int | tuple[int, int] | None = None, seed: int = 0,
               frag_gap: float = 0.0, px_stall: float = 0.0, ar_stall: float = 0.0,
               rvalid_gap: float = 0.0, h_err: Sequence[tuple[int, int]] = (),
               t_err: Sequence[tuple[int, int]] = (), timeout: int | None = None,
               stall: int | None = None, checked: bool | None = None,
               waves: str | Path | None = None, progress: ProgressFn | None = None,
               binary: Path | None = None, rings: int = 1,
               reset: int = 10) -> tuple[RtlPixels, dict[str, Any]]:
    """Run one frame's fragments ((N, 16) words, :func:`fragment_words`) through the harness.

    Every knob is a harness option (``pipeline_harness --help``): AXI latency of both ports (or
    per port), random gaps and stalls, SLVERR ranges, the clock watchdogs ``timeout`` (whole
    frame) and ``stall`` (between two pixels), the clocks of reset at the start (``reset``, the
    registers starting from the seed's random values).  ``progress(done, total)`` is called about twice a
    second.  ``rings``: the harness with that many traverse rings (:data:`RINGS`).  Raises
    :class:`tb.harness.build.RtlEngineError` with the harness's message when the run fails (a
    watchdog, a pixel lost or returned twice, an AXI protocol violation).
    """
    variant = default_variant(checked, waves is not None)
    exe = binary if binary is not None else build(variant, rings=rings)
    n = len(frags)
    with tempfile.TemporaryDirectory(prefix="dm_pipeline_") as tmp:
        tdir = Path(tmp)
        write_input(tdir / "in.bin", fi, frags)
        lat = _latency(latency)
        cmd = [str(exe), "--in", str(tdir / "in.bin"), "--out", str(tdir / "out.bin"),
               "--stats", str(tdir / "stats.json"), "--latency", lat,
               "--h-latency", _latency(h_latency) if h_latency is not None else lat,
               "--t-latency", _latency(t_latency) if t_latency is not None else lat,
               "--seed", str(int(seed)), "--frag-gap", repr(float(frag_gap)),
               "--px-stall", repr(float(px_stall)), "--ar-stall", repr(float(ar_stall)),
               "--rvalid-gap", repr(float(rvalid_gap)), "--reset", str(int(reset)), "--quiet"]
        for opt, ranges in (("--h-err", h_err), ("--t-err", t_err)):
            for a, b in ranges:
                cmd += [opt, f"{int(a)}:{int(b)}"]
        if timeout is not None:
            cmd += ["--timeout", str(int(timeout))]
        if stall is not None:
            cmd += ["--stall", str(int(stall))]
        if waves is not None:
            Path(waves).parent.mkdir(parents=True, exist_ok=True)
            cmd += ["--waves", str(Path(waves).resolve())]
        if progress is not None:
            cmd.append("--progress")
        t0 = time.monotonic()
        with subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True) as p:
            assert p.stdout is not None and p.stderr is not None
            other: list[str] = []
            for line in p.stdout:
                parts = line.split()
                if progress is not None and len(parts) == 4 and parts[0] == "progress":
                    progress(int(parts[1]), int(parts[2]))
                else:
                    other.append(line)
            err = p.stderr.read()
            rc = p.wait()
        wall = time.monotonic() - t0
        if rc != 0:
            raise RtlEngineError(f"pipeline harness exit status {rc}: "
                                 + (err.strip() or "".join(other).strip()))
        out = read_output(tdir / "out.bin", n).copy()
        stats: dict[str, Any] = json.loads((tdir / "stats.json").read_text())
    if progress is not None:
        progress(n, n)
    stats["harness_variant"] = variant
    stats["rings"] = rings
    stats["harness_wall_seconds"] = round(wall, 3)
    return to_pixels(out), stats


def derived_stats(stats: dict[str, Any]) -> dict[str, Any]:
    """Per-pixel ratios of the harness statistics (cycles, iterations, bytes per pixel)."""
    n = max(int(stats["pixels"]), 1)
    return {"cycles_per_pixel": stats["cycles"] / n,
            "iterations_per_pixel": stats["iterations"] / n,
            "bytes_per_pixel": stats["mem_bytes"] / n,
            "height_bytes_per_pixel": stats["height_mem_bytes"] / n,
            "texture_bytes_per_pixel": stats["texture_mem_bytes"] / n,
            "cycles_per_iteration": stats["cycles"] / max(int(stats["iterations"]), 1)}


def render_rtl(frame: shade.Frame, cam: Camera, *, tile: int = DEFAULT_TILE,
               blocks: str = DEFAULT_BLOCKS, frags: Fragments | None = None,
               **options: Any) -> tuple[shade.Image, dict[str, Any]]:
    """Render the camera's image through the RTL: :func:`model.shade.render`'s layout.

    Fragments go in ``tile`` x ``tile`` blocks, the blocks in ``blocks`` order
    (:func:`model.camera.tile_order`); ``options`` go to :func:`run_pixels`.  Pixels
    the quad does not cover get :data:`model.shade.BACKGROUND`; MIP levels are -1 (the RTL does
    not output them).  ``stats`` also carries ``errors`` (pixels an AXI error touched) and the
    ratios of :func:`derived_stats`.
    """
    fi = frame_image(frame)
    f, inp = shade.pixel_inputs(cam, frags)
    order = tile_order(f.row, f.col, cam.image_w, tile, blocks)
    px, stats = run_pixels(fi, fragment_words(inp.subset(order)), **options)
    n = len(f)
    rgb_cov = np.empty((n, 3), dtype=np.uint8)
    hit = np.zeros(n, dtype=bool)
    inval = np.zeros(n, dtype=bool)
    iters = np.zeros(n, dtype=np.int64)
    rgb_cov[order], hit[order], inval[order], iters[order] = (px.rgb, px.hit, px.invalid,
                                                              px.iterations)
    img = np.empty(f.mask.shape + (3,), dtype=np.uint8)
    img[:] = shade.BACKGROUND
    img[f.row, f.col] = rgb_cov
    none = np.full(n, -1, dtype=np.int64)
    stats.update(derived_stats(stats))
    stats["tile"] = tile
    return shade.Image(img, f, shade.PixelOutputs(rgb_cov, hit, inval, iters, none, none.copy())), \
        stats


def compare(rtl: shade.PixelOutputs, ref: shade.PixelOutputs) -> npt.NDArray[np.int64]:
    """Indices of covered pixels whose rgb, hit, invalid flag or iteration count differ."""
    bad = ((rtl.rgb != ref.rgb).any(axis=1) | (rtl.hit != ref.hit)
           | (rtl.invalid != ref.invalid) | (rtl.iterations != ref.iterations))
    return np.nonzero(bad)[0].astype(np.int64)


#: Park et al. 2013: their units ran at 84 MHz (Virtex-6): quoted beside ours as the paper's figure,
#: and in place of ours only when no routed result of ours is at hand.
PAPER_MHZ = 84.0
#: Where make synth writes the place-and-route result (scripts/flow/synth.py).
SYNTH_REPORT = ROOT / "out" / "synth" / "report.json"
#: The project's committed routed results of the FPGA top (nextpnr-ecp5), one entry per top
#: configuration: {"tops": [{"name", "rings", "lut", "ff", "dsp", "bram", "fmax_mhz", "seed",
#: "router", "device", "rtl_commit"}]}.
ROUTED_RESULTS = ROOT / "docs" / "results" / "synth-ecp5.json"
#: The FPGA top whose routed clock the pipeline's Mpixels/s are quoted at (one pipeline).
FPGA_TOP = "dm_pipeline_fpga_top"


#: The blocks dm_pipeline is made of, as scripts/flow/synth.py names them: when the top has no
#: place-and-route result, the slowest of their out-of-context fmax bounds its clock.
PIPELINE_BLOCKS = ("view_calc", "traverse_system", "mip_level", "tex_addr", "tex_cache",
                   "tex_filter", "shade_unit")


def _positive(x: Any) -> float | None:
    try:
        f = float(x)
    except (TypeError, ValueError):
        return None
    return f if f > 0 else None


def synth_clock(report: Path | None = None, blocks: bool = True) -> tuple[float, str] | None:
    """The clock ``make synth``'s report (default :data:`SYNTH_REPORT`) gives the pipeline, in
    MHz, and where it comes from: the top's place-and-route fmax; without one (the top was not
    placed and routed, e.g. it does not fit the device) and with ``blocks``, the lowest
    out-of-context fmax among :data:`PIPELINE_BLOCKS`, labelled as that bound; None when there is
    no usable report."""
    try:
        rep = json.loads((report or SYNTH_REPORT).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(rep, dict):
        return None
    settings = rep.get("settings")
    dev = settings.get("device_name", "") if isinstance(settings, dict) else ""
    where = f"out/synth/report.json{', ' + dev if dev else ''}"
    f = _positive(rep.get("fmax_mhz"))
    if f is not None:
        return f, f"fmax of {rep.get('top', 'the top')} from place and route ({where})"
    if not blocks:
        return None
    rep_blocks = rep.get("blocks")
    fm = []
    for name in PIPELINE_BLOCKS:
        b = rep_blocks.get(name) if isinstance(rep_blocks, dict) else None
        v = _positive(b.get("fmax_mhz")) if isinstance(b, dict) else None
        if v is not None:
            fm.append((v, name))
    if not fm:
        return None
    f, name = min(fm)
    return f, (f"bound: the slowest block of the pipeline placed and routed out of context, "
               f"{name} ({where}); the top itself has no place-and-route fmax")


def _shown(path: Path) -> str:
    """A path as the messages show it: relative to the repository when inside it."""
    try:
        return path.resolve().relative_to(ROOT).as_posix()
    except ValueError:
        return str(path)


def routed_clock(results: Path | None = None, rings: int = 1) -> tuple[float, str] | None:
    """The routed fmax of :data:`FPGA_TOP` with ``rings`` traverse rings in the committed results
    (default :data:`ROUTED_RESULTS`), in MHz, and where it comes from; None without one."""
    path = results or ROUTED_RESULTS
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    tops = doc.get("tops") if isinstance(doc, dict) else None
    for top in tops if isinstance(tops, list) else []:
        if not (isinstance(top, dict) and top.get("name") == FPGA_TOP
                and top.get("rings", 1) == rings):
            continue
        f = _positive(top.get("fmax_mhz"))
        if f is None:
            continue
        where = _shown(path)
        run = ", ".join(str(x) for x in (top.get("device"), f"seed {top['seed']}" if "seed" in top
                                         else None, top.get("router"),
                                         f"RTL of {top['rtl_commit']}" if "rtl_commit" in top
                                         else None) if x)
        return f, (f"routed fmax of {FPGA_TOP}{f' ({rings} rings)' if rings > 1 else ''} "
                   f"({where}{': ' + run if run else ''})")
    return None


def pipeline_clock(rings: int = 1) -> tuple[float, str]:
    """The clock to quote Mpixels/s at, and where it comes from.  One ring: the top's
    place-and-route fmax of a local ``make synth`` (:func:`synth_clock`), else the project's
    committed routed result (:func:`routed_clock`), else a local report's bound from the blocks,
    else the paper's 84 MHz, labelled as assumed.  More rings: the committed routed result of
    that top, else the paper's 84 MHz, labelled as assumed (a local report and the blocks'
    bounds describe the one-ring top)."""
    if rings != 1:
        return routed_clock(rings=rings) or (
            PAPER_MHZ, f"assumed: the paper's {PAPER_MHZ:g} MHz (no routed result of the "
            f"{rings}-ring top in {_shown(ROUTED_RESULTS)})")
    return synth_clock(blocks=False) or routed_clock() or synth_clock() or (
        PAPER_MHZ, f"assumed: the paper's {PAPER_MHZ:g} MHz (no routed result: neither "
        f"{_shown(ROUTED_RESULTS)} nor out/synth/report.json)")


def scene_frame(scene: str, map_size: int, angle: str | float, image: int,
                method: str = "park", mip: bool = True) -> tuple[shade.Frame, Camera]:
    """A procedural scene's frame (f24 engine) and camera, as ``make render`` builds them."""
    from model import camera, heightmap, scenes, texture

    sc = scenes.load_scene(scene, map_size)
    pyr = heightmap.build(sc.heights)
    tex, ntex = texture.build(sc.texture), texture.build(scenes.encode_normals(sc.normals))
    cam = camera.Camera.for_view(angle, pyr.width, pyr.height, image, image,
                                 depth_scale=sc.depth_scale)
    frame = shade.Frame(pyr=pyr, colour=tex, normals=ntex, depth_scale=sc.depth_scale,
                        log2pb_colour=cam.log2_pb(tex.width, tex.height),
                        log2pb_normal=cam.log2_pb(ntex.width, ntex.height), method=method,
                        engine="f24", mip=mip)
    return frame, cam


def main(argv: Sequence[str] | None = None) -> int:
    """Build the harness, render a scene through the RTL and the f24 model, compare, report."""
    from model import camera, scenes
    from model.cli import Parser, fail

    prog = "python -m tb.harness.dm_pipeline"
    ap = Parser(prog=prog, description=main.__doc__)
    ap.add_argument("--scene", default="rocks", choices=scenes.SCENES)
    ap.add_argument("--angle", default="oblique", choices=tuple(camera.VIEWS))
    ap.add_argument("--method", default="park", choices=traverse.EXACT_METHODS)
    ap.add_argument("--size", type=int, default=64, help="map and image side (default 64)")
    ap.add_argument("--variant", default="fast", choices=VARIANTS)
    ap.add_argument("--build-only", action="store_true")
    a = ap.parse_args(argv)
    if not 2 <= a.size <= 4096:
        fail(prog, f"--size must be in 2..4096, got {a.size}")
    t0 = time.monotonic()
    build(a.variant, quiet=False)
    print(f"dm_pipeline: harness ready ({time.monotonic() - t0:.1f} s)")
    if a.build_only:
        return 0
    frame, cam = scene_frame(a.scene, a.size, a.angle, a.size, a.method)
    try:
        check_limits(frame)
    except RtlLimitError as e:
        fail(prog, f"the pipeline RTL cannot render this: {e}")
    img, st = render_rtl(frame, cam, checked=a.variant == "checked")
    ref = shade.render(frame, cam)
    bad = compare(img.out, ref.out)
    print(f"dm_pipeline: {st['pixels']} pixels, {st['cycles']} clocks "
          f"({st['cycles_per_pixel']:.2f} / pixel, {st['cycles_per_iteration']:.3f} / iteration), "
          f"height cache {st['height_cache_hit_rate']:.4f}, texture cache "
          f"{st['texture_cache_hit_rate']:.4f}, {st['bytes_per_pixel']:.2f} bytes / pixel; "
          f"{st['clocks_per_second'] / 1e6:.3f} M clocks/s; {len(bad)} pixels differ from f24")
    return 1 if len(bad) else 0


if __name__ == "__main__":
    sys.exit(main())
