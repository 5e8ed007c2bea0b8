#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Run one cocotb test with waveforms (`make waves TEST=...`) and say where the FST is.

  waves.py TEST [--case NAME]

TEST is a testbench directory (`traverse_system`, `tb/traverse_system`), a test file
(`tb/traverse_system/test_traverse_system.py`) or a pytest node id
(`tb/traverse_system/test_traverse_system.py::test_traverse_system`).  --case selects cocotb tests
inside it by name (COCOTB_TEST_FILTER).  The test runs with WAVES=1: tb/common/runner.py builds a
separate, traced Verilator model and writes build/sim/<name>-waves/dump.fst.  Exit status: the
test's (the FST is reported even when the test fails: that is when it is wanted); a TEST that
names nothing: one line, exit status 2.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TB = ROOT / "tb"
SIM = ROOT / "build" / "sim"
GTKW = TB / "waves"
PROG = "waves.py"
from model.cli import Parser


def fail(msg: str) -> int:
    print(f"{PROG}: error: {msg}", file=sys.stderr)
    return 2


def resolve(test: str) -> tuple[str, Path]:
    """(pytest node id relative to the repository, its testbench directory)."""
    path, sep, rest = test.partition("::")
    p = Path(path)
    cands = [p, ROOT / p, TB / p] if not p.is_absolute() else [p]
    for c in cands:
        if c.is_dir():
            files = sorted(c.glob("test_*.py"))
            if not files:
                raise ValueError(f"no test_*.py in {c}")
            if sep:
                raise ValueError(f"{test}: a directory takes no ::test part")
            return str(c.resolve().relative_to(ROOT)), c.resolve()
        if c.is_file() and c.suffix == ".py":
            return str(c.resolve().relative_to(ROOT)) + sep + rest, c.resolve().parent
    names = sorted(d.name for d in TB.iterdir() if d.is_dir() and any(d.glob("test_*.py")))
    raise ValueError(f"no test {test!r} (testbenches: {', '.join(names)})")


def gtkw_for(fst: Path) -> Path | None:
    """The save file for a build named <top>[-params]-waves, if tb/waves has one."""
    name = fst.parent.name.removesuffix("-waves")
    for cand in sorted(GTKW.glob("*.gtkw"), key=lambda p: -len(p.stem)):
        if name == cand.stem or name.startswith(cand.stem + "-"):
            return cand
    return None


def cocotb_tests(tb_dir: Path) -> list[str]:
    """The @cocotb.test functions of a testbench directory's test files."""
    pat = re.compile(r"@cocotb\.test\([^)]*\)\s*\n\s*async\s+def\s+(\w+)")
    return sorted({m for f in tb_dir.glob("test_*.py") for m in pat.findall(f.read_text())})


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    ap.add_argument("test", help="testbench dir, test file or pytest node id")
    ap.add_argument("--case", help="cocotb test name(s), comma-separated (default: all)")
    args = ap.parse_args(argv)
    if not args.test.strip():
        return fail("name the test: make waves TEST=<tb directory, test file or pytest node id>, "
                    "e.g. TEST=traverse_system")
    try:
        node, tb_dir = resolve(args.test)
    except ValueError as e:
        return fail(str(e))
    env = dict(os.environ, WAVES="1")
    if args.case:
        names = [n.strip() for n in args.case.split(",") if n.strip()]
        tests = cocotb_tests(tb_dir)
        # cocotb's filter (below) takes a test whose name ends with a given name
        none = [n for n in names if not any(t.endswith(n) for t in tests)]
        if none:
            return fail(f"--case {', '.join(none)}: no such cocotb test in {node} (tests: "
                        f"{', '.join(tests)})")
        # the filter cocotb_tools.runner builds for its own `testcase` argument
        env["COCOTB_TEST_FILTER"] = r"\.(" + "|".join(rf".*{re.escape(n)}" for n in names) + ")$"
    start = time.time()
    print(f"{PROG}: running {node} with WAVES=1"
          + (f" (cocotb tests: {args.case})" if args.case else "")
          + "; a traced build takes a few minutes the first time", flush=True)
    rc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", node],
                        cwd=ROOT, env=env).returncode
    fresh = sorted((f for f in SIM.glob("*-waves/dump.fst") if f.stat().st_mtime >= start - 1),
                   key=lambda f: f.stat().st_mtime)
    if not fresh:
        print(f"{PROG}: no FST was written (exit status {rc}); did the test reach the simulator?")
        return rc or 1
    for f in fresh:
        print(f"{PROG}: waveform {f.relative_to(ROOT)} ({f.stat().st_size / 1e6:.1f} MB)")
        g = gtkw_for(f)
        if g is not None:
            print(f"{PROG}:   view: gtkwave {f.relative_to(ROOT)} {g.relative_to(ROOT)}")
        else:
            print(f"{PROG}:   view: gtkwave {f.relative_to(ROOT)}")
    if rc != 0:
        print(f"{PROG}: the test FAILED (exit status {rc}); the waveform shows the run up to there")
    return rc


if __name__ == "__main__":
    sys.exit(main())
