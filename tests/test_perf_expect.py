# SPDX-License-Identifier: Apache-2.0
"""Performance expectations: clocks, cache hits and bytes read of a few fixed frames and ray
batches, held to the values the design gives (tests/perf_expect.json).

Pixels equal to the model do not prove the caches work as designed: a replacement policy that
evicts the line just used keeps every pixel and raises the texture memory traffic by a third.  So
each case here runs a deterministic workload (fixed scene or seeded random map, fixed AXI
latency, no gaps, no back-pressure) through the Verilator harnesses and compares every count it
holds with the committed expectation, exactly: a change of a single clock or byte fails, and the
failure lists each quantity that moved (expected, measured, change in per cent).

- frames (tb.harness.dm_pipeline.render_rtl, the dm_pipeline harness): clocks, iterations, pixels and
  hits, height-cache hits / misses and bytes, texture requests, quad and texel hits, line misses
  and bytes;
- ray batches (tb.harness.traverse_system.trace_rtl, the traverse harness): clocks, iterations, lookups,
  crossings, descents, level-ups, hits, height-cache hits / misses and bytes.

When a change of the design moves these figures on purpose, regenerate the file and commit it
with the change (the diff shows what moved):

    PERF_EXPECT_UPDATE=1 .venv/bin/python -m pytest -q -p no:cacheprovider tests/test_perf_expect.py
    (or: make perf-expect)

The update run writes the measured values and prints what changed; it fails nothing.
"""
from __future__ import annotations

import fcntl
import json
import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

# The harness front ends (one place, to re-point should they move).
from model import heightmap
from tb.harness import dm_pipeline as pipeline_harness
from tb.harness import traverse_system as traverse_harness
from model.traverse import Rays
from tb.common import report

EXPECT = Path(__file__).resolve().parent / "perf_expect.json"
LOCK = Path(__file__).resolve().parents[1] / "build" / "perf_expect.lock"
UPDATE = os.environ.get("PERF_EXPECT_UPDATE") == "1"

#: Frames: scene, map side, view, image side, method, AXI latency (both ports).
FRAMES: dict[str, dict[str, Any]] = {
    "rocks-oblique-128": {"scene": "rocks", "map": 256, "view": "oblique", "image": 128,
                          "method": "park", "latency": 20},
    "rocks-grazing-128": {"scene": "rocks", "map": 256, "view": "grazing", "image": 128,
                          "method": "park", "latency": 20},
    "wall-front-64": {"scene": "wall", "map": 128, "view": "front", "image": 64,
                      "method": "park", "latency": 50},
}
#: Ray batches: a random map (heights u^3, seeded), random rays over it, method, AXI latency.
RAYS: dict[str, dict[str, Any]] = {
    "random256-park-4000": {"map": 256, "rays": 4000, "method": "park", "latency": 20,
                            "seed": 1},
    "random128-oh-2000": {"map": 128, "rays": 2000, "method": "oh", "latency": 50, "seed": 2},
}
FRAME_KEYS = ("cycles", "pixels", "iterations", "hits", "height_cache_hits",
              "height_cache_misses", "height_mem_bytes", "texture_requests", "texture_quad_hits",
              "texture_texel_hits", "texture_line_misses", "texture_mem_bytes")
RAY_KEYS = ("cycles", "rays", "iterations", "lookups", "crossings", "descents", "level_ups",
            "hits", "height_cache_hits", "height_cache_misses", "mem_bytes")


def measure_frame(spec: dict[str, Any]) -> dict[str, int]:
    frame, cam = pipeline_harness.scene_frame(spec["scene"], spec["map"], spec["view"],
                                              spec["image"], spec["method"])
    _, st = pipeline_harness.render_rtl(frame, cam, latency=spec["latency"], seed=0)
    return {k: int(st[k]) for k in FRAME_KEYS}


