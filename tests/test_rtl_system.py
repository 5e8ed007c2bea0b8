# SPDX-License-Identifier: Apache-2.0
"""The system top as a renderer (tb/harness/pidm_system.py: rtl/top/pidm_top.sv in the Verilator
harness tb/harness/system_harness.cpp, which writes the registers as the CPU and serves the four
AXI ports as the memory) and ``scripts/render.py --engine rtl --top system`` (``make render
TOP=system``).

Small frames read back from the framebuffer and the status buffer must equal the model
(``model.shade.render`` with the f24 engine) bit for bit and equal the pipeline top's pixels
(tb/harness/dm_pipeline.py), under fixed and random AXI latency; render.py's statistics say
``identical`` and ``top``; a frame whose pixel ids do not fit is a one-line error.

The harness variant is ``checked`` (the RTL's assertions on, bound checkers included) under the
test suite's ``RTL_ENGINE_CHECKED=1``; its build (a few minutes, cached in
build/harness/system/) happens once.  Every test here runs on one xdist worker.
"""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from model import camera, heightmap, scenes, shade, texture
from tb.common import report
from tb.harness import dm_pipeline, pidm_system

ROOT = Path(__file__).resolve().parents[1]
RENDER = ROOT / "scripts" / "render.py"

pytestmark = pytest.mark.xdist_group("rtl_system")


@pytest.fixture(scope="module")
def harness() -> Path:
    return pidm_system.build(dm_pipeline.default_variant())


def make_frame(name: str, size: int, angle: str, image: int, method: str
               ) -> tuple[shade.Frame, camera.Camera]:
    sc = scenes.load_scene(name, size)
    tex = texture.build(sc.texture)
    ntex = texture.build(scenes.encode_normals(sc.normals))
    cam = camera.Camera.for_view(angle, size, size, image, image, depth_scale=sc.depth_scale)
    frame = shade.Frame(pyr=heightmap.build(sc.heights), colour=tex, normals=ntex,
                        depth_scale=sc.depth_scale,
                        log2pb_colour=cam.log2_pb(tex.width, tex.height),
                        log2pb_normal=cam.log2_pb(ntex.width, ntex.height),
                        method=method, engine="f24", mip=True)
    return frame, cam


@pytest.mark.parametrize("case,latency", [
    (("rocks", 64, "oblique", 40, "park"), 20),
    (("bump", 32, "grazing", 24, "park-xor"), (1, 60)),
    (("four-shapes", 32, "front", 20, "oh"), (5, 30)),
])
def test_system_equals_model_and_pipeline(harness: Path, case: tuple, latency) -> None:
    frame, cam = make_frame(*case)
    ref = shade.render(frame, cam)
    img, st = pidm_system.render_rtl(frame, cam, latency=latency, seed=3)
    bad = dm_pipeline.compare(img.out, ref.out)
    report.record("pidm_top (system harness)", "pixels vs model.shade f24", len(ref.frags),
                  len(bad))
    assert len(bad) == 0, f"{case}: {len(bad)} pixels differ from the model"
    assert np.array_equal(img.rgb, ref.rgb), f"{case}: the framebuffer differs from the image"
    pipe, _ = dm_pipeline.render_rtl(frame, cam, latency=latency, seed=3)
    assert len(dm_pipeline.compare(img.out, pipe.out)) == 0, \
        f"{case}: the system top's pixels differ from the pipeline top's"
    assert st["pixels"] == len(ref.frags) and st["errors"] == 0
    assert st["iterations"] == int(ref.out.iterations.sum())
    assert 0 < st["height_cache_hit_rate"] <= 1 and st["mem_bytes"] > 0
    assert 0 < st["busy_cycles"] <= st["cycles"]   # clocks with a pixel inside, within the frame


def test_render_top_system(harness: Path, tmp_path: Path) -> None:
    stats = tmp_path / "s.json"
    p = subprocess.run([sys.executable, str(RENDER), "--scene", "rocks", "--map-size", "32",
                        "--size", "24", "--engine", "rtl", "--top", "system", "--quiet",
                        "--out", str(tmp_path / "r.png"), "--model-out", str(tmp_path / "m.png"),
                        "--stats", str(stats)], capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    st = json.loads(stats.read_text())
    assert st["identical"] is True and st["top"] == "system" and st["pixels"] > 0


def test_top_needs_rtl_engine(tmp_path: Path) -> None:
    p = subprocess.run([sys.executable, str(RENDER), "--scene", "rocks", "--size", "8",
                        "--top", "system", "--out", str(tmp_path / "r.png")],
                       capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert "--top" in p.stderr
