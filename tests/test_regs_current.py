# SPDX-License-Identifier: Apache-2.0
"""The generated register files (rtl/top/pidm_regs*.sv, sw/pidm_regs.h, docs/registers.md) are
current with rtl/top/pidm_regs.rdl (scripts/flow/regs.py --check), and the check can fail."""
from __future__ import annotations

from pathlib import Path

import pytest

from scripts.flow import regs


def test_generated_register_files_are_current(capsys):
    assert regs.main(["--check"]) == 0, capsys.readouterr().out


def test_a_stale_file_is_named(tmp_path, monkeypatch, capsys):
    """A copy of the repository's generated files with one edited: the check names that file."""
    for o in regs.OUTPUTS:
        dst = tmp_path / o.path
        dst.parent.mkdir(parents=True, exist_ok=True)
        dst.write_bytes((regs.ROOT / o.path).read_bytes())
    stale = tmp_path / "sw/pidm_regs.h"
    stale.write_text(stale.read_text() + "\n")
    real_root = regs.ROOT
    monkeypatch.setattr(regs, "ROOT", tmp_path)
    # PeakRDL still reads the .rdl file of the real repository (run from its root).
    monkeypatch.setattr(regs, "generate", lambda out, _g=regs.generate: _run_in(real_root, _g, out))
    assert regs.check() == 1
    assert capsys.readouterr().out.strip() == "regs: sw/pidm_regs.h is stale (run make regs)"


def _run_in(root: Path, gen, out: Path) -> None:
    """Run ``gen(out)`` with regs.ROOT set to ``root``."""
    saved = regs.ROOT
    regs.ROOT = root
    try:
        gen(out)
    finally:
        regs.ROOT = saved


def test_bad_rdl_is_one_line_exit_2(tmp_path, monkeypatch, capsys):
    (tmp_path / "rtl/top").mkdir(parents=True)
    (tmp_path / "rtl/top/pidm_regs.rdl").write_text("addrmap pidm_regs { reg { field {} f; } R; ")
    monkeypatch.setattr(regs, "ROOT", tmp_path)
    with pytest.raises(SystemExit) as e:
        regs.main(["--check"])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("regs.py: error:")