def measure_rays(spec: dict[str, Any]) -> dict[str, int]:
    rng = np.random.default_rng(spec["seed"])
    n, size = spec["rays"], spec["map"]
    pyr = heightmap.build(rng.random((size, size)) ** 3, 8)
    ang = rng.uniform(0, 2 * np.pi, n)
    ln = rng.uniform(0, size / 4, n)
    rays = Rays(rng.uniform(0, size, n), rng.uniform(0, size, n), ln * np.cos(ang),
                ln * np.sin(ang))
    _, st = traverse_harness.trace_rtl(pyr, rays, spec["method"], latency=spec["latency"],
                                       seed=0)
    return {k: int(st[k]) for k in RAY_KEYS}


def changes(expected: dict[str, int], got: dict[str, int]) -> list[str]:
    """One line per quantity that differs: expected -> measured (change in per cent)."""
    out = []
    for k in sorted(set(expected) | set(got)):
        e, g = expected.get(k), got.get(k)
        if e != g:
            pct = f" ({100.0 * (g - e) / e:+.2f}%)" if e and g is not None else ""
            out.append(f"{k}: expected {e}, measured {g}{pct}")
    return out


def update(name: str, spec: dict[str, Any], got: dict[str, int]) -> None:
    """Write one case into the expectation file (a lock: xdist workers update in parallel)."""
    LOCK.parent.mkdir(parents=True, exist_ok=True)
    with open(LOCK, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        data = json.loads(EXPECT.read_text()) if EXPECT.exists() else {}
        data.setdefault("cases", {})[name] = {"setup": spec, "expect": got}
        data["doc"] = ("Performance expectations of tests/test_perf_expect.py; regenerate with "
                       "PERF_EXPECT_UPDATE=1 (make perf-expect) when a change moves them on "
                       "purpose.")
        data["cases"] = dict(sorted(data["cases"].items()))
        EXPECT.write_text(json.dumps(data, indent=1) + "\n")


def check(name: str, spec: dict[str, Any], got: dict[str, int]) -> None:
    print(f"\nPERF {name}: " + ", ".join(f"{k} {v}" for k, v in got.items()))
    data = json.loads(EXPECT.read_text()) if EXPECT.exists() else {"cases": {}}
    case = data["cases"].get(name)
    if UPDATE:
        diff = changes(case["expect"], got) if case else ["(new case)"]
        print(f"PERF {name}: expectation written; " + ("; ".join(diff) or "unchanged"))
        update(name, spec, got)
        return
    assert case is not None, (f"{name}: no expectation in {EXPECT.name}; run with "
                              "PERF_EXPECT_UPDATE=1 to record it")
    assert case["setup"] == spec, (f"{name}: the case's setup {spec} differs from the one "
                                   f"recorded {case['setup']}; run with PERF_EXPECT_UPDATE=1")
    diff = changes(case["expect"], got)
    report.record("perf expectations", "counts vs tests/perf_expect.json", len(got), len(diff))
    assert not diff, (f"{name}: performance differs from {EXPECT.name} (regenerate with "
                      "PERF_EXPECT_UPDATE=1 only if the change is meant):\n  "
                      + "\n  ".join(diff))


@pytest.mark.xdist_group("rtl_pipeline")
@pytest.mark.parametrize("name", list(FRAMES))
def test_frame_perf(name: str) -> None:
    check(name, FRAMES[name], measure_frame(FRAMES[name]))


@pytest.mark.xdist_group("rtl_engine")
@pytest.mark.parametrize("name", list(RAYS))
def test_rays_perf(name: str) -> None:
    check(name, RAYS[name], measure_rays(RAYS[name]))


def test_changes_reports_every_difference() -> None:
    """The comparison names each quantity that moved, with its relative change (a 30% rise of
    texture bytes reads as +30.00%)."""
    e = {"cycles": 100, "texture_mem_bytes": 1000, "hits": 5}
    g = {"cycles": 100, "texture_mem_bytes": 1300, "hits": 4}
    assert changes(e, g) == ["hits: expected 5, measured 4 (-20.00%)",
                             "texture_mem_bytes: expected 1000, measured 1300 (+30.00%)"]
    assert changes(e, dict(e)) == []
