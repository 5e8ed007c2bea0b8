# SPDX-License-Identifier: Apache-2.0
"""scripts/bench/soak.py: its pieces (the read recorder, the level-0-last layout, the fault
expectation, the comparison) and a small end-to-end run on the RTL harness."""
from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from model import heightmap, traverse
from tb.harness import traverse_system

ROOT = Path(__file__).resolve().parents[1]


def _load() -> ModuleType:
    spec = importlib.util.spec_from_file_location("soak", ROOT / "scripts" / "bench" / "soak.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules["soak"] = mod
    spec.loader.exec_module(mod)
    return mod


soak = _load()


def test_recorded_reads_follow_each_ray(rng: np.random.Generator) -> None:
    """The batch recorder's per-ray paths equal the model's own step record of each ray alone."""
    pyr = heightmap.build(rng.random((37, 52)) ** 3)
    rays, _ = soak.make_rays(rng, 52, 37, 120, camera_ok=False)
    for method in ("park", "park-xor", "drobot", "oh"):
        with soak.recorded_reads() as reads:
            res = traverse.trace(pyr, rays, method, "f24")
        path: dict[int, list[tuple[int, int, int]]] = {}
        for p, act in soak.read_passes(reads, res.iterations):
            k, cx, cy = reads[p]
            for j, i in enumerate(act):
                path.setdefault(int(i), []).append((int(k[j]), int(cx[j]), int(cy[j])))
        checked = 0
        for i in range(len(rays)):
            rec: list[dict] = []
            traverse.trace(pyr, rays.subset([i]), method, "f24", record=rec)
            want = [(r["level"], r["cx"], r["cy"]) for r in rec]
            assert path.get(i, []) == want, (method, i)
            checked += bool(want)
        assert checked > 60


def test_level_zero_last_layout() -> None:
    pyr = heightmap.build(np.random.default_rng(3).random((70, 90)), 16)
    lay = soak.LevelZeroLast(pyr)
    img = lay.memory_image()
    offs = lay.level_offsets()
    assert offs[pyr.n] == 0 and offs[0] == max(offs) and len(img) == lay.full_bytes()
    for k, lv in enumerate(pyr.levels):
        raw = lv.astype("<u2").tobytes()
        assert img[offs[k]:offs[k] + len(raw)] == raw
    lay.limit = 2 * soak.PAGE
    assert len(lay.memory_image()) == 2 * soak.PAGE


def test_fault_lines() -> None:
    f = soak.Faults("slverr", [(1000, 1001)], 0, 1 << 20)
    lines = np.array([960, 992, 1024, 1 << 20, (1 << 20) - 32], dtype=np.int64)
    assert soak.Faults.bad_lines(f, lines).tolist() == [False, True, False, True, False]


def _faulty_batch() -> tuple:
    """A batch with SLVERR or DECERR faults where some rays fail and others hit."""
    for index in range(40):
        b = soak.make_batch(11, index, 600, 128, 1.0)
        func = soak.Functional()
        m = soak.run_model(b, func)
        nerr = int((m.first_bad >= 0).sum())
        if 10 < nerr < len(b.rays) - 50 and m.res.hit[m.first_bad < 0].sum() > 20:
            return b, m, func
    raise AssertionError("no selective fault batch among the first 40")


def test_compare_finds_every_kind_of_difference() -> None:
    """The RTL's answer passes as it is; each corruption of it is reported."""
    b, m, func = _faulty_batch()
    out, st, error, _ = soak.run_rtl(b, True)
    assert error is None, error
    bad, counts = soak.compare(b, out, st, m, func)
    assert bad == [] and counts["err_rays"] == counts["err_expected"] > 0
    hit = np.nonzero(m.res.hit & (m.first_bad < 0))[0][0]
    failing = np.nonzero(m.first_bad >= 0)[0][0]
    clean = np.nonzero((m.first_bad < 0) & (m.res.iterations > 0))[0][0]
    # (what, field, ray, xor mask or +1 for a count)
    corruptions = [("t word", "t", hit, 1), ("v word", "v", hit, 0x10000),
                   ("hit flag", "flags", hit, traverse_system.FLAG_HIT),
                   ("iterations", "iterations", clean, None),
                   ("missing err", "flags", failing, traverse_system.FLAG_ERR),
                   ("err iterations", "iterations", failing, None),
                   ("spurious err", "flags", clean, traverse_system.FLAG_ERR),
                   ("invalid flag", "flags", clean, traverse_system.FLAG_INVALID),
                   ("id", "id", 0, 1)]
    for name, fld, i, mask in corruptions:
        o = out.copy()
        o[fld][i] = o[fld][i] + 1 if mask is None else o[fld][i] ^ mask
        got, _ = soak.compare(b, o, st, m, soak.Functional())
        assert got, f"the comparison missed a corrupted {name}"
    st2 = dict(st, rays_out=st["rays_out"] - 1)
    got, _ = soak.compare(b, out, st2, m, soak.Functional())
    assert any("rays_out" in g for g in got)


def test_small_soak_run(tmp_path: Path) -> None:
    """A few thousand rays and a few hundred fragments with faults in every batch: exit 0, the
    statistics written, the expected err rays flagged, every method's functional counts."""
    p = subprocess.run([sys.executable, str(ROOT / "scripts" / "bench" / "soak.py"), "--rays", "3000",
                        "--batch-rays", "300", "--seed", "5", "--faults", "1", "--max-side", "96",
                        "--fragments", "300", "--out", str(tmp_path), "--quiet"],
                       capture_output=True, text=True, cwd=ROOT, timeout=900)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    d = json.loads((tmp_path / "soak.json").read_text())
    assert d["rays"] == 3000 and d["batches"] == 10 and d["mismatched_rays"] == 0
    assert d["harness_failures"] == 0 and d["err_rays"] == d["err_rays_expected"] > 0
    assert set(d["per_method"]) == set(traverse.EXACT_METHODS)
    assert d["pipeline"]["fragments"] >= 300 and d["pipeline"]["mismatches"] == 0
    assert sum(d["ray_kinds"].values()) == 3000 and d["ray_kinds"]["bad-number"] > 0
