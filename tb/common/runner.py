# SPDX-License-Identifier: Apache-2.0
"""Build and run one cocotb test module on Verilator through cocotb's Python runner.

Each ``tb/<unit>/test_<unit>.py`` holds the cocotb coroutines and a pytest function that calls
:func:`run`.  Builds go to ``build/sim/<name>`` (one directory per parameter set), so pytest-xdist
workers never share one.  Set ``WAVES=1`` to write an FST waveform (``build/sim/<name>-waves/dump.fst``,
a separate build with tracing compiled in).

Coverage (``make coverage``, ``scripts/bench/coverage.py``): with ``COVERAGE=1`` the build adds
Verilator's line and toggle coverage (``--coverage-line --coverage-toggle``) in its own build
directory (``build/sim/<name>-cov``), and each run writes its counters to
``build/coverage/<name>[-<case>]-<h>.dat`` (``<h>``: a short hash of the test module, test case and
extra environment, so two runs of one build with different settings keep separate files);
``COVERAGE_DIR`` overrides ``build/coverage``.  Coverage and waves do not combine (``WAVES=1`` wins:
no coverage).  cocotb itself reads the old ``COVERAGE`` variable as "measure the Python test code's
coverage"; :func:`run` sets ``COCOTB_USER_COVERAGE=0`` for the simulation (unless the caller set
it) so that it does not.
"""
from __future__ import annotations

import hashlib
import os
import re
from pathlib import Path
from typing import Mapping, Sequence

from cocotb_tools.runner import get_runner

from tb.common import objcache, vbuild

ROOT = Path(__file__).resolve().parents[2]
RTL = ROOT / "rtl"
BUILD = ROOT / "build" / "sim"
COVERAGE_DIR = ROOT / "build" / "coverage"
#: Verilator options of a coverage build (scripts/bench/coverage.py reads the counters they produce).
COVERAGE_ARGS = ("--coverage-line", "--coverage-toggle")


#: The C++ optimisation of the largest models (dm_pipeline, pidm_top: one model function of 12
#: to 20 MB).  GCC takes minutes over such a function at -O1; at -O0 it compiles in about half
#: -Og's time, but nothing is inlined, so every array index and wide-word access of the model is
#: a call: a pidm_top frame then takes about 5 times the process time it takes at -Og (perf: 90 %
#: of the simulation's process time in the model, 30 % of it in those accessors).  -Og inlines
#: them and adds about 25 s of compile time to such a build.
LARGE_MODEL_OPT = "-Og"


def long_stimulus() -> bool:
    """True under ``make test-long`` (``TB_LONG=1``): the testbenches' longer stimulus."""
    return os.environ.get("TB_LONG") == "1"

_MODULE_RE = re.compile(r"^\s*(?:module|package)\s+(\w+)", re.M)


def rtl_index() -> dict[str, Path]:
    """Map every module and package name under rtl/ to its file (one per file, named after it)."""
    index: dict[str, Path] = {}
    for path in sorted(RTL.rglob("*.sv")):
        for name in _MODULE_RE.findall(path.read_text()):
            index[name] = path
    return index


def rtl_files() -> list[Path]:
    """Every SystemVerilog file under rtl/, packages first (a bound checker's file may hold only
    its ``bind``, so files are listed, not modules)."""
    files = sorted(RTL.rglob("*.sv"))
    return [p for p in files if p.name.endswith("_pkg.sv")] + \
        [p for p in files if not p.name.endswith("_pkg.sv")]


def is_bound_checker(path: Path) -> bool:
    """True for a file of bound assertions (``rtl/**/<module>_assert.sv``: a checker module and
    the ``bind`` that puts it into every instance of <module>).  It is compiled with the RTL (the
    binds apply wherever the module is used) but is never a top of its own: it reads the bound
    module's internals through a hierarchical reference."""
    return path.name.endswith("_assert.sv")


def sources_for(top: str, extra: Sequence[str] = ()) -> list[Path]:
    """The packages first, then every other file under rtl/ (Verilator picks the modules it needs;
    the bound checkers' binds apply wherever their modules are used)."""
    index = rtl_index()
    if top not in index:
        raise KeyError(f"no module {top!r} under {RTL}")
    return rtl_files() + [Path(e) for e in extra]


def coverage_enabled() -> bool:
    """True when this run collects coverage: ``COVERAGE=1`` and no ``WAVES=1``."""
    return os.environ.get("COVERAGE", "0") == "1" and os.environ.get("WAVES", "0") != "1"


