# SPDX-License-Identifier: Apache-2.0
"""model/relief_texture.py: Oliveira's pre-warp (against a literal per-texel loop, the 3-D
geometry and the exact ray caster), zero depth = plain texture mapping, and the serial /
pipelined / split-image variants giving identical frames; scripts/relief_texture.py's errors.
"""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from model import heightmap, traverse
from model import relief_texture as R
from model.camera import Camera

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "scripts" / "relief_texture.py"


# ---- an independent, literal serial warp --------------------------------------------------------

def warp_lines_loop(colour: np.ndarray, depth: np.ndarray, valid: np.ndarray, k: float,
                    k3: float, reverse: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Oliveira's 1-D warp as a plain loop: per line, the segments from both ends towards the
    epipole (``reverse``: away from it, the wrong order), the straddling one last; each writes
    the target pixels between its warped ends (both included) unless it folds back."""
    nl, ns = depth.shape
    oc = np.zeros(colour.shape, np.float32)
    od = np.zeros(depth.shape)
    ov = np.zeros(depth.shape, bool)
    e = k / k3 - 0.5
    for r in range(nl):
        q = [(j + 0.5 + k * depth[r, j]) / (1.0 + k3 * depth[r, j]) - 0.5 for j in range(ns)]
        left = [(j, j + 1) for j in range(ns - 1) if j + 1 <= e]
        right = [(j + 1, j) for j in range(ns - 2, -1, -1) if j >= e]
        mid = [(j, j + 1) for j in range(ns - 1) if j < e < j + 1]
        order = left + right + mid
        if reverse:
            order = [(b, a) for a, b in reversed(order)]
        for a, b in order:
            if not (valid[r, a] and valid[r, b]):
                continue
            if (b > a and q[b] < q[a]) or (b < a and q[b] > q[a]):
                continue                                   # folds back: a hidden surface
            lo = max(math.ceil(min(q[a], q[b])), 0)
            hi = min(math.floor(max(q[a], q[b])), ns - 1)
            for x in range(lo, hi + 1):
                den = q[b] - q[a]
                w = (x - q[a]) / den if den != 0 else 0.0
                w32 = np.float32(w)
                oc[r, x] = (np.float32(1) - w32) * colour[r, a] + w32 * colour[r, b]
                od[r, x] = (1 - w) * depth[r, a] + w * depth[r, b]
                ov[r, x] = True
    return oc, od, ov


def prewarp_loop(rt: R.ReliefTexture, pw: R.Prewarp, reverse: bool = False) -> R.Warped:
    c1, d1, v1 = warp_lines_loop(rt.colour, rt.depth, rt.valid, pw.k1, pw.k3, reverse)
    c2, d2, v2 = warp_lines_loop(np.ascontiguousarray(c1.transpose(1, 0, 2)), d1.T.copy(),
                                 v1.T.copy(), pw.k2, pw.k3, reverse)
    return R.Warped(c2.transpose(1, 0, 2), d2.T, v2.T)


def coordinate_agreement(rt: R.ReliefTexture, cam: Camera, reverse: bool | None = None) -> float:
    """Share of covered pixels where relief texture mapping shows the texel the exact ray
    caster hits, within one texel (or both show nothing).

    The colour of texel (i, j) is its own centre (j + 0.5, i + 0.5), so the pre-warp's linear
    interpolation yields a texture coordinate; the ray caster is the pyramidal traversal of the
    box height field (f64).  ``reverse`` warps with the literal loop, in the wrong order if True.
    """
    hh, ww = rt.depth.shape
    jj, ii = np.meshgrid(np.arange(ww) + 0.5, np.arange(hh) + 0.5)
    crt = R.ReliefTexture(np.stack([jj, ii, np.zeros_like(jj)], -1).astype(np.float32),
                          rt.depth, rt.valid, rt.depth_scale)
    v = R.make_view(cam, crt)
    w = R.prewarp(crt, v.pw) if reverse is None else prewarp_loop(crt, v.pw, reverse)
    est, shown = w.colour.reshape(-1, 3)[v.texel], w.valid.ravel()[v.texel]
    cr = cam.rays()                       # the same covered pixels, in the same order
    assert np.array_equal(cr.row * cam.image_w + cr.col, v.pixel)
    res = traverse.trace(heightmap.build(1.0 - rt.depth, 16), cr.rays, "park", "f64")
    with np.errstate(invalid="ignore"):
        close = np.hypot(est[:, 0] - res.u, est[:, 1] - res.v) <= 1.0
    return float(np.mean((shown & res.hit & close) | (~shown & ~res.hit)))


# ---- tests --------------------------------------------------------------------------------------

def test_vectorised_warp_equals_literal_loop(rng: np.random.Generator) -> None:
    for _ in range(60):
        nl, ns = int(rng.integers(1, 6)), int(rng.integers(2, 40))
        col = rng.random((nl, ns, 3)).astype(np.float32)
        dep = rng.random((nl, ns)) * float(rng.choice([0.0, 0.05, 1.0, 3.0]))
        if rng.random() < 0.3:
            dep = np.round(dep * 4) / 4                    # plateaus and steps
        val = rng.random((nl, ns)) > float(rng.choice([0.0, 0.2]))
        k3 = float(rng.uniform(0.005, 2.0))
        e = float(rng.choice([rng.uniform(-10, ns + 10), float(rng.integers(0, ns)) + 0.5]))
        w = R.warp_lines(col, dep, val, k3 * e, k3)
        oc, od, ov = warp_lines_loop(col, dep, val, k3 * e, k3)
        assert np.array_equal(w.valid, ov)
        assert np.array_equal(w.colour, oc)
        assert np.array_equal(w.depth, od)


def test_prewarp_equals_loop_on_a_scene() -> None:
    rt = R.scene_relief("four-shapes", 40, invalid_floor=True)
    for v in R.orbit(rt, 3, 48, elevation=35.0):
        a, b = R.prewarp(rt, v.pw), prewarp_loop(rt, v.pw)
        assert np.array_equal(a.valid, b.valid)
        assert np.array_equal(a.colour, b.colour)


def test_constants_put_texels_on_their_eye_rays(rng: np.random.Generator) -> None:
    """Oliveira's vector form equals the closed form, and every pre-warped point lies on the
    line from the eye through the texel's 3-D point (where that line meets the polygon)."""
    for _ in range(20):
        eye = np.array([rng.uniform(-300, 300), rng.uniform(-300, 300), rng.uniform(1, 400)])
        d_scale = float(rng.uniform(1, 50))
        pw = R.prewarp_constants(eye, d_scale)
        assert pw.k1 == pytest.approx(d_scale * eye[0] / eye[2])
        assert pw.k2 == pytest.approx(d_scale * eye[1] / eye[2])
        assert pw.k3 == pytest.approx(d_scale / eye[2])
        assert pw.epipole == pytest.approx((eye[0], eye[1]))
        us, vs, d = rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 1)
        ui = (us + pw.k1 * d) / (1 + pw.k3 * d)
        vi = (vs + pw.k2 * d) / (1 + pw.k3 * d)
        x = np.array([us, vs, -d_scale * d])
        p = np.array([ui, vi, 0.0])
        assert np.linalg.norm(np.cross(x - eye, p - eye)) <= 1e-9 * np.linalg.norm(x - eye) ** 2
    with pytest.raises(ValueError):
        R.prewarp_constants([0.0, 0.0, -1.0], 4.0)


