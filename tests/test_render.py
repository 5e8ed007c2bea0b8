# SPDX-License-Identifier: Apache-2.0
"""The texture / colour path (model.texture, model.shade) and the render tool (scripts/render.py)."""
from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from model import camera, f24, heightmap, scenes, shade, texture
from model.arith import ENGINES

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("render_script", ROOT / "scripts" / "render.py")
render = importlib.util.module_from_spec(_spec)
assert _spec.loader is not None
_spec.loader.exec_module(render)

F64, F24 = ENGINES["f64"], ENGINES["f24"]


def read_png(path: Path) -> np.ndarray:
    import OpenImageIO as oiio

    buf = oiio.ImageBuf(str(path))
    return np.asarray(buf.get_pixels(oiio.UINT8))


def write_image(path: Path, a: np.ndarray, fmt: str) -> None:
    import OpenImageIO as oiio

    a = np.ascontiguousarray(a)
    ch = 1 if a.ndim == 2 else a.shape[2]
    out = oiio.ImageOutput.create(str(path))
    assert out is not None
    assert out.open(str(path), oiio.ImageSpec(a.shape[1], a.shape[0], ch,
                                              oiio.UINT16 if fmt == "u16" else oiio.UINT8))
    assert out.write_image(a)
    out.close()


def run(tmp_path: Path, *args: str) -> tuple[np.ndarray, dict]:
    out, st = tmp_path / "img.png", tmp_path / "stats.json"
    assert render.main([*args, "--out", str(out), "--stats", str(st), "--quiet"]) == 0
    return read_png(out), json.loads(st.read_text())


# ---- renders ---------------------------------------------------------------------------------

@pytest.mark.parametrize("angle", ["front", "oblique", "grazing"])
def test_render_angles_f64_f24(tmp_path: Path, angle: str) -> None:
    imgs = {}
    for eng in ("f64", "f24"):
        img, st = run(tmp_path, "--scene", "rocks", "--map-size", "64", "--size", "40",
                      "--angle", angle, "--engine", eng, "--jobs", "1")
        assert img.shape == (40, 40, 3)
        assert st["pixels"] == 1600 and 0 < st["hits"] <= st["covered_pixels"] < 1600
        assert st["method"] == "park" and st["engine"] == eng and st["angle"] == angle
        assert st["iterations"] >= st["hits"] and st["iterations_per_pixel"] > 1
        assert sum(st["mip_levels"]) == st["hits"] and len(st["mip_levels"]) == 7
        assert st["seconds"] >= 0 and st["scene"] == "rocks"
        assert tuple(img[0, 0]) == shade.BACKGROUND  # corners are not covered
        imgs[eng] = img.astype(int)
    d = np.abs(imgs["f64"] - imgs["f24"])
    assert d.mean() < 1.0  # the engines agree up to rare texel / rounding differences


def test_render_scene_defaults_and_no_mip(tmp_path: Path) -> None:
    img, st = run(tmp_path, "--scene", "bump", "--map-size", "48", "--size", "24")
    assert st["engine"] == "f24" and st["angle"] == "oblique" and st["mip"] is True
    assert st["mip_levels"][0] < st["hits"]  # minified: levels above 0 are used
    img2, st2 = run(tmp_path, "--scene", "bump", "--map-size", "48", "--size", "24", "--no-mip")
    assert st2["mip_levels"][0] == st2["hits"] and st2["mip"] is False
    assert st2["iterations"] == st["iterations"]  # MIP-mapping does not change the traversal


def test_render_approximate_method(tmp_path: Path) -> None:
    img, st = run(tmp_path, "--scene", "stones", "--map-size", "32", "--size", "24",
                  "--method", "relief")
    assert st["engine"] == "f64" and st["hits"] > 0


