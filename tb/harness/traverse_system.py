# SPDX-License-Identifier: Apache-2.0
"""The RTL as a trace engine: ray batches through ``rtl/traverse/traverse_system.sv`` (traverse unit +
height cache + an AXI4 memory model) in a Verilator C++ harness (``tb/harness/traverse_harness.cpp``).

    res, stats = trace_rtl(pyr, rays, "park", latency=(20, 40), seed=1, backpressure=0.1)

``res`` is a :class:`~model.rays.TraceResult` like :func:`model.traverse.trace`'s (t, u, v as float64
from the unit's f24 words, NaN where there is no hit; hit, invalid and iterations are the RTL's own),
``stats`` the harness's JSON statistics (cycles, iterations, cache hits / misses, bytes read, wall
and CPU seconds, simulated clocks per second of each, ...).  The rays are quantised exactly as the model's
``ar.r()`` quantises them (:func:`model.f24.from_float`); which rays are invalid is the RTL's call.

The harness (:data:`TRAVERSE`) is built on demand by :func:`tb.harness.build.build` into
``build/harness/<variant>/`` -- ``fast``, ``checked`` (the RTL's assertions on; ``checked=True`` or
``RTL_ENGINE_CHECKED=1``, which the test suite sets) or ``waves`` (used when ``waves=FILE.fst`` is
given) -- from the RTL sources under rtl/common, rtl/fp, rtl/traverse and rtl/cache.

File formats between this module and the harness: ``tb/harness/traverse_harness.h``.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Mapping, Sequence

import numpy as np
import numpy.typing as npt

from model import f24
from model.heightmap import Pyramid
from model.rays import Rays, TraceResult
from model.traverse import METHOD_CODES

from . import build as _build
from .build import (BUILD, COMMON_SOURCES, HARNESS_DIR, ROOT, HarnessSpec, RtlEngineError,
                    read_records)
from .traverse_words import MAX_LEVELS, config, ray_words

HARNESS_SOURCES = (HARNESS_DIR / "traverse_harness.cpp", HARNESS_DIR / "traverse_harness.h",
                   *COMMON_SOURCES)
RTL_DIRS = ("common", "fp", "traverse", "cache")
#: traverse_pkg reads the float units' depths from pipe_pkg.
RTL_FILES = (ROOT / "rtl" / "pipe" / "pipe_pkg.sv",)
TOP = "traverse_system"
CACHE_SV = ROOT / "rtl" / "cache" / "height_cache.sv"
BINARY = "traverse_harness"

#: traverse_system parameters the harness is built with (passed as -G and as -DHARNESS_*).
PARAMS: dict[str, int] = {"RAY_ID_W": 16, "AXI_ID_W": 4, "AXI_DATA_W": 64}
#: Default byte address of the pyramid in the AXI address space.
DEFAULT_BASE = 0x4000_0000
#: Default AXI read latency (clocks from the address to the first beat).
DEFAULT_LATENCY = (20, 20)

# ---- the file formats of tb/harness/traverse_harness.h --------------------------------------------
IN_MAGIC = b"TRVHIN01"
IN_VERSION = 1
IN_HEADER_WORDS = 32
OUT_MAGIC = b"TRVHOUT1"
OUT_RECORD = np.dtype([("id", "<u4"), ("t", "<u4"), ("u", "<u4"), ("v", "<u4"), ("flags", "<u4"),
                       ("iterations", "<u4")])
FLAG_HIT, FLAG_INVALID, FLAG_CAPPED, FLAG_ERR = 1, 2, 4, 8

def cache_available() -> bool:
    """True once ``rtl/cache/height_cache.sv`` exists (the system needs it)."""
    return CACHE_SV.is_file()


# ---- input / output files ----------------------------------------------------------------------

def write_input(path: Path, pyr: Pyramid, rays: Rays, method: str, base: int = DEFAULT_BASE) -> None:
    """Write the harness input: header (configuration), memory image, rays as f24 words.

    Layout (all little-endian; tb/harness/traverse_harness.h):
      32 x u32 header: "TRVHIN01", version 1, header bytes 128, method, width, height, root level,
        bits16, base, root code, iteration cap, ray count, image bytes, level offsets [16], 0, 0;
      the memory image (Pyramid.memory_image()), zero-padded to a multiple of 4 bytes;
      per ray 4 x u32: u0, v0, du, dv as f24 words (f24.from_float, the model's quantisation).
    """
    if method not in METHOD_CODES:
        raise ValueError(f"unknown exact method {method!r} ({', '.join(METHOD_CODES)})")
    cfg = config(pyr, method, base=base)
    img = pyr.memory_image()
    if base + len(img) > 1 << 32:
        raise ValueError("the memory image does not fit the 32-bit address space at this base")
    if len(rays) >= 1 << 32:
        raise ValueError("too many rays for one batch")
    offs = [(cfg.level_off >> (32 * k)) & 0xFFFFFFFF for k in range(MAX_LEVELS)]
    head = np.zeros(IN_HEADER_WORDS, dtype="<u4")
    head[0:2] = np.frombuffer(IN_MAGIC, dtype="<u4")
    head[2:14] = [IN_VERSION, 4 * IN_HEADER_WORDS, cfg.method, cfg.width, cfg.height,
                  cfg.root_level, cfg.bits16, cfg.base, cfg.root_code, cfg.iter_cap, len(rays),
                  len(img)]
    head[14:14 + MAX_LEVELS] = offs
    words = np.stack([w.astype("<u4") for w in ray_words(rays)], axis=1) if len(rays) else \
        np.zeros((0, 4), dtype="<u4")
    with open(path, "wb") as f:
        f.write(head.tobytes())
        f.write(img)
        f.write(bytes(-len(img) % 4))
        f.write(np.ascontiguousarray(words, dtype="<u4").tobytes())


def read_output(path: Path, n: int) -> npt.NDArray[Any]:
    """The harness output: one OUT_RECORD per ray, in input order."""
    return read_records(path, OUT_MAGIC, OUT_RECORD, n, "harness")


def to_result(out: npt.NDArray[Any]) -> TraceResult:
    """Harness records -> TraceResult (t, u, v NaN where no hit)."""
    hit = (out["flags"] & FLAG_HIT) != 0
    nan = np.nan

    def val(w: npt.NDArray[np.uint32]) -> npt.NDArray[np.float64]:
        return np.where(hit, f24.to_float(w.astype(np.uint32)), nan)

    return TraceResult(t=val(out["t"]), u=val(out["u"]), v=val(out["v"]), hit=hit,
                       invalid=(out["flags"] & FLAG_INVALID) != 0,
                       iterations=out["iterations"].astype(np.int64))


def _training_input(path: Path) -> None:
    """A fixed ray batch for the profile-guided build: a rough 64x64 map, rays of every length
    and direction, the park-xor method (most of the loop's paths)."""
    from model import heightmap

    rng = np.random.default_rng(12345)
    pyr = heightmap.build(rng.random((64, 64)) ** 3, 8)
    n = 3000
    ang = rng.uniform(0, 2 * np.pi, n)
    ln = rng.uniform(0, 24, n)
    rays = Rays(rng.uniform(0, 64, n), rng.uniform(0, 64, n), ln * np.cos(ang), ln * np.sin(ang))
    write_input(path, pyr, rays, "park-xor")


#: The traverse-unit harness (traverse_system).
TRAVERSE = HarnessSpec(name="traverse", top=TOP, rtl_dirs=RTL_DIRS, sources=HARNESS_SOURCES,
                       binary=BINARY, params=PARAMS, build_dir=BUILD, training=_training_input,
                       required=(CACHE_SV,), rtl_files=RTL_FILES)
#: The same harness with the ring's park queue (traverse_loop PARK = 1), in its own build dir.
PARK_PARAMS: dict[str, int] = {**PARAMS, "PARK": 1}
TRAVERSE_PARK = HarnessSpec(name="traverse_park", top=TOP, rtl_dirs=RTL_DIRS,
                            sources=HARNESS_SOURCES, binary=BINARY, params=PARK_PARAMS,
                            build_dir=BUILD / "traverse_park", training=_training_input,
                            required=(CACHE_SV,), rtl_files=RTL_FILES)


def spec(park: bool = False, params: Mapping[str, int] | None = None) -> HarnessSpec:
    """The harness spec: :data:`TRAVERSE`, :data:`TRAVERSE_PARK` with ``park``, or with further
    traverse_system ``params`` (e.g. ``{"MSHRS": 8, "PARK_WAIT": 8}``) a build of its own in
    ``build/traverse_<name><value>...`` (for sweeps; the defaults' builds are unchanged)."""
    base = TRAVERSE_PARK if park else TRAVERSE
    if not params:
        return base
    full = {**base.params, **{k: int(v) for k, v in params.items()}}
    tag = "_".join(f"{k.lower()}{v}" for k, v in sorted(full.items()) if k not in PARAMS
                   or full[k] != PARAMS[k])
    return HarnessSpec(name=f"traverse_{tag}", top=TOP, rtl_dirs=RTL_DIRS,
                       sources=HARNESS_SOURCES, binary=BINARY, params=full,
                       build_dir=BUILD / f"traverse_{tag}", training=_training_input,
                       required=(CACHE_SV,), rtl_files=RTL_FILES)


def is_built(variant: str = "fast", *, park: bool = False,
             params: Mapping[str, int] | None = None) -> bool:
    """True when the variant's binary is current (:func:`build` would not rebuild it)."""
    return _build.is_built(spec(park, params), variant)


def default_variant(checked: bool | None = None) -> str:
    """The variant :func:`trace_rtl` runs without waves: ``checked`` (the RTL's assertions on)
    when ``checked`` is True, or when it is None and the environment has
    ``RTL_ENGINE_CHECKED=1`` (the test suite sets it); else ``fast``.  A driver that builds the
    harness before its runs builds this variant, so a run under the test suite does not compile a
    fast harness it never uses."""
    if checked is None:
        checked = os.environ.get("RTL_ENGINE_CHECKED", "") == "1"
    return "checked" if checked else "fast"


def build(variant: str = "fast", *, force: bool = False, quiet: bool = True,
          park: bool = False, params: Mapping[str, int] | None = None) -> Path:
    """Build the traverse harness variant when its inputs changed; returns the binary's path
    (:func:`tb.harness.build.build` with :data:`TRAVERSE`, or :data:`TRAVERSE_PARK` with
    ``park``: the ring with its park queue; ``params``: further traverse_system parameters,
    :func:`spec`)."""
    return _build.build(spec(park, params), variant, force=force, quiet=quiet)


# ---- run -----------------------------------------------------------------------------------------

def _latency(latency: int | tuple[int, int]) -> tuple[int, int]:
    lo, hi = (latency, latency) if isinstance(latency, (int, np.integer)) else latency
    lo, hi = int(lo), int(hi)
    if not 1 <= lo <= hi:
        raise ValueError(f"latency wants 1 <= min <= max, got {latency}")
    return lo, hi


def run_batch(pyr: Pyramid, rays: Rays, method: str, *,
              latency: int | tuple[int, int] = DEFAULT_LATENCY, seed: int = 0,
              ray_gap: float = 0.0, res_stall: float = 0.0, ar_stall: float = 0.0,
              rvalid_gap: float = 0.0, err_ranges: Sequence[tuple[int, int]] = (),
              base: int = DEFAULT_BASE, warm: bool = False, timeout: int | None = None,
              waves: str | Path | None = None, checked: bool | None = None,
              park: bool = False, params: Mapping[str, int] | None = None
              ) -> tuple[npt.NDArray[Any], dict[str, Any]]:
    """Run one batch through the harness; returns the raw records (OUT_RECORD) and the stats.

    Every knob is a harness option (``traverse_harness --help``).  ``checked``: run the variant
    with the RTL's assertions on (default: the environment's ``RTL_ENGINE_CHECKED=1``; waves
    always have them).  ``park``: the build with the ring's park queue; ``params``: further
    traverse_system parameters (:func:`spec`, a build of their own).  Raises RtlEngineError with the
    harness's message when the run fails (timeout, a ray lost or returned twice, AXI violation).
    """
    lo, hi = _latency(latency)
    binary = build("waves" if waves else default_variant(checked), park=park, params=params)
    n = len(rays)
    with tempfile.TemporaryDirectory(prefix="traverse_system_") as tmp:
        tdir = Path(tmp)
        write_input(tdir / "in.bin", pyr, rays, method, base)
        cmd = [str(binary), "--in", str(tdir / "in.bin"), "--out", str(tdir / "out.bin"),
               "--stats", str(tdir / "stats.json"), "--latency", f"{lo}:{hi}",
               "--seed", str(int(seed)), "--ray-gap", repr(float(ray_gap)),
               "--res-stall", repr(float(res_stall)), "--ar-stall", repr(float(ar_stall)),
               "--rvalid-gap", repr(float(rvalid_gap)), "--quiet"]
        for a, b in err_ranges:
            cmd += ["--err", f"{int(a)}:{int(b)}"]
        if warm:
            cmd.append("--warm")
        if timeout is not None:
            cmd += ["--timeout", str(int(timeout))]
        if waves:
            Path(waves).parent.mkdir(parents=True, exist_ok=True)
            cmd += ["--waves", str(Path(waves).resolve())]
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            raise RtlEngineError(f"harness exit status {p.returncode}:\n"
                                 + (p.stderr.strip() or p.stdout.strip()))
        out = read_output(tdir / "out.bin", n).copy()
        stats = json.loads((tdir / "stats.json").read_text())
    stats["method"] = method
    return out, stats


def trace_rtl(pyr: Pyramid, rays: Rays, method: str, *,
              latency: int | tuple[int, int] = DEFAULT_LATENCY, seed: int = 0,
              backpressure: float = 0.0, waves: str | Path | None = None,
              **options: Any) -> tuple[TraceResult, dict[str, Any]]:
    """Trace ``rays`` through ``pyr`` with an exact ``method`` on the RTL.

    latency: AXI read latency in clocks, fixed or (min, max) drawn per burst.  backpressure: the
    per-clock probability of a gap in the ray stream, of res_ready low and of an rvalid bubble
    (0: none).  waves: write an FST waveform there (builds the ``waves`` variant).  Further
    ``options`` go to :func:`run_batch` (ray_gap, res_stall, ar_stall, rvalid_gap override the
    backpressure defaults; err_ranges, base, warm, timeout, park, params).
    Returns (TraceResult, stats); per-ray capped / err flags are counted in stats.
    """
    bp = float(backpressure)
    if not 0.0 <= bp <= 1.0:
        raise ValueError("backpressure is a probability in [0, 1]")
    kw = {"ray_gap": bp, "res_stall": bp, "rvalid_gap": bp}
    kw.update(options)
    out, stats = run_batch(pyr, rays, method, latency=latency, seed=seed, waves=waves, **kw)
    return to_result(out), stats


def main(argv: Sequence[str] | None = None) -> int:
    """Build the harness, then measure it on a random map (clocks/s, clocks/iteration, hit rate)."""
    from model import heightmap, traverse
    from model.cli import Parser, fail

    prog = "python -m tb.harness.traverse_system"
    ap = Parser(prog=prog, description=main.__doc__)
    ap.add_argument("--size", type=int, default=256, help="map side (default 256)")
    ap.add_argument("--rays", type=int, default=20000)
    ap.add_argument("--method", default="park", choices=traverse.EXACT_METHODS)
    ap.add_argument("--latency", default="20", help="L or MIN:MAX, clocks >= 1")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--build-only", action="store_true")
    a = ap.parse_args(argv)
    if not 1 <= a.size <= 8192:
        fail(prog, f"--size must be in 1..8192, got {a.size}")
    if a.rays < 1:
        fail(prog, f"--rays must be positive, got {a.rays}")
    try:
        lat = tuple(int(x) for x in a.latency.split(":")) if ":" in a.latency else int(a.latency)
    except ValueError:
        fail(prog, f"--latency must be L or MIN:MAX, got {a.latency!r}")
    if min(lat if isinstance(lat, tuple) else (lat,)) < 1 or (
            isinstance(lat, tuple) and (len(lat) != 2 or lat[0] > lat[1])):
        fail(prog, f"--latency must be L >= 1 or MIN:MAX with 1 <= MIN <= MAX, got {a.latency!r}")
    t0 = time.monotonic()
    build(default_variant(), quiet=False)  # the variant trace_rtl below runs
    print(f"traverse_system: harness ready ({time.monotonic() - t0:.1f} s)")
    if a.build_only:
        return 0
    rng = np.random.default_rng(a.seed)
    pyr = heightmap.build(rng.random((a.size, a.size)) ** 3, 8)
    ang = rng.uniform(0, 2 * np.pi, a.rays)
    ln = rng.uniform(0, a.size / 4, a.rays)
    rays = Rays(rng.uniform(0, a.size, a.rays), rng.uniform(0, a.size, a.rays),
                ln * np.cos(ang), ln * np.sin(ang))
    for warm in (False, True):
        _, st = trace_rtl(pyr, rays, a.method, latency=lat, seed=a.seed, warm=warm)
        print(f"{'warm' if warm else 'cold'}: {st['rays']} rays, {st['iterations']} iterations, "
              f"{st['cycles']} clocks = {st['cycles_per_iteration']:.3f} clocks/iteration, "
              f"cache hit rate {st['height_cache_hit_rate']:.4f}, {st['mem_bytes']} bytes read; "
              f"{st['sim_clocks']} clocks simulated in {st['wall_seconds']:.2f} s = "
              f"{st['clocks_per_second'] / 1e6:.2f} M clocks/s "
              f"({st['clocks_per_cpu_second'] / 1e6:.2f} M per CPU second)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