def test_zero_depth_is_plain_texture_mapping() -> None:
    rt = R.scene_relief("saints", 64)
    flat = R.ReliefTexture(rt.colour, np.zeros_like(rt.depth), rt.valid, rt.depth_scale)
    for v in R.orbit(flat, 4, 80, elevation=30.0):
        pw = R.prewarp(flat, v.pw)
        assert pw.valid.all() and np.array_equal(pw.colour, flat.colour)
        assert np.array_equal(R.render(flat, v), R.plain_texture_map(flat, v))
    # and with depth the pre-warp does move texels (the test above is not vacuous)
    v = R.orbit(rt, 1, 80, elevation=30.0)[0]
    assert not np.array_equal(R.render(rt, v), R.plain_texture_map(rt, v))


@pytest.mark.parametrize("name,floor", [("bump", 0.97), ("dent", 0.97), ("four-shapes", 0.9),
                                        ("stones", 0.8)])
def test_agrees_with_exact_ray_cast_and_order_matters(name: str, floor: float) -> None:
    """Relief texture mapping shows the texel the exact ray caster hits on most pixels (the
    rest: reconstruction -- linear between texel centres against the box field's vertical
    walls -- and the two-pass factorisation); where texels occlude each other, processing away
    from the epipole (the wrong order) lets hidden texels win and agrees clearly less."""
    rt = R.scene_relief(name, 64)
    cam = Camera.for_view(30.0, 64, 64, 96, 96, depth_scale=rt.depth_scale)
    good = coordinate_agreement(rt, cam)
    assert good >= floor
    assert coordinate_agreement(rt, cam, reverse=False) == good     # the loop agrees too
    if name in ("four-shapes", "stones"):
        assert good > coordinate_agreement(rt, cam, reverse=True) + 0.05


