# SPDX-License-Identifier: Apache-2.0
"""scripts/animate.py (make animate): a tiny animation through pyr_build and the pipeline RTL.

Needs Verilator (builds the pyr_build simulation and the pipeline harness on first use).  Checks:
every frame identical, the stats' shape, a dirty rectangle after frame 0; a corrupted built
pyramid is caught (the render reads the builder's bytes, so a wrong byte cannot pass); usage
errors exit 2 with one line.  ``--top system``: the same loop through pidm_top (the builder and
the frame started through its registers, tb/harness/pidm_system.py): every frame identical, the
same statistics, a corrupted read-back caught.
"""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from scripts import animate
from tb.harness import pidm_system, pyr_run

pytestmark = pytest.mark.skipif(shutil.which("verilator") is None, reason="needs Verilator")

KEYS = {"pyramid_cycles", "pyramid_bound_cycles", "render_cycles", "identical", "dirty_rect"}


def run(tmp: Path, *extra: str) -> tuple[int, dict]:
    rc = animate.main(["--frames", "3", "--map-size", "32", "--image", "24", "--out", str(tmp),
                       *extra])
    return rc, json.loads((tmp / "stats.json").read_text())


@pytest.mark.parametrize("motion", ["dent"])
def test_animate_identical(tmp_path: Path, motion: str) -> None:
    rc, st = run(tmp_path, "--motion", motion)
    assert rc == 0 and st["identical"] is True and st["frames"] == 3
    assert len(st["per_frame"]) == 3
    for k, p in enumerate(st["per_frame"]):
        assert KEYS <= set(p), p
        assert p["identical"] is True and p["render_cycles"] > 0
        assert p["pyramid_bound_cycles"] == 128       # 32x32 unorm8 on a 64-bit bus
        assert (tmp_path / f"frame_{k:03d}.png").is_file()
    assert st["per_frame"][0]["dirty_rect"] == [0, 0, 31, 31]
    assert st["per_frame"][0]["pyramid_cycles"] > 0
    r1 = st["per_frame"][1]["dirty_rect"]
    assert r1 is not None and r1 != [0, 0, 31, 31]    # the dent: a rebuild of a part of the map
    assert (tmp_path / "animation.gif").is_file()


def test_animate_catches_a_wrong_pyramid(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    real = pyr_run.run_builds

    def corrupt(*args, **kw):  # type: ignore[no-untyped-def]
        r = real(*args, **kw)
        img = bytearray(r.images[1])
        img[1024] ^= 0xFF                    # level 1's first texel of a 32x32 map
        return pyr_run.BuildResult([r.images[0], bytes(img), *r.images[2:]], r.clocks, r.rects)

    monkeypatch.setattr(pyr_run, "run_builds", corrupt)
    rc, st = run(tmp_path, "--frames", "2", "--motion", "dent")
    assert rc == 1 and st["identical"] is False
    assert st["per_frame"][0]["identical"] is True
    assert st["per_frame"][1]["pyramid_identical"] is False


def test_animate_system(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rc, st = run(tmp_path, "--motion", "dent", "--top", "system")
    assert rc == 0 and st["identical"] is True and len(st["per_frame"]) == 3
    for p in st["per_frame"]:
        assert KEYS <= set(p), p
        assert p["identical"] is True and p["render_cycles"] > 0 and p["pyramid_cycles"] > 0
    assert st["per_frame"][0]["dirty_rect"] == [0, 0, 31, 31]
    assert st["per_frame"][1]["dirty_rect"] not in (None, [0, 0, 31, 31])
    real = pidm_system.build_and_render

    def corrupt(*args, **kw):  # type: ignore[no-untyped-def]
        img, stats, heights = real(*args, **kw)
        h = bytearray(heights)
        h[1024] ^= 0xFF                      # level 1's first texel of a 32x32 map
        return img, stats, bytes(h)

    monkeypatch.setattr(pidm_system, "build_and_render", corrupt)
    rc, st = run(tmp_path / "bad", "--frames", "1", "--motion", "dent", "--top", "system")
    assert rc == 1 and st["per_frame"][0]["pyramid_identical"] is False


def test_animate_usage_errors(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    for args in (["--frames", "0"], ["--map-size", "1"], ["--motion", "wave"]):
        with pytest.raises(SystemExit) as e:
            animate.main([*args, "--out", str(tmp_path)])
        assert e.value.code == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and err.startswith("animate: error:")