def coverage_file(name: str, test_module: str, testcase: str | None,
                  extra_env: Mapping[str, str] | None) -> Path:
    """Where a coverage run of build ``name`` writes its counters (see the module docstring)."""
    key = "\0".join([test_module, testcase or "",
                     *(f"{k}={v}" for k, v in sorted((extra_env or {}).items()))])
    tag = hashlib.sha256(key.encode()).hexdigest()[:8]
    out = Path(os.environ.get("COVERAGE_DIR") or COVERAGE_DIR)
    return out / f"{name}{'-' + testcase if testcase else ''}-{tag}.dat"


def build_path(name: str) -> Path:
    """The directory of build ``name``: ``build/sim/<name>``, with ``-waves`` (``WAVES=1``) or
    ``-cov`` (:func:`coverage_enabled`) appended."""
    waves = os.environ.get("WAVES", "0") == "1"
    return BUILD / (name + ("-waves" if waves else "-cov" if coverage_enabled() else ""))


def verilator_args(waves: bool, coverage: bool = False, opt: str = "-O1") -> list[str]:
    # The model in one C++ file: no precompiled header (tb/common/vbuild.py says why).
    args = ["--assert", "-Wno-fatal", "-O3", "--x-assign", "unique", "--x-initial", "unique",
            *vbuild.ONE_FILE, "-CFLAGS", f"{vbuild.CXX_STD} {opt}", "--build-jobs", "1"]
    if waves:
        # Verilator's FST writer includes <lz4.h> and links -llz4, which this machine lacks: our
        # header-only LZ4 block writer (tb/harness/lz4_compat) stands in, and an empty archive
        # satisfies -llz4; zlib is the system's.
        stub = BUILD / "lz4stub"
        stub.mkdir(parents=True, exist_ok=True)
        if not (stub / "liblz4.a").is_file():
            (stub / "liblz4.a").write_bytes(b"!<arch>\n")
        args += ["--trace-fst", "--trace-structs",
                 "-CFLAGS", f"-I{ROOT / 'tb' / 'harness' / 'lz4_compat'}",
                 "-LDFLAGS", f"-L{stub} -lz"]
    elif coverage:
        args += list(COVERAGE_ARGS)
    return args


def run(top: str, test_module: str, test_dir: Path, parameters: Mapping[str, object] | None = None,
        name: str | None = None, extra_env: Mapping[str, str] | None = None,
        testcase: str | None = None, extra_sources: Sequence[str] = (),
        rtl_top: str | None = None, opt: str = "-O1") -> None:
    """Build ``top`` (with ``parameters``) and run the cocotb tests in ``test_module``.

    ``opt`` is the C++ optimisation of the model: :data:`LARGE_MODEL_OPT` suits a large design
    (its one model function compiles in a fraction of -O1's time).

    ``extra_sources`` are testbench files (e.g. a wrapper that is ``top``); ``rtl_top`` names the
    RTL module whose sources are needed when ``top`` is such a wrapper.
    """
    parameters = dict(parameters or {})
    name = name or top + "".join(f"-{k}{v}" for k, v in sorted(parameters.items()))
    waves = os.environ.get("WAVES", "0") == "1"
    cov = coverage_enabled()
    build_dir = build_path(name)
    # Verilator's makefiles prefix every compile with $(OBJCACHE): the runtime and cocotb's main
    # are compiled once, not in every build (set OBJCACHE= empty to compile everything again).
    os.environ.setdefault("OBJCACHE", objcache.COMMAND)
    runner = get_runner("verilator")
    with vbuild.build_lock(build_dir.parent / f"{build_dir.name}.lock"):
        runner.build(
            sources=[str(p) for p in sources_for(rtl_top or top, extra_sources)],
            hdl_toplevel=top,
            parameters=parameters,
            build_dir=str(build_dir),
            build_args=verilator_args(waves, cov, opt),
            waves=False,
            always=False,
            timescale=("1ns", "1ps"),
        )
    env = {"PYTHONPATH": os.pathsep.join([str(ROOT), str(test_dir)])}
    env.update(extra_env or {})
    plusargs: list[str] = []
    if "COVERAGE" in os.environ and "COCOTB_USER_COVERAGE" not in os.environ:
        env.setdefault("COCOTB_USER_COVERAGE", "0")  # COVERAGE means RTL coverage here
    if cov:
        dat = coverage_file(name, test_module, testcase, extra_env)
        dat.parent.mkdir(parents=True, exist_ok=True)
        dat.unlink(missing_ok=True)
        plusargs.append(f"+verilator+coverage+file+{dat}")
    runner.test(
        hdl_toplevel=top,
        test_module=test_module,
        test_dir=str(test_dir),
        build_dir=str(build_dir),
        extra_env=env,
        testcase=testcase,
        test_args=["--trace", "--trace-file", str(build_dir / "dump.fst")] if waves else [],
        plusargs=plusargs,
        results_xml=str(build_dir / "results.xml"),
    )
