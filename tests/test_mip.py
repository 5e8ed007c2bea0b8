# SPDX-License-Identifier: Apache-2.0
"""model/mip.py: the MIP-level logic gathered in one place (re-exports, the per-hit level, the
triangle-table words) agrees with the functions it wraps and with the renderer's use of them."""
from __future__ import annotations

import numpy as np
import pytest

from model import camera, f24, heightmap, mip, scenes, shade, texture, traverse, view
from model.arith import ENGINES
from model.rays import Rays

F64, F24 = ENGINES["f64"], ENGINES["f24"]


def test_one_algorithm_re_exported() -> None:
    assert mip.log2_pb is camera.log2_pb and mip.mip_lod is camera.mip_lod
    assert mip.ray_length is texture.ray_length and mip.mip_level is texture.mip_level
    assert mip.log2 is texture.log2


@pytest.mark.parametrize("engine", ["f64", "f24"])
def test_level_is_the_composition(engine: str, rng: np.random.Generator) -> None:
    ar = ENGINES[engine]
    n = 20000
    pl0 = ar.r(np.exp(rng.uniform(0, 10, n)))
    t = ar.r(rng.uniform(0, 1, n))
    seg = ar.r(np.exp(rng.uniform(0, 6, n)))
    pb = ar.r(rng.uniform(-6, 16, n))
    t[:50] = np.nan                      # no hit
    pl0[50:100] = -ar.mul(t[50:100], seg[50:100])  # Pl = 0
    want = texture.mip_level(ar, texture.ray_length(ar, pl0, t, seg), pb, 9)
    got = mip.level(ar, pl0, t, seg, pb, 9)
    assert np.array_equal(got, want) and got.dtype == np.int64
    assert set(np.unique(got)) == set(range(9))
    assert np.all(got[:50] == 0)         # NaN t: level 0
    assert np.array_equal(mip.level(ar, pl0, t, seg, pb, 9, mip=False), np.zeros(n, np.int64))


def test_f24_edges() -> None:
    """The cases the RTL unit documents: NaN / zero / negative / infinite ray length."""
    pl0 = np.array([0.0, -0.0, -5.0, np.inf, np.nan, 100.0, 100.0])
    t = np.array([0.0, 0.0, 0.0, 0.0, 0.0, np.inf, -1.0])
    seg = np.array([1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 200.0])
    got = mip.level(F24, pl0, t, seg, np.zeros(7), 12)
    assert list(got) == [0, 0, 0, 11, 0, 11, 0]
    # Pl = +Inf: log2Pb = -Inf gives lod = +Inf -> 11, log2Pb = +Inf lod = NaN -> 0;
    # Pl = 8, log2Pb = +Inf: lod = -Inf -> 0
    got = mip.level(F24, np.array([np.inf, np.inf, 8.0]), np.zeros(3), np.ones(3),
                    np.array([-np.inf, np.inf, np.inf]), 12)
    assert list(got) == [11, 0, 0]


def test_table_words() -> None:
    c = np.array([0.1, -3.7, 12.25])
    n = np.array([1e-30, np.inf, np.nan])
    w = mip.table_words(c, n)
    assert w.shape == (3, 2) and w.dtype == np.uint32
    assert np.array_equal(f24.to_float(w[:, mip.TEX_COLOUR]), F24.r(c))
    assert list(w[:, mip.TEX_NORMAL]) == [f24.POS_ZERO, f24.POS_INF, f24.NAN]
    with pytest.raises(ValueError):
        mip.table_words(c, n[:2])


def test_matches_the_renderer() -> None:
    """mip.level on the renderer's inputs gives the levels model.shade.render_pixels reports."""
    sc = scenes.load_scene("rocks", 48)
    pyr = heightmap.build(sc.heights)
    tex = texture.build(sc.texture)
    nt = texture.build(scenes.encode_normals(sc.normals)[::2, ::2])  # another size: own levels
    cam = camera.Camera.for_view("oblique", 48, 48, 48, 48)
    fr = shade.Frame(pyr, tex, nt, sc.depth_scale, cam.log2_pb(tex.width, tex.height),
                     cam.log2_pb(nt.width, nt.height))
    _, inp = shade.pixel_inputs(cam)
    out = shade.render_pixels(fr, inp)
    vo = view.view_calc(F24, inp.tbn, inp.view, fr.depth_scale)
    res = traverse.trace(pyr, Rays(inp.u0, inp.v0, vo.du, vo.dv), fr.method, "f24")
    idx = np.nonzero(res.hit)[0]
    assert idx.size > 100
    tri = inp.tri[idx]
    words = mip.table_words(fr.log2pb_colour, fr.log2pb_normal)
    for col, n_levels, got in ((mip.TEX_COLOUR, tex.n_levels, out.level),
                               (mip.TEX_NORMAL, nt.n_levels, out.level_normal)):
        lv = mip.level(F24, F24.r(inp.pl0[idx]), F24.r(res.t[idx]), vo.seg[idx],
                       f24.to_float(words[tri, col]), n_levels)
        assert np.array_equal(lv, got[idx])
    assert len(np.unique(out.level[idx])) > 1
