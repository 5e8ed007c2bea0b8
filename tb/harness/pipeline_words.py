# SPDX-License-Identifier: Apache-2.0
"""Driving ``rtl/pipe/dm_pipeline.sv`` (the whole displacement-mapping pipeline) from the model:
the configuration port values, the triangle-table and texture level-table writes, the memory
images and the per-pixel fragment words of a frame (:class:`model.shade.Frame`, :class:`model.camera.Camera`).

The RTL's pixels must equal ``model.shade.render_pixels(frame, inputs)`` with the f24 engine:
rgb, hit, invalid and iterations per pixel.  Packed-array ports are single integers here, element
i at bit i * width (the SystemVerilog packing of ``logic [N-1:0][W-1:0]``).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from model import f24, mip, shade
from model.arith import ENGINES

from . import sv_params, traverse_words

#: rtl/pipe/pipe_pkg.sv: levels a texture configuration holds, and the widths of its fields.
TEX_LEVELS, TEX_DIM_W, TEX_ADDR_W, TEX_LVL_W = sv_params.values(
    "pipe_pkg", "TEX_LEVELS", "TEX_DIM_W", "TEX_ADDR_W", "TEX_LVL_W")
#: rtl/pipe/pipe_pkg.sv: the kinds of a level-table word (dm_pipeline's lvt_waddr_i).
LVT_HEIGHT_OFF, LVT_TEX_OFF, LVT_TEX_SIZE = sv_params.values(
    "pipe_pkg", "LVT_HEIGHT_OFF", "LVT_TEX_OFF", "LVT_TEX_SIZE")
#: Default byte addresses of the pyramid and the two textures in the AXI address spaces.
HEIGHT_BASE = 0x4000_0000
COLOUR_BASE = 0x1000_0000
NORMAL_BASE = 0x2000_0000


def pack(words: npt.ArrayLike, width: int) -> int:
    """Element i of a packed array at bits [i*width +: width]."""
    out = 0
    for i, w in enumerate(np.asarray(words).ravel().tolist()):
        out |= (int(w) & ((1 << width) - 1)) << (i * width)
    return out


def lvt_addr(kind: int, tex: int, level: int) -> int:
    """dm_pipeline's lvt_waddr_i {kind, texture, level}: kind LVT_HEIGHT_OFF the height
    pyramid's level offset (tex 0), LVT_TEX_OFF a texture level's byte offset, LVT_TEX_SIZE its
    size word {height, width}."""
    return (kind << (1 + TEX_LVL_W)) | (tex << TEX_LVL_W) | level


def lvt_fields(addr: int) -> tuple[int, int, int]:
    """(kind, texture, level) of a lvt_waddr_i: the inverse of lvt_addr."""
    return addr >> (1 + TEX_LVL_W), (addr >> TEX_LVL_W) & 1, addr & ((1 << TEX_LVL_W) - 1)


@dataclass
class PipelineConfig:
    """``ports``: cfg_* values; ``tri_writes``: (tt_waddr_i, tt_wdata_i) pairs; ``height`` and
    ``textures``: (base, image) the memories must hold (height port; texture port);
    ``lvt_writes``: (lvt_waddr_i, lvt_wdata_i) pairs, the level tables: the height pyramid's
    MAX_LEVELS level offsets, then per texture the TEX_LEVELS offsets and the TEX_LEVELS
    sizes."""

    ports: dict[str, int]
    tri_writes: list[tuple[int, int]]
    height: tuple[int, bytes]
    textures: list[tuple[int, bytes]] = field(default_factory=list)
    lvt_writes: list[tuple[int, int]] = field(default_factory=list)


def _f24(x: float) -> int:
    return int(f24.from_float(np.array([float(x)]))[0])


def config(frame: shade.Frame, height_base: int = HEIGHT_BASE, colour_base: int = COLOUR_BASE,
           normal_base: int = NORMAL_BASE) -> PipelineConfig:
    """Everything a driver writes before the frame (the frame's method must be exact, f24)."""
    if frame.engine != "f24":
        raise ValueError("the RTL pipeline is the f24 engine")
    ar = ENGINES["f24"]
    pyr = frame.pyr
    tcfg = traverse_words.config(pyr, frame.method, base=height_base)
    ports = dict(tcfg.ports())
    d = _f24(frame.depth_scale)
    m = frame.material
    lu = m.light_unit()
    dd = int(f24.mul(np.array([d], np.uint32), np.array([d], np.uint32))[0])
    shade_words = [_f24(lu[0]), _f24(lu[1]), _f24(lu[2]), _f24(m.ambient), _f24(m.kd),
                   _f24(m.ks), d, dd]
    # shade_cfg_t: light_x is the most significant field
    ports["cfg_shade_i"] = pack(shade_words[::-1], 24)
    ports["cfg_depth_i"] = d
    ports["cfg_mip_en_i"] = int(frame.mip)
    ports["cfg_levels_colour_i"] = frame.colour.n_levels
    ports["cfg_levels_normal_i"] = frame.normals.n_levels
    ports["cfg_miss_rgb_i"] = pack(shade.MISS_COLOUR, 8)
    su, sv, bases = [], [], []
    lvt = [(lvt_addr(LVT_HEIGHT_OFF, 0, k), off) for k, off in tcfg.hlt_writes()]
    for x, (tex, base) in enumerate(((frame.colour, colour_base), (frame.normals, normal_base))):
        if tex.n_levels > TEX_LEVELS:
            raise ValueError(f"a texture of {tex.n_levels} levels; the RTL holds {TEX_LEVELS}")
        s_u, s_v = tex.scale_for(ar, pyr.width, pyr.height)
        su.append(int(f24.from_float(s_u)[0]))
        sv.append(int(f24.from_float(s_v)[0]))
        w = [lv.shape[1] for lv in tex.levels] + [1] * (TEX_LEVELS - tex.n_levels)
        h = [lv.shape[0] for lv in tex.levels] + [1] * (TEX_LEVELS - tex.n_levels)
        o = tex.level_offsets() + [0] * (TEX_LEVELS - tex.n_levels)
        lvt += [(lvt_addr(LVT_TEX_OFF, x, k), o[k]) for k in range(TEX_LEVELS)]
        lvt += [(lvt_addr(LVT_TEX_SIZE, x, k), (h[k] << TEX_DIM_W) | w[k])
                for k in range(TEX_LEVELS)]
        bases.append(base)
    ports["cfg_tex_su_i"] = pack(su, 24)
    ports["cfg_tex_sv_i"] = pack(sv, 24)
    ports["cfg_tex_base_i"] = pack(bases, TEX_ADDR_W)
    words = mip.table_words(frame.log2pb_colour, frame.log2pb_normal)
    tri = [(2 * t + x, int(words[t, x])) for t in range(words.shape[0]) for x in range(2)]
    return PipelineConfig(ports, tri, (height_base, pyr.memory_image()),
                          [(colour_base, frame.colour.memory_image()),
                           (normal_base, frame.normals.memory_image())], lvt)


def fragment_words(inp: shade.PixelInputs) -> dict[str, npt.NDArray[np.int64]]:
    """Per fragment the words of the frag_* ports (frag_id_i = the index)."""
    def w(x: npt.ArrayLike) -> npt.NDArray[np.int64]:
        with np.errstate(invalid="ignore"):
            return f24.from_float(np.asarray(x, dtype=np.float64)).astype(np.int64)

    n = len(inp.u0)
    tbn = np.asarray(inp.tbn, dtype=np.float64)
    view = np.asarray(inp.view, dtype=np.float64)
    # T (0..2), B (3..5), N (6..8): the columns of the TBN matrix
    tw = [w(tbn[:, i, c]) for c in range(3) for i in range(3)]
    vw = [w(view[:, i]) for i in range(3)]
    tbn_packed = np.array([pack([t[k] for t in tw], 24) for k in range(n)], dtype=object)
    view_packed = np.array([pack([v[k] for v in vw], 24) for k in range(n)], dtype=object)
    return {"frag_id_i": np.arange(n, dtype=np.int64), "frag_u0_i": w(inp.u0),
            "frag_v0_i": w(inp.v0), "frag_pl0_i": w(inp.pl0),
            "frag_tri_i": np.asarray(inp.tri, dtype=np.int64),
            "frag_tbn_i": tbn_packed, "frag_view_i": view_packed}
