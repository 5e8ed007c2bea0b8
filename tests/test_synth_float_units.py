# SPDX-License-Identifier: Apache-2.0
"""`scripts/flow/synth.py --float-units` on the real design: Yosys (yowasp, slang front end)
elaborates the FPGA top with its hierarchy kept (a few seconds, no synthesis) and the float units
of every block are counted into report.json and report.md.  The counts of the tree walk are
checked against a second count from the instance paths Yosys gives the modules."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from scripts.flow import synth

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def out() -> Path:
    """An output directory inside the repository (the WASI tools see only it)."""
    d = ROOT / "out" / f"test_float_units_{os.getpid()}"
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    yield d
    shutil.rmtree(d, ignore_errors=True)


def by_paths(stat: dict) -> dict[str, dict[str, int]]:
    """Float units per block from the module names alone: yosys-slang names each instance's module
    `<module>$<instance path>`, so a unit lies inside a block when its path extends the block's."""
    names = [m.lstrip("\\").partition("$") for m in stat["modules"]]
    counts: dict[str, dict[str, int]] = {}
    for kind, _, path in names:
        if kind not in synth.FLOAT_BLOCKS or not path:
            continue
        row = counts.setdefault(kind, {u: 0 for u in synth.FLOAT_UNITS})
        for u, _, p in names:
            if u in synth.FLOAT_UNITS and p.startswith(path + "."):
                row[u] += 1
    return counts


def test_float_units_of_the_design(out: Path) -> None:
    # an earlier report's figures and settings stay; only float_units is (re)written
    (out / "report.json").write_text(json.dumps({
        "date": "2026-01-01T00:00:00", "top": synth.TOP,
        "settings": {"yosys": "Y", "nextpnr": "N", "device_name": "LFE5U-45F", "speed": 8,
                     "package": "CABGA756", "target_mhz": 100.0,
                     "lpf": "constraints/dm_pipeline.lpf", "seed": 7},
        "blocks": {"f24_add": {"lut": 10, "ff": 5, "dsp": 0, "bram": 0, "what": "add"}},
        "xilinx": {}, "pnr": {}, "seconds": {}}))
    p = subprocess.run([sys.executable, "scripts/flow/synth.py", "--float-units",
                        "--out", str(out)], cwd=ROOT, capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    rep = json.loads((out / "report.json").read_text())
    assert rep["settings"]["seed"] == 7 and rep["blocks"]["f24_add"]["lut"] == 10
    fu = rep["float_units"]
    blocks = fu["blocks"]
    assert list(blocks) == synth.FLOAT_BLOCKS      # every block, once, below the top
    assert all(b["instances"] == 1 for b in blocks.values())
    # the second count, from the instance paths of the same elaboration
    stat = json.loads((out / "logs" / "inventory.stat.json").read_text())
    paths = by_paths(stat)
    for name, row in blocks.items():
        assert {u: row[u] for u in synth.FLOAT_UNITS} == paths[name], name
    # the traverse unit is its two modes; the whole unit holds every block's units
    for u in synth.FLOAT_UNITS:
        assert blocks["traverse_unit"][u] == (blocks["traverse_setup"][u]
                                              + blocks["traverse_loop"][u])
        assert blocks["dm_pipeline"][u] >= sum(fu["paper_rows"][r][u] for r in synth.PAPER_ROWS)
    assert min(blocks["dm_pipeline"][u] for u in ("f24_add", "f24_mul", "f24_div")) > 0
    md = (out / "report.md").read_text()
    row = blocks["view_calc"]
    assert ("| `view_calc` | 1 | " + " | ".join(str(row[u]) for u in synth.FLOAT_UNITS) + " |"
            in md)
    assert "| Total | 8 / 2 / 7 / 12 / 4 / 1 |" in md and "| `f24_add` | add | 10 |" in md
    # docs/synthesis.md shows the tables as generated (copy them from report.md when they move)
    doc = (ROOT / "docs" / "synthesis.md").read_text()
    tables = [ln for ln in md.split("## Float units per block", 1)[1].split("\n## ", 1)[0]
              .splitlines() if ln.startswith("|")]
    missing = [ln for ln in tables if ln not in doc]
    assert not missing, f"docs/synthesis.md lacks the generated rows {missing}"