def test_jobs_and_tiles_identical(tmp_path: Path) -> None:
    sc = scenes.load_scene("stones", 48)
    pyr = heightmap.build(sc.heights)
    tex = texture.build(sc.texture)
    nt = texture.build(scenes.encode_normals(sc.normals))
    cam = camera.Camera.for_view("oblique", 48, 48, 48, 40)
    fr = shade.Frame(pyr, tex, nt, sc.depth_scale, cam.log2_pb(), cam.log2_pb())
    a = shade.render(fr, cam, jobs=1, tile=16)
    b = shade.render(fr, cam, jobs=2, tile=16)
    c = shade.render(fr, cam, jobs=1, tile=1000)
    assert len(shade.tiles_of(a.frags, 16)) > 2
    for x in (b, c):
        assert np.array_equal(a.rgb, x.rgb)
        for p, q in zip(a.out, x.out):
            assert np.array_equal(p, q)
    # and through the tool
    i1, _ = run(tmp_path, "--scene", "wall", "--map-size", "40", "--size", "40", "--jobs", "1")
    i2, s2 = run(tmp_path, "--scene", "wall", "--map-size", "40", "--size", "40", "--jobs", "2",
                 "--tile", "12")
    assert s2["jobs"] == 2 and np.array_equal(i1, i2)


@pytest.mark.parametrize("fmt", ["u8", "u16"])
def test_user_heightmap_png(tmp_path: Path, fmt: str) -> None:
    h = scenes.height("four-shapes", (24, 40))  # non-square: 24 rows, 40 columns
    m = 65535 if fmt == "u16" else 255
    write_image(tmp_path / "h.png", np.rint(h * m).astype(np.uint16 if fmt == "u16" else np.uint8),
                fmt)
    img, st = run(tmp_path, "--heightmap", str(tmp_path / "h.png"), "--size", "32")
    assert st["map"] == [24, 40] and st["texture"] == [24, 40] and st["hits"] > 0
    assert img.shape == (32, 32, 3)
    # a texture and a normal map of other sizes (scaled by Wt / W), 16-bit normal map
    tx = (np.random.default_rng(1).random((48, 80, 3)) * 255).astype(np.uint8)
    write_image(tmp_path / "t.png", tx, "u8")
    nm = scenes.encode_normals(scenes.normal_map(scenes.height("four-shapes", (12, 20)), 3.0))
    write_image(tmp_path / "n.png", nm.astype(np.uint16) * 257, "u16")
    img2, st2 = run(tmp_path, "--heightmap", str(tmp_path / "h.png"), "--texture",
                    str(tmp_path / "t.png"), "--normal-map", str(tmp_path / "n.png"),
                    "--size", "32", "--engine", "f64")
    assert st2["texture"] == [48, 80] and st2["normal_map"] == [12, 20]
    assert st2["hits"] == st["hits"] or st2["engine"] != st["engine"]
    assert not np.array_equal(img, img2)


def test_user_heightmap_npy(tmp_path: Path) -> None:
    np.save(tmp_path / "h.npy", scenes.height("dent", (30, 20)))
    _, st = run(tmp_path, "--heightmap", str(tmp_path / "h.npy"), "--size", "24")
    assert st["map"] == [30, 20] and st["hits"] > 0


# ---- bad arguments: one line on stderr, exit status 2 ----------------------------------------

