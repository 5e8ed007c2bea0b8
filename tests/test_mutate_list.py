# SPDX-License-Identifier: Apache-2.0
"""scripts/bench/mutate.py's list (scripts/bench/mutations.toml) is not stale: every pattern
matches exactly one line of the RTL, so a refactor that moves or rewrites a mutated statement
fails here, in make test, rather than in the long make mutate run.  Also the tool's own checks: a
pattern that matches nothing or several lines is refused with a one-line error (exit status 2).
"""
from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TOOL = ROOT / "scripts" / "bench" / "mutate.py"


def _tool():
    spec = importlib.util.spec_from_file_location("mutate", TOOL)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["mutate"] = mod  # (dataclasses look their module up)
    spec.loader.exec_module(mod)
    return mod


def test_every_pattern_matches_one_line() -> None:
    mt = _tool()
    muts = mt.load(mt.LIST)
    assert len(muts) >= 20
    for m in muts:
        mt.locate(m, ROOT)
        assert m.before != m.after, m.id
        for t in m.tests:  # the testbenches named exist
            assert (ROOT / t.split("::")[0]).exists(), (m.id, t)


def test_stale_or_ambiguous_pattern_is_refused(tmp_path: Path) -> None:
    mt = _tool()
    (tmp_path / "rtl").mkdir()
    (tmp_path / "rtl" / "a.sv").write_text("assign x = a & b;\nassign y = a & b;\n")
    stale = mt.Mutation("s", "k", "rtl/*.sv", "a | b", "a & b", ["tb"], "why")
    with pytest.raises(mt.ListError, match="matches nothing"):
        mt.locate(stale, tmp_path)
    twice = mt.Mutation("t", "k", "rtl/*.sv", "a & b", "a | b", ["tb"], "why")
    with pytest.raises(mt.ListError, match="matches 2 lines"):
        mt.locate(twice, tmp_path)
    twice.occurrence = 2
    mt.locate(twice, tmp_path)
    assert (twice.line, twice.after) == (2, "assign y = a | b;")
    lst = tmp_path / "list.toml"
    lst.write_text('[[mutation]]\nid = "s"\nkind = "k"\nfile = "rtl/nothing.sv"\nfind = "a"\n'
                   'replace = "b"\ntests = ["tb"]\nwhy = "w"\n')
    p = subprocess.run([sys.executable, str(TOOL), "--list", str(lst), "--check"],
                       capture_output=True, text=True)
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert "no file matches" in p.stderr
