# SPDX-License-Identifier: Apache-2.0
"""A frame for the system top pidm_top in memory: the height pyramid, the colour and normal MIP
chains, the fragment buffer and the framebuffer as memory regions, and the register writes that
program the core (``scripts/pack_frame.py`` writes them to files; a system test loads them).

Everything is the model's: :func:`tb.harness.pipeline_words.config` gives the configuration port
values and the triangle-table words, :func:`tb.harness.dm_pipeline.frame_image` the memory images
and their bases, :func:`tb.harness.dm_pipeline.fragment_words` the fragment words; this module
only places them.  Register addresses and fields come from ``rtl/top/pidm_regs.rdl``
(:mod:`tb.harness.pidm_regmap`); the fragment record, pixel and status-word layouts from
``rtl/top/pidm_pkg.sv`` (:mod:`tb.harness.sv_params`).  docs/system.md describes the formats.

Pixel ids: a fragment of pixel (row, col) carries the id ``(row << xbits) | col`` with ``xbits``
the bits of the image width; pidm_top writes its pixel at ``FB_BASE + row * FB_PITCH + 4 col``.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from model import shade
from model.camera import Camera, Fragments, tile_order

from . import dm_pipeline, pidm_regmap, pipeline_words, sv_params
from .pipeline_words import PipelineConfig, TEX_ADDR_W, TEX_DIM_W

# ---- rtl/top/pidm_pkg.sv ------------------------------------------------------------------------
(FRAG_BYTES, FRAG_WORDS, FRAG_U0_WORD, FRAG_V0_WORD, FRAG_PL0_WORD, FRAG_TRI_WORD, FRAG_TRI_LSB,
 FRAG_TRI_BITS, FRAG_ID_WORD, FRAG_ID_LSB, FRAG_ID_BITS, FRAG_TBN_WORD, FRAG_VIEW_WORD,
 F24_BITS) = sv_params.values(
    "pidm_pkg", "FRAG_BYTES", "FRAG_WORDS", "FRAG_U0_WORD", "FRAG_V0_WORD", "FRAG_PL0_WORD",
    "FRAG_TRI_WORD", "FRAG_TRI_LSB", "FRAG_TRI_BITS", "FRAG_ID_WORD", "FRAG_ID_LSB",
    "FRAG_ID_BITS", "FRAG_TBN_WORD", "FRAG_VIEW_WORD", "F24_BITS")
(PIX_BYTES, PIX_ALPHA, STW_ITERS_LSB, STW_ITERS_BITS, STW_HIT_BIT, STW_INVALID_BIT,
 STW_ERR_BIT) = sv_params.values(
    "pidm_pkg", "PIX_BYTES", "PIX_ALPHA", "STW_ITERS_LSB", "STW_ITERS_BITS", "STW_HIT_BIT",
    "STW_INVALID_BIT", "STW_ERR_BIT")

#: Default byte addresses of the regions pidm_top's DMA engines use (one address space; the
#: pyramid and textures keep the harness's bases, pipeline_words.HEIGHT_BASE / COLOUR_BASE).
FRAG_BASE = 0x6000_0000
FB_BASE = 0x7000_0000
STATUS_BASE = 0x7800_0000
#: dm_pipeline's pixel-id width the harness and the system top are built with.
PIX_W = dm_pipeline.PARAMS["PIX_W"]

#: cfg_shade_i fields (shade_cfg_t, light_x the most significant) and their SHADE registers.
SHADE_REGS = ("LIGHT_X", "LIGHT_Y", "LIGHT_Z", "AMBIENT", "KD", "KS", "D", "D2")

Writes = list[tuple[int, int]]


class FrameError(ValueError):
    """A frame pidm_top cannot take in this layout (one line)."""


def _elems(v: int, width: int, n: int) -> list[int]:
    """Elements 0 .. n-1 of a packed array (element i at bits [i*width +: width])."""
    return [(int(v) >> (i * width)) & ((1 << width) - 1) for i in range(n)]


# ---- configuration ports <-> register writes ---------------------------------------------------

def config_writes(cfg: PipelineConfig) -> Writes:
    """The register writes of the configuration (HEIGHT, SHADE, TEX[0], TEX[1]) in address
    order, then the triangle table (TT_WRITE, one write per table word)."""
    p = cfg.ports
    R = pidm_regmap.reg
    out: Writes = [
        (R("HEIGHT.MODE").addr, R("HEIGHT.MODE").value(
            method=p["cfg_method_i"], root_level=p["cfg_root_level_i"],
            bits16=p["cfg_bits16_i"])),
        (R("HEIGHT.SIZE").addr, R("HEIGHT.SIZE").value(width=p["cfg_width_i"],
                                                       height=p["cfg_height_i"])),
        (R("HEIGHT.BASE").addr, R("HEIGHT.BASE").value(val=p["cfg_base_i"])),
        (R("HEIGHT.ROOT").addr, R("HEIGHT.ROOT").value(root_code=p["cfg_root_code_i"],
                                                       iter_cap=p["cfg_iter_cap_i"])),
        (R("HEIGHT.DEPTH").addr, R("HEIGHT.DEPTH").value(val=p["cfg_depth_i"])),
    ]
    for a, off in cfg.lvt_writes:
        kind, _, k = pipeline_words.lvt_fields(a)
        if kind == pipeline_words.LVT_HEIGHT_OFF:
            out.append((R(f"HEIGHT.LEVEL_OFF[{k}]").addr,
                        R(f"HEIGHT.LEVEL_OFF[{k}]").value(val=off)))
    red, green, blue = _elems(p["cfg_miss_rgb_i"], 8, 3)
    out += [
        (R("SHADE.MIP").addr, R("SHADE.MIP").value(
            mip_en=p["cfg_mip_en_i"], levels_colour=p["cfg_levels_colour_i"],
            levels_normal=p["cfg_levels_normal_i"])),
        (R("SHADE.MISS_RGB").addr, R("SHADE.MISS_RGB").value(red=red, green=green, blue=blue)),
    ]
    shade_words = _elems(p["cfg_shade_i"], 24, len(SHADE_REGS))[::-1]   # light_x first
    for name, w in zip(SHADE_REGS, shade_words):
        out.append((R(f"SHADE.{name}").addr, R(f"SHADE.{name}").value(val=w)))
    su, sv = _elems(p["cfg_tex_su_i"], 24, 2), _elems(p["cfg_tex_sv_i"], 24, 2)
    bases = _elems(p["cfg_tex_base_i"], TEX_ADDR_W, 2)
    for x in range(2):
        t = f"TEX[{x}]"
        out += [(R(f"{t}.SU").addr, R(f"{t}.SU").value(val=su[x])),
                (R(f"{t}.SV").addr, R(f"{t}.SV").value(val=sv[x])),
                (R(f"{t}.BASE").addr, R(f"{t}.BASE").value(val=bases[x]))]
        for a, d in cfg.lvt_writes:
            kind, tex, k = pipeline_words.lvt_fields(a)
            if tex != x or kind == pipeline_words.LVT_HEIGHT_OFF:
                continue
            if kind == pipeline_words.LVT_TEX_SIZE:
                r = R(f"{t}.LEVEL_SIZE[{k}]")
                out.append((r.addr, r.value(width=d & ((1 << TEX_DIM_W) - 1),
                                            height=d >> TEX_DIM_W)))
            else:
                r = R(f"{t}.LEVEL_OFF[{k}]")
                out.append((r.addr, r.value(val=d)))
    tt = R("TT_WRITE")
    out += [(tt.addr, tt.value(data=d, addr=a)) for a, d in cfg.tri_writes]
    return out


def _lvt_of(path: str, f: dict[str, int]) -> tuple[int, int] | None:
    """The level-table write (lvt_waddr_i, lvt_wdata_i) a write of register ``path`` makes
    (HEIGHT.LEVEL_OFF[k], TEX[x].LEVEL_OFF[k], TEX[x].LEVEL_SIZE[k]), else None."""
    m = re.fullmatch(r"HEIGHT\.LEVEL_OFF\[(\d+)\]", path)
    if m is not None:
        return pipeline_words.lvt_addr(pipeline_words.LVT_HEIGHT_OFF, 0, int(m[1])), f["val"]
    m = re.fullmatch(r"TEX\[(\d)\]\.LEVEL_(OFF|SIZE)\[(\d+)\]", path)
    if m is None:
        return None
    x, kind, k = int(m[1]), m[2], int(m[3])
    if kind == "OFF":
        return pipeline_words.lvt_addr(pipeline_words.LVT_TEX_OFF, x, k), f["val"]
    return (pipeline_words.lvt_addr(pipeline_words.LVT_TEX_SIZE, x, k),
            (f["height"] << TEX_DIM_W) | f["width"])


def ports_from_writes(writes: Writes) -> tuple[dict[str, int], list[tuple[int, int]],
                                               list[tuple[int, int]]]:
    """The inverse of :func:`config_writes`: the cfg_* port values the registers hold after the
    writes (the last write of a register counts), the triangle-table writes (tt_waddr_i,
    tt_wdata_i) and the level-table writes (lvt_waddr_i, lvt_wdata_i), each in order.
    What pidm_top wires from its register block to dm_pipeline."""
    regs = pidm_regmap.by_address()
    tt_addr = pidm_regmap.reg("TT_WRITE").addr
    held: dict[str, dict[str, int]] = {}
    tri: list[tuple[int, int]] = []
    lvt: list[tuple[int, int]] = []
    for addr, value in writes:
        r = regs.get(addr)
        if r is None:
            raise FrameError(f"no register at {addr:#05x}")
        f = r.fields_of(value)
        if addr == tt_addr:
            tri.append((f["addr"], f["data"]))
        w = _lvt_of(r.path, f)
        if w is not None:
            lvt.append(w)
        held[r.path] = f

    def g(path: str, name: str) -> int:
        return held.get(path, {}).get(name, 0)

    p = {
        "cfg_method_i": g("HEIGHT.MODE", "method"), "cfg_width_i": g("HEIGHT.SIZE", "width"),
        "cfg_height_i": g("HEIGHT.SIZE", "height"),
        "cfg_root_level_i": g("HEIGHT.MODE", "root_level"),
        "cfg_bits16_i": g("HEIGHT.MODE", "bits16"), "cfg_base_i": g("HEIGHT.BASE", "val"),
        "cfg_root_code_i": g("HEIGHT.ROOT", "root_code"),
        "cfg_iter_cap_i": g("HEIGHT.ROOT", "iter_cap"), "cfg_depth_i": g("HEIGHT.DEPTH", "val"),
        "cfg_mip_en_i": g("SHADE.MIP", "mip_en"),
        "cfg_levels_colour_i": g("SHADE.MIP", "levels_colour"),
        "cfg_levels_normal_i": g("SHADE.MIP", "levels_normal"),
        "cfg_shade_i": pipeline_words.pack([g(f"SHADE.{n}", "val") for n in SHADE_REGS][::-1], 24),
        "cfg_miss_rgb_i": pipeline_words.pack([g("SHADE.MISS_RGB", c)
                                               for c in ("red", "green", "blue")], 8),
        "cfg_tex_su_i": pipeline_words.pack([g(f"TEX[{x}].SU", "val") for x in range(2)], 24),
        "cfg_tex_sv_i": pipeline_words.pack([g(f"TEX[{x}].SV", "val") for x in range(2)], 24),
        "cfg_tex_base_i": pipeline_words.pack([g(f"TEX[{x}].BASE", "val") for x in range(2)],
                                              TEX_ADDR_W),
    }
    return p, tri, lvt


# ---- fragments ---------------------------------------------------------------------------------

def xbits_for(width: int) -> int:
    """Bits of the pixel id that hold x for an image ``width`` pixels wide."""
    return max(1, (int(width) - 1).bit_length())


def fragment_records(inp: shade.PixelInputs, ids: npt.ArrayLike) -> npt.NDArray[np.uint32]:
    """(N, FRAG_WORDS) little-endian u32: the fragment buffer's records (docs/system.md), the
    words of :func:`tb.harness.dm_pipeline.fragment_words` with each pixel id beside its
    triangle."""
    words = dm_pipeline.fragment_words(inp)
    if words.shape[1] != FRAG_WORDS:
        raise FrameError(f"fragment words {words.shape[1]} != pidm_pkg FRAG_WORDS {FRAG_WORDS}")
    ids = np.asarray(ids, dtype=np.int64)
    if len(ids) and (ids.min() < 0 or ids.max() >> FRAG_ID_BITS):
        raise FrameError(f"pixel ids must fit {FRAG_ID_BITS} bits")
    tri = words[:, FRAG_TRI_WORD].astype(np.int64)
    if len(tri) and tri.max() >> FRAG_TRI_BITS:
        raise FrameError(f"triangle ids must fit {FRAG_TRI_BITS} bits")
    out = np.zeros((len(ids), FRAG_WORDS), dtype="<u4")
    out[:, FRAG_U0_WORD] = words[:, 0]
    out[:, FRAG_V0_WORD] = words[:, 1]
    out[:, FRAG_PL0_WORD] = words[:, 2]
    out[:, FRAG_TBN_WORD:FRAG_TBN_WORD + 9] = words[:, 4:13]
    out[:, FRAG_VIEW_WORD:FRAG_VIEW_WORD + 3] = words[:, 13:16]
    out[:, FRAG_TRI_WORD] = (tri << FRAG_TRI_LSB).astype(np.uint32)
    out[:, FRAG_ID_WORD] |= (ids << FRAG_ID_LSB).astype(np.uint32)
    return out


def decode_records(buf: bytes) -> dict[str, npt.NDArray[np.int64]]:
    """The fields of a fragment buffer (FRAG_BYTES per record): ``id``, ``tri``, ``u0``, ``v0``,
    ``pl0`` (f24 words), ``tbn`` (N, 9) and ``view`` (N, 3) (f24 words)."""
    if len(buf) % FRAG_BYTES:
        raise FrameError(f"a fragment buffer is a multiple of {FRAG_BYTES} bytes, got {len(buf)}")
    w = np.frombuffer(buf, dtype="<u4").reshape(-1, FRAG_WORDS).astype(np.int64)
    f24m = (1 << F24_BITS) - 1
    return {"id": (w[:, FRAG_ID_WORD] >> FRAG_ID_LSB) & ((1 << FRAG_ID_BITS) - 1),
            "tri": (w[:, FRAG_TRI_WORD] >> FRAG_TRI_LSB) & ((1 << FRAG_TRI_BITS) - 1),
            "u0": w[:, FRAG_U0_WORD] & f24m, "v0": w[:, FRAG_V0_WORD] & f24m,
            "pl0": w[:, FRAG_PL0_WORD] & f24m,
            "tbn": w[:, FRAG_TBN_WORD:FRAG_TBN_WORD + 9] & f24m,
            "view": w[:, FRAG_VIEW_WORD:FRAG_VIEW_WORD + 3] & f24m}


# ---- the packed frame --------------------------------------------------------------------------

@dataclass
class Region:
    """A memory region: its name, byte address and initial contents."""

    name: str
    base: int
    data: bytes


@dataclass
class PackedFrame:
    """A frame ready for pidm_top: the memory regions, the configuration writes (with the
    triangle table), the frame descriptor and its register writes, the CTRL write that starts
    it; ``order[i]`` is the covered-pixel index (the model's row-major order) of fragment i."""

    regions: list[Region]
    config: Writes
    descriptor: dict[str, int]
    frame_writes: Writes
    start: tuple[int, int]
    image_w: int
    image_h: int
    frags: Fragments
    order: npt.NDArray[np.int64]
    extra: dict[str, Any] = field(default_factory=dict)

    def region(self, name: str) -> Region:
        return next(r for r in self.regions if r.name == name)


def descriptor_writes(d: dict[str, int]) -> Writes:
    """The FRAME register writes of a descriptor (keys as :func:`pack` makes them)."""
    R = pidm_regmap.reg
    m32 = 0xFFFF_FFFF
    out: Writes = []
    for key, reg in (("frag_base", "FRAG_BASE"), ("fb_base", "FB_BASE"),
                     ("status_base", "STATUS_BASE")):
        out.append((R(f"FRAME.{reg}.LO").addr, d[key] & m32))
        out.append((R(f"FRAME.{reg}.HI").addr, (d[key] >> 32) & m32))
    out += [(R("FRAME.FRAG_COUNT").addr, R("FRAME.FRAG_COUNT").value(val=d["frag_count"])),
            (R("FRAME.FB_PITCH").addr, R("FRAME.FB_PITCH").value(val=d["fb_pitch"])),
            (R("FRAME.FB_LAYOUT").addr, R("FRAME.FB_LAYOUT").value(
                xbits=d["xbits"], status_en=d["status_en"]))]
    return sorted(out)


def pack(frame: shade.Frame, cam: Camera, *, tile: int = dm_pipeline.DEFAULT_TILE,
         blocks: str = dm_pipeline.DEFAULT_BLOCKS, frag_base: int = FRAG_BASE,
         fb_base: int = FB_BASE, status_base: int = STATUS_BASE, status_en: bool = True,
         pix_w: int = PIX_W, frags: Fragments | None = None) -> PackedFrame:
    """Pack ``frame`` seen by ``cam``: fragments in ``tile`` x ``tile`` blocks (``blocks``
    order), as :func:`tb.harness.dm_pipeline.render_rtl` feeds them."""
    try:
        fi = dm_pipeline.frame_image(frame)
    except dm_pipeline.RtlLimitError as e:
        raise FrameError(str(e)) from None
    f, inp = shade.pixel_inputs(cam, frags)
    if len(f) == 0:
        raise FrameError("the camera sees no pixel of the surface (no fragment)")
    xbits = xbits_for(cam.image_w)
    ybits = max(1, (int(cam.image_h) - 1).bit_length())
    if xbits + ybits > min(pix_w, FRAG_ID_BITS):
        raise FrameError(f"a {cam.image_w} x {cam.image_h} image needs {xbits + ybits}-bit pixel "
                         f"ids; PIX_W is {pix_w}")
    for name, base, align in (("--frag-base", frag_base, FRAG_BYTES), ("--fb-base", fb_base, 4),
                              ("--status-base", status_base, 4)):
        if base < 0 or base >> 64 or base % align:
            raise FrameError(f"{name} {base:#x} must be a 64-bit address aligned to {align}")
    order = tile_order(f.row, f.col, cam.image_w, tile, blocks)
    rows, cols = f.row[order], f.col[order]
    ids = (rows.astype(np.int64) << xbits) | cols.astype(np.int64)
    recs = fragment_records(inp.subset(order), ids)
    pitch = PIX_BYTES * int(cam.image_w)
    bg = np.empty((cam.image_h, cam.image_w, 4), dtype=np.uint8)
    bg[..., :3] = shade.BACKGROUND
    bg[..., 3] = PIX_ALPHA
    h_base, h_img = fi.cfg.height
    regions = [Region("heights", h_base, h_img), Region("textures", fi.tex_base, fi.tex_image),
               Region("fragments", frag_base, recs.tobytes()),
               Region("framebuffer", fb_base, bg.tobytes())]
    if status_en:
        regions.append(Region("status", status_base, bytes(pitch * cam.image_h)))
    spans = sorted((r.base, r.base + len(r.data), r.name) for r in regions)
    for (b0, e0, n0), (b1, _, n1) in zip(spans, spans[1:]):
        if b1 < e0:
            raise FrameError(f"memory regions {n0} and {n1} overlap")
    desc = {"frag_base": frag_base, "frag_count": len(recs), "fb_base": fb_base,
            "fb_pitch": pitch, "xbits": xbits, "status_base": status_base,
            "status_en": int(status_en)}
    ctrl = pidm_regmap.reg("CTRL")
    return PackedFrame(regions, config_writes(fi.cfg), desc, descriptor_writes(desc),
                       (ctrl.addr, ctrl.value(start=1)), int(cam.image_w), int(cam.image_h), f,
                       order)


def expected_memory(packed: PackedFrame, ref: shade.Image) -> dict[str, bytes]:
    """What the framebuffer (and the status buffer) must hold after the frame: the model's image
    ``ref`` (:func:`model.shade.render` of the same frame and camera) as RGBA8 with A =
    PIX_ALPHA, and per covered pixel its status word (iterations, hit, invalid; no error)."""
    img = np.empty((packed.image_h, packed.image_w, 4), dtype=np.uint8)
    img[..., :3] = ref.rgb
    img[..., 3] = PIX_ALPHA
    out = {"framebuffer": img.tobytes()}
    if packed.descriptor["status_en"]:
        st = np.zeros((packed.image_h, packed.image_w), dtype="<u4")
        o = ref.out
        word = ((o.iterations.astype(np.int64) & ((1 << STW_ITERS_BITS) - 1)) << STW_ITERS_LSB) \
            | (o.hit.astype(np.int64) << STW_HIT_BIT) | (o.invalid.astype(np.int64) << STW_INVALID_BIT)
        st[ref.frags.row, ref.frags.col] = word.astype(np.uint32)
        out["status"] = st.tobytes()
    return out