def _bad_cases(tmp: Path) -> list[list[str]]:
    (tmp / "garbage.png").write_text("not an image")
    np.save(tmp / "flat.npy", np.zeros(5))
    (tmp / "adir").mkdir(exist_ok=True)
    (tmp / "afile").write_text("x")
    np.save(tmp / "ok.npy", np.zeros((8, 8)))
    ok = str(tmp / "ok.npy")
    return [
        ["--scene", "nosuch"],                        # unknown scene
        ["--method", "nosuch"],                       # unknown method
        ["--engine", "rtl", "--method", "relief"],    # approximate methods have no RTL
        ["--engine", "f32"],                          # unknown engine
        ["--method", "relief", "--engine", "f24"],    # approximate methods are f64 only
        ["--angle", "sideways"],                      # unknown view
        ["--angle", "0"],                             # elevation out of (0, 90]
        ["--angle", "95"],
        ["--size", "0"],                              # bad numbers
        ["--size", "-4"],
        ["--size", "abc"],
        ["--size", "100000"],
        ["--size", "1.5"],
        ["--map-size", "0"],
        ["--jobs", "0"],
        ["--tile", "x"],
        ["--heightmap", str(tmp / "missing.png")],    # missing / unreadable files
        ["--heightmap", str(tmp / "garbage.png")],
        ["--heightmap", str(tmp / "flat.npy")],
        ["--heightmap", ok, "--texture", str(tmp / "missing.png")],
        ["--heightmap", ok, "--normal-map", str(tmp / "missing.png")],
        ["--heightmap", ok, "--texture", str(tmp / "garbage.png")],
        ["--scene", "rocks", "--heightmap", ok],      # conflicting options
        ["--texture", ok],
        ["--heightmap", ok, "--map-size", "64"],
        ["--out", str(tmp / "adir")],                 # unwritable outputs
        ["--out", str(tmp / "afile" / "x.png")],
        ["--bogus"],                                  # unknown option
    ]


