# SPDX-License-Identifier: Apache-2.0
"""scripts/bench/study.py: the quick run writes its three files with plausible numbers; bad arguments
end in one line and exit status 2."""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
STUDY = ROOT / "scripts" / "bench" / "study.py"
EXACT = ("oh", "tevs", "drobot", "start-level", "multi-down", "selective", "coherent", "park",
         "park-gpu", "park-xor")


def run(*args: str, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, str(STUDY), *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=timeout)


@pytest.fixture(scope="module")
def quick(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict, str]:
    out = tmp_path_factory.mktemp("study")
    p = run("--quick", "--quiet", "--out", str(out))
    assert p.returncode == 0, p.stderr
    return out, json.loads((out / "study.json").read_text()), p.stdout


def finite(x: object) -> bool:
    return isinstance(x, (int, float)) and math.isfinite(x)


def test_files(quick: tuple[Path, dict, str]) -> None:
    out, _, stdout = quick
    for name in ("study.md", "study.json", "study.png"):
        assert (out / name).is_file() and (out / name).stat().st_size > 0, name
    assert (out / "study.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    md = (out / "study.md").read_text()
    for title in ("Table 2", "Table 3", "Table 4", "Reduction", "Approximate", "f24 against f64"):
        assert title in md, title
    assert "mean iterations per pixel" in stdout and "study.md" in stdout


def test_keys(quick: tuple[Path, dict, str]) -> None:
    _, d, _ = quick
    for key in ("config", "paper", "rays", "table2", "table2_mean_p_cross", "table3", "table4",
                "table4_mean", "reduction", "reduction_range", "approx", "approx_mean",
                "engine", "engine_summary"):
        assert key in d, key
    cfg = d["config"]
    assert cfg["quick"] and cfg["engine"] == "f64"
    assert cfg["angles"] == ["front", "oblique", "grazing"]
    assert set(cfg["methods"]) >= set(EXACT)
    for s in cfg["scenes"]:
        for a in cfg["angles"]:
            assert d["rays"][s][a] > 100
            assert set(d["table4"][s][a]) >= set(EXACT)
            assert set(d["table3"][s][a]) == {"1", "2", "3", "4"}
    assert d["capped_rays"] == 0


def test_park_beats_oh(quick: tuple[Path, dict, str]) -> None:
    _, d, _ = quick
    for a, row in d["table4_mean"].items():
        assert 1.0 <= row["park"] < row["oh"], (a, row)
        assert row["park-xor"] <= row["park"] + 0.05, (a, row)
    # Table 3: n = 1 is oh and n = 2 is multi-down, exactly
    for s, by_angle in d["table3"].items():
        for a, t3 in by_angle.items():
            assert t3["1"] == d["table4"][s][a]["oh"]
            assert t3["2"] == d["table4"][s][a]["multi-down"]
    for k, v in d["reduction_of_means"].items():
        assert 0 < v["park_vs_oh"] < 100, k


def test_probabilities(quick: tuple[Path, dict, str]) -> None:
    _, d, _ = quick
    for s, by_angle in d["table2"].items():
        for a, by_method in by_angle.items():
            for m, f in by_method.items():
                parts = [f[k] for k in ("down", "cross", "hit", "miss")]
                assert all(0.0 <= p <= 1.0 for p in parts), (s, a, m, f)
                assert abs(sum(parts) - 1.0) < 1e-9, (s, a, m, f)
                assert abs(f["p_cross"] + f["p_down"] + f["p_end"] - 1.0) < 1e-9
                if m in ("oh", "start-level", "multi-down"):
                    assert f["level_up_per_cross"] == 0.0
            assert by_method["drobot"]["level_up_per_cross"] <= 1.0
    # crossings get more frequent as the view gets flatter (Table 2's trend)
    p = d["table2_mean_p_cross"]
    assert p["front"]["oh"] < p["oblique"]["oh"] < p["grazing"]["oh"]


def test_approx_and_engines(quick: tuple[Path, dict, str]) -> None:
    _, d, _ = quick
    names = d["config"]["approx_methods"]
    for a, rows in d["approx_mean"].items():
        for n in names:
            r = rows[n]
            if "error" in r:
                continue
            assert 0 <= r["texel_differs_pct"] <= 100 and finite(r["mean_abs_dt"])
            assert 0 <= r["mean_abs_dt"] <= r["max_abs_dt"] <= 1
            assert r["iterations"] >= 1
    for m, v in d["engine_summary"].items():
        assert 90.0 <= v["min_texel_agree_pct"] <= 100.0, m


@pytest.mark.parametrize("args", [
    ["--scenes", "nope"],
    ["--angles", "sideways"],
    ["--angles", "95"],
    ["--engine", "rtl"],
    ["--size", "0"],
    ["--image-size", "x"],
    ["--bogus"],
])
def test_bad_arguments(args: list[str], tmp_path: Path) -> None:
    p = run("--quick", "--out", str(tmp_path / "o"), *args, timeout=60)
    assert p.returncode == 2, p
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "error" in lines[0] and "Traceback" not in p.stderr, p.stderr
    assert not (tmp_path / "o" / "study.json").exists()


def test_out_is_a_file(tmp_path: Path) -> None:
    f = tmp_path / "file"
    f.write_text("x")
    p = run("--quick", "--out", str(f), timeout=60)
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1


def test_counts_match_the_record_hook() -> None:
    """The study's action counts equal those of trace()'s per-iteration record, ray by ray."""
    import importlib.util

    from model import camera, heightmap, scenes, traverse

    spec = importlib.util.spec_from_file_location("study", STUDY)
    assert spec and spec.loader
    study = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(study)
    counted = study.Counted()
    pyr = heightmap.build(scenes.load_scene("rocks", 64).heights)
    rays = camera.Camera.for_view("grazing", 64, 64, 32, 32).rays().rays
    rays = rays.subset(np.arange(0, len(rays), max(1, len(rays) // 40)))
    for name in ("oh", "tevs", "park", "park-xor"):
        m = traverse.METHODS[name]
        _, got = counted(pyr, rays, m, "f64")
        want = dict.fromkeys(("down", "cross", "up", "hit", "miss"), 0)
        for i in range(len(rays)):
            rec: list[dict] = []
            traverse.trace(pyr, rays.subset([i]), name, "f64", record=rec)
            for r in rec:
                a = r["action"]
                want["cross" if a.startswith("cross") else a] += 1
                want["up"] += a == "cross-up"
        assert got == want, name