def test_variants_give_identical_frames() -> None:
    rt = R.scene_relief("stones", 48)
    views = R.orbit(rt, 4, 56, elevation=40.0)
    runs = [R.render_frames(rt, views, "serial"),
            R.render_frames(rt, views, "pipelined", backend="thread"),
            R.render_frames(rt, views, "split", backend="thread", workers=3),
            R.render_frames(rt, views, "pipelined", backend="process"),
            R.render_frames(rt, views, "split", backend="process", workers=2)]
    assert R.frames_identical(runs)
    assert all(len(r.images) == 4 and len(r.done) == 4 and r.fps > 0 for r in runs)
    # frames differ from each other (the camera moves), so equality is not trivial
    assert not np.array_equal(runs[0].images[0], runs[0].images[1])
    ar = R.render_async(rt, views, "thread")
    assert ar.warps == 3 and ar.draws >= 1


def test_bad_parameters() -> None:
    rt = R.scene_relief("bump", 16)
    with pytest.raises(ValueError):
        R.render_frames(rt, [], "sideways")
    with pytest.raises(ValueError):
        R.render_frames(rt, [], "split", backend="gpu")
    with pytest.raises(ValueError):
        R.render_frames(rt, [], "split", workers=0)
    with pytest.raises(ValueError):
        R.ReliefTexture.from_heights(np.zeros((1, 5)), np.zeros((1, 5, 3)), 4.0)
    with pytest.raises(ValueError):
        R.ReliefTexture.from_heights(np.zeros((4, 4)), np.zeros((4, 5, 3)), 4.0)


def run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)


@pytest.mark.parametrize("args", [
    ["--samples", "nosuch"], ["--frames", "0"], ["--backends", "gpu"], ["--size", "x"],
    ["--elevation", "95"], ["--workers", "-1"], ["--bogus"]])
def test_script_bad_args_exit_2(args: list[str], tmp_path: Path) -> None:
    p = run(*args, "--out", str(tmp_path))
    assert p.returncode == 2
    assert len(p.stderr.strip().splitlines()) == 1 and "Traceback" not in p.stderr


def test_script_quick_run(tmp_path: Path) -> None:
    p = run("--samples", "four-shapes", "--size", "32", "--image", "32", "--frames", "3",
            "--repeats", "1", "--backends", "thread", "--out", str(tmp_path), "--quiet")
    assert p.returncode == 0, p.stderr
    doc = json.loads((tmp_path / "relief_texture.json").read_text())
    s = doc["samples"]["four-shapes"]
    assert s["identical_images"] is True
    assert s["invalid_texels"] > 0
    assert set(s["variants"]) == {"serial", "pipelined-thread", "split-thread", "async-thread"}
    assert all(v.get("fps_median", 1) > 0 for v in s["variants"].values())
    for f in ("four-shapes_frame0.png", "four-shapes_raycast.png", "relief_texture.md"):
        assert (tmp_path / f).is_file()