def test_bad_arguments_exit_2_one_line(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    for case in _bad_cases(tmp_path):
        argv = [*case, "--size", "8"] if "--size" not in case else case
        argv += [] if "--out" in case else ["--out", str(tmp_path / "o.png")]
        argv += ["--stats", str(tmp_path / "s.json"), "--quiet"]
        with pytest.raises(SystemExit) as ei:
            render.main(argv)
        err = capsys.readouterr().err
        assert ei.value.code == 2, case
        lines = err.strip().splitlines()
        assert len(lines) == 1 and "error" in lines[0], (case, err)
        if case == ["--engine", "rtl", "--method", "relief"]:
            assert "pipeline RTL" in lines[0]


def test_bad_argument_subprocess(tmp_path: Path) -> None:
    p = subprocess.run([sys.executable, str(ROOT / "scripts" / "render.py"), "--heightmap",
                        str(tmp_path / "nope.png")], capture_output=True, text=True)
    assert p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1
    assert "nope.png" in p.stderr and "Traceback" not in p.stderr


# ---- texture: MIP chain, layout, bilinear lookup, level selection ----------------------------

def test_mip_chain_npot_box_filter_clamp() -> None:
    codes = np.arange(15, dtype=np.uint8).reshape(3, 5) * 10  # 3 rows x 5 columns, grey
    t = texture.build(codes)
    assert [t.level_size(k) for k in range(t.n_levels)] == [(5, 3), (3, 2), (2, 1), (1, 1)]
    l1 = t.levels[1][..., 0].astype(int)
    c = codes.astype(int)
    # (0, 2): columns 4 and (clamped) 4, rows 0, 1
    assert l1[0, 2] == (c[0, 4] + c[0, 4] + c[1, 4] + c[1, 4] + 2) >> 2
    # (1, 0): rows 2 and (clamped) 2
    assert l1[1, 0] == (c[2, 0] + c[2, 1] + c[2, 0] + c[2, 1] + 2) >> 2
    assert l1[0, 0] == (0 + 10 + 50 + 60 + 2) >> 2
    assert np.all(t.levels[0][..., 3] == 255) and np.all(t.levels[0][..., 1] == codes)


def test_memory_layout() -> None:
    t = texture.build(np.random.default_rng(3).random((7, 9, 3)))
    offs = t.level_offsets()
    assert offs[0] == 0 and all(o % 64 == 0 for o in offs)
    assert all(offs[k + 1] - offs[k] >= 4 * t.levels[k].shape[0] * t.levels[k].shape[1]
               for k in range(t.n_levels - 1))
    mem = np.frombuffer(t.memory_image(), dtype=np.uint8)
    assert mem.size % 64 == 0
    for k, lv in enumerate(t.levels):
        i, j = lv.shape[0] - 1, lv.shape[1] - 1
        a = int(t.address(k, i, j))
        assert a == offs[k] + 4 * (i * lv.shape[1] + j)
        assert np.array_equal(mem[a:a + 4], lv[i, j])


@pytest.mark.parametrize("eng", ["f64", "f24"])
def test_bilinear_exact_at_centres(eng: str) -> None:
    ar = ENGINES[eng]
    t = texture.build(np.random.default_rng(5).integers(0, 256, (5, 7, 3)).astype(np.uint8))
    ii, jj = np.meshgrid(np.arange(5), np.arange(7), indexing="ij")
    u, v = jj.ravel() + 0.5, ii.ravel() + 0.5
    got = texture.sample(t, ar, u, v, 0).value
    want = ar.from_unorm(t.levels[0][ii.ravel(), jj.ravel()], 8)
    assert np.array_equal(got, want)
    # level 1 at its own texel centres (level-0 coordinates 2 (j + 0.5))
    l1 = t.levels[1]
    ii, jj = np.meshgrid(np.arange(l1.shape[0]), np.arange(l1.shape[1]), indexing="ij")
    got = texture.sample(t, ar, 2.0 * (jj.ravel() + 0.5), 2.0 * (ii.ravel() + 0.5), 1).value
    assert np.array_equal(got, ar.from_unorm(l1[ii.ravel(), jj.ravel()], 8))


@pytest.mark.parametrize("eng", ["f64", "f24"])
def test_bilinear_halfway_and_clamp(eng: str) -> None:
    ar = ENGINES[eng]
    codes = np.array([[0, 100, 200], [50, 150, 250]], dtype=np.uint8)
    t = texture.build(codes)
    tol = 0.0 if eng == "f64" else 2.0**-15
    c = codes.astype(float) / 255.0

    def at(u: float, v: float) -> float:
        return float(texture.sample(t, ar, np.array([u]), np.array([v]), 0).value[0, 0])

    assert at(1.0, 0.5) == pytest.approx((c[0, 0] + c[0, 1]) / 2, abs=tol + 1e-15)
    assert at(0.5, 1.0) == pytest.approx((c[0, 0] + c[1, 0]) / 2, abs=tol + 1e-15)
    assert at(2.0, 1.0) == pytest.approx(c[:, 1:].mean(), abs=tol + 1e-15)
    assert at(1.25, 0.5) == pytest.approx(0.25 * c[0, 0] + 0.75 * c[0, 1], abs=tol + 1e-15)  # x = 0.75
    # clamp to edge: beyond the outer texel centres the edge texels are returned
    for u, v, w in [(0.1, 0.2, c[0, 0]), (2.9, 0.5, c[0, 2]), (-5.0, 9.0, c[1, 0]),
                    (50.0, -3.0, c[0, 2]), (0.0, 2.0, c[1, 0])]:
        assert at(u, v) == pytest.approx(w, abs=tol + 1e-15), (u, v)


def test_texture_scale_for_other_sizes() -> None:
    t = texture.build(np.random.default_rng(7).random((16, 24, 3)))
    u, v = np.array([1.3, 5.7, 11.0]), np.array([0.2, 3.9, 7.5])
    for ar in (F64, F24):
        sc = t.scale_for(ar, 12, 8)  # the texture is twice the map's size: exact scale 2
        assert float(sc[0][0]) == 2.0 and float(sc[1][0]) == 2.0
        assert np.array_equal(texture.sample(t, ar, u, v, 0, sc).value,
                              texture.sample(t, ar, 2 * u, 2 * v, 0).value)


def test_level_selection_from_lod() -> None:
    for ar in (F64, F24):
        pl = np.array([1.0, 2.0, 4.0, 1024.0, 0.25, 2.0**40])
        lv = texture.mip_level(ar, pl, np.zeros(6), 9)
        assert list(lv) == [0, 1, 2, 8, 0, 8]  # log2 exact at powers of two; clamped
    # rounding to nearest: lod = 1.49 -> 1, 1.51 -> 2 (f64); Pb shifts the lod
    lv = texture.mip_level(F64, np.array([2.0**1.49, 2.0**1.51, 8.0]), np.array([0.0, 0.0, 1.0]),
                           9)
    assert list(lv) == [1, 2, 2]
    # the f24 engine uses the approximate log2 unit
    x = np.array([3.0, 5.0, 1000.0])
    assert np.array_equal(texture.log2(F24, x), f24.to_float(f24.log2(f24.from_float(x))))


# ---- shading ---------------------------------------------------------------------------------

@pytest.mark.parametrize("eng", ["f64", "f24"])
def test_shading_flat_from_above(eng: str) -> None:
    ar = ENGINES[eng]
    mat = shade.Material(light=(0.0, 0.0, 1.0))
    tex = np.array([[0.4, 0.2, 0.1], [0.1, 0.3, 0.5]])
    zero = np.zeros(2)
    # an exactly flat normal (M = 0.5, 0.5, 1): n = l = v = h = (0, 0, 1), all cosines 1
    out = shade.shade(ar, tex, np.array([[0.5, 0.5, 1.0]] * 2), zero, zero, 20.0, mat)
    want = np.floor(np.clip(tex * (shade.AMBIENT + shade.KD) + shade.KS, 0, 1) * 255 + 0.5)
    assert np.array_equal(out, want.astype(np.uint8))  # 0.4 + 0.25 = 0.65 -> 166, ...
    assert list(out[0]) == [166, 115, 89]
    # the unorm8 flat normal (128, 128, 255) decodes to (1/255, 1/255, 1): a hair off vertical
    m = ar.from_unorm(np.array([[128, 128, 255]] * 2), 8)
    out = shade.shade(ar, tex, m, zero, zero, 20.0, mat)
    cos = 1.0 / np.sqrt(1.0 + 2.0 / 255.0**2)
    want = np.floor(np.clip(tex * (shade.AMBIENT + shade.KD * cos) + shade.KS * cos**16, 0, 1)
                    * 255 + 0.5)
    assert np.array_equal(out, want.astype(np.uint8))


def test_shading_cases() -> None:
    mat = shade.Material(light=(0.0, 0.0, 1.0))
    tex = np.full((3, 3), 0.5)
    # normals: facing the light, sideways (n.l = 0: ambient only, n.h < 1), away (tangent)
    m = np.array([[0.5, 0.5, 1.0], [1.0, 0.5, 0.5], [0.5, 0.0, 0.5]])
    for ar in (F64, F24):
        out = shade.shade(ar, tex, m, np.zeros(3), np.zeros(3), 10.0, mat).astype(int)
        assert out[0, 0] == 191                                  # 0.5 * 1 + 0.25 = 0.75
        assert out[1, 0] == out[2, 0] == int(0.5 * shade.AMBIENT * 255 + 0.5)  # 38
    # clamp: a white texel lit head-on saturates at 255; a zero normal does not give NaN
    out = shade.shade(F24, np.ones((1, 3)), np.array([[0.5, 0.5, 0.5]]), np.zeros(1),
                      np.zeros(1), 10.0, mat)
    assert list(out[0]) == [int(shade.AMBIENT * 255 + 0.5)] * 3
    out = shade.shade(F24, np.ones((1, 3)), np.array([[0.5, 0.5, 1.0]]), np.zeros(1),
                      np.zeros(1), 10.0, mat)
    assert list(out[0]) == [255, 255, 255]


def test_rsqrt_engines() -> None:
    x = np.array([0.25, 2.0, 3.0, 1e6])
    assert np.allclose(shade.rsqrt(F64, x), 1 / np.sqrt(x), rtol=0, atol=0)
    assert np.array_equal(shade.rsqrt(F24, x), f24.to_float(f24.rsqrt(f24.from_float(x))))
    assert np.allclose(shade.rsqrt(F24, x), 1 / np.sqrt(x), rtol=2.0**-16)
