# SPDX-License-Identifier: Apache-2.0
"""Height-map loading (OpenImageIO and .npy), quantisation, the pyramid and its memory layout."""
from __future__ import annotations

import numpy as np
import OpenImageIO as oiio
import pytest

from model import heightmap, scenes, traverse
from model.rays import Rays


def write_image(path, data: np.ndarray, fmt) -> None:
    if data.ndim == 2:  # OpenImageIO's write_image wants (height, width, channels)
        data = data[..., None].copy()
    h, w, ch = data.shape
    out = oiio.ImageOutput.create(str(path))
    assert out is not None, oiio.geterror()
    assert out.open(str(path), oiio.ImageSpec(w, h, ch, fmt))
    assert out.write_image(data)
    out.close()


def test_load_png8_png16_float_tiff_npy(tmp_path) -> None:
    rng = np.random.default_rng(0)
    a8 = rng.integers(0, 256, (13, 21), dtype=np.uint8)
    write_image(tmp_path / "a.png", a8, oiio.UINT8)
    assert np.array_equal(heightmap.load(tmp_path / "a.png"), a8 / 255.0)
    a16 = rng.integers(0, 65536, (9, 5), dtype=np.uint16)
    write_image(tmp_path / "b.png", a16, oiio.UINT16)
    assert np.allclose(heightmap.load(tmp_path / "b.png"), a16 / 65535.0, atol=1e-7)
    f = rng.uniform(-0.5, 1.5, (6, 7, 3)).astype(np.float32)
    write_image(tmp_path / "c.tif", f, oiio.FLOAT)
    assert np.allclose(heightmap.load(tmp_path / "c.tif"), np.clip(f[..., 0], 0, 1))
    np.save(tmp_path / "d.npy", a16)
    assert np.array_equal(heightmap.load(tmp_path / "d.npy"), a16 / 65535.0)
    np.save(tmp_path / "e.npy", np.array([[0.2, np.nan], [2.0, -1.0]]))
    assert np.array_equal(heightmap.load(tmp_path / "e.npy"), [[0.2, 0.0], [1.0, 0.0]])


@pytest.mark.parametrize("bad", ["missing.png", "garbage.png", "empty.npy", "threed.npy"])
def test_bad_files_raise_heightmap_error(tmp_path, bad: str) -> None:
    (tmp_path / "garbage.png").write_bytes(b"not an image")
    np.save(tmp_path / "empty.npy", np.zeros((0, 3)))
    np.save(tmp_path / "threed.npy", np.zeros((2, 2, 2, 2)))
    with pytest.raises(heightmap.HeightMapError):
        heightmap.load(tmp_path / bad)


@pytest.mark.parametrize("shape", [(1, 1), (2, 2), (3, 5), (37, 61), (64, 64), (100, 7)])
@pytest.mark.parametrize("bits", [8, 16])
def test_pyramid_is_block_maximum(shape: tuple[int, int], bits: int) -> None:
    rng = np.random.default_rng(1)
    pyr = heightmap.build(rng.random(shape), bits=bits)
    assert pyr.size >= max(shape) and pyr.size < 2 * max(shape) or pyr.size == 1
    assert pyr.levels[0].shape == (pyr.size, pyr.size)
    assert (pyr.levels[0][shape[0]:, :] == 0).all() and (pyr.levels[0][:, shape[1]:] == 0).all()
    for k, lv in enumerate(pyr.levels):
        side = pyr.size >> k
        assert lv.shape == (side, side)
        full = pyr.levels[0].reshape(side, 1 << k, side, 1 << k).max(axis=(1, 3))
        assert np.array_equal(lv, full)
    assert pyr.levels[-1][0, 0] == pyr.codes.max()


def test_memory_image_layout() -> None:
    pyr = heightmap.build(np.random.default_rng(2).random((20, 30)), bits=16)
    offs = pyr.level_offsets()
    img = pyr.memory_image()
    assert all(o % 64 == 0 for o in offs)
    for k, lv in enumerate(pyr.levels):
        side = pyr.size >> k
        got = np.frombuffer(img, dtype="<u2", count=side * side, offset=offs[k]).reshape(side, side)
        assert np.array_equal(got, lv)


def test_quantised_heights_are_what_every_engine_traces() -> None:
    """Vertical rays hit at 1 - code/255 (f64), whatever the float heights were."""
    h = np.random.default_rng(3).random((8, 8))
    pyr = heightmap.build(h)
    jj, ii = np.meshgrid(np.arange(8), np.arange(8))
    rays = Rays(jj.ravel() + 0.5, ii.ravel() + 0.5, np.zeros(64), np.zeros(64))
    res = traverse.trace(pyr, rays, "park", "f64")
    assert np.array_equal(res.t, 1 - pyr.codes.ravel() / 255.0)


def test_every_scene_builds() -> None:
    for name in scenes.SCENES:
        pyr = heightmap.build(scenes.height(name, (40, 56)))
        assert pyr.width == 56 and pyr.height == 40 and pyr.n == 6
