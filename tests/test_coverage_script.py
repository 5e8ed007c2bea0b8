# SPDX-License-Identifier: Apache-2.0
"""scripts/bench/coverage.py's reading, merging and per-module figures, and the runner's coverage
options (the coverage run itself is `make coverage`, not part of make test)."""
from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import pytest

from tb.common import runner

ROOT = Path(__file__).resolve().parents[1]


def _load() -> ModuleType:
    spec = importlib.util.spec_from_file_location("coverage_script",
                                                  ROOT / "scripts" / "bench" / "coverage.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["coverage_script"] = mod
    spec.loader.exec_module(mod)
    return mod


cov = _load()


def key(f: str, line: int, page: str, o: str, h: str) -> str:
    return (f"\x01f\x02{f}\x01l\x02{line}\x01n\x021\x01t\x02x\x01page\x02{page}\x01o\x02{o}"
            f"\x01h\x02{h}")


def write(path: Path, points: dict[str, int]) -> Path:
    cov.write_dat(path, points)
    return path


def test_merge_and_per_module(tmp_path: Path) -> None:
    fifo = str(ROOT / "rtl" / "traverse" / "traverse_fifo.sv")
    tb = str(ROOT / "tb" / "pipe_credit" / "pipe_credit_tb.sv")
    a = write(tmp_path / "a.dat", {
        key(fifo, 10, "v_line/traverse_fifo", "block", "TOP.u0"): 3,
        key(fifo, 11, "v_branch/traverse_fifo", "if", "TOP.u0"): 0,
        key(fifo, 12, "v_toggle/traverse_fifo", "x[0]:0->1", "TOP.u0"): 0,
        key(fifo, 12, "v_toggle/traverse_fifo", "x[0]:1->0", "TOP.u0"): 0,
        key(tb, 5, "v_line/pipe_credit_tb", "block", "TOP"): 0})
    b = write(tmp_path / "b.dat", {
        key(fifo, 10, "v_line/traverse_fifo", "block", "TOP.u0"): 2,
        # another instance, of a parameterised copy (its page names it), covers the branch and
        # one toggle direction
        key(fifo, 11, "v_branch/traverse_fifo__W7", "if", "TOP.u1"): 1,
        key(fifo, 12, "v_toggle/traverse_fifo__W7", "x[0]:0->1", "TOP.u1"): 7})
    merged = cov.merge([a, b])
    assert merged[key(fifo, 10, "v_line/traverse_fifo", "block", "TOP.u0")] == 5
    assert cov.read_dat(write(tmp_path / "m.dat", merged)) == merged
    mods = cov.per_module(merged)
    assert set(mods) == {"traverse_fifo"}  # testbench files are left out
    m = mods["traverse_fifo"]
    assert (m.line_points, m.line_covered) == (2, 2)   # union over the instances
    assert (m.toggle_points, m.toggle_covered) == (2, 1)
    assert dict(m.untoggled) == {"x": 1}


def test_unreadable_files(tmp_path: Path) -> None:
    (tmp_path / "x.dat").write_text("not a coverage file\n")
    with pytest.raises(cov.CoverageError):
        cov.read_dat(tmp_path / "x.dat")
    (tmp_path / "y.dat").write_text(cov.HEADER + "\nC 'broken\n")
    with pytest.raises(cov.CoverageError):
        cov.read_dat(tmp_path / "y.dat")


def test_group_targets() -> None:
    m = cov.ModuleCoverage("traverse_loop", "rtl/traverse/traverse_loop.sv", 100, 96, 10, 7)
    n = cov.ModuleCoverage("traverse_addr", "rtl/traverse/traverse_addr.sv", 0, 0, 10, 9)
    doc, md = cov.report({"traverse_loop": m, "traverse_addr": n}, [], {"summary": "t"}, None)
    g = doc["groups"][0]
    assert g["line_pct"] == 96.0 and g["toggle_pct"] == 80.0
    assert g["line_met"] and g["toggle_met"]
    per = {p["module"]: p for p in g["per_module"]}
    assert not per["traverse_loop"]["toggle_met"] and per["traverse_addr"]["line_met"]
    assert not g["all_modules_met"]  # the other traverse modules were not simulated
    assert "not simulated" in md


def test_runner_coverage_options(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setenv("COVERAGE", "1")
    monkeypatch.delenv("WAVES", raising=False)
    monkeypatch.setenv("COVERAGE_DIR", str(tmp_path))
    assert runner.coverage_enabled()
    assert set(runner.COVERAGE_ARGS) <= set(runner.verilator_args(False, True))
    assert not set(runner.COVERAGE_ARGS) & set(runner.verilator_args(False, False))
    f1 = runner.coverage_file("x-W8", "test_x", None, {"A": "1"})
    f2 = runner.coverage_file("x-W8", "test_x", None, {"A": "2"})
    assert f1.parent == tmp_path and f1 != f2 and f1.name.startswith("x-W8-")
    monkeypatch.setenv("WAVES", "1")
    assert not runner.coverage_enabled()
