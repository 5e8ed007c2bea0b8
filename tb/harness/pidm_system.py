# SPDX-License-Identifier: Apache-2.0
"""The system top ``rtl/top/pidm_top.sv`` as a renderer: a frame packed by
:func:`tb.harness.pidm_frame.pack` (memory regions and register writes) runs in a Verilator C++
harness (``tb/harness/system_harness.cpp``) that plays the CPU (AXI4-Lite register writes, the
interrupt, the statistics registers) and the memory (the fragment, height and texture read ports
and the framebuffer write port).

    img, stats = render_rtl(frame, cam)            # like tb.harness.dm_pipeline.render_rtl
    img, stats, heights = build_and_render(frame, cam, memory, rect)
                                                   # the pyramid built through the registers first

``img`` is read back from the framebuffer (RGBA8) and the status buffer (hit, invalid, error,
iterations per pixel): the same :class:`model.shade.Image` layout as the pipeline harness gives,
so the same comparison with the model applies (:func:`tb.harness.dm_pipeline.compare`).
``stats`` holds the harness's figures (``cycles``: clocks from the CTRL.start write to the
interrupt; the cache and memory counters read from the STATS registers) and the per-pixel ratios.

:func:`build_and_render` runs a pyramid build first, as a driver does (sw/pidm.c
``pidm_pyr_build``): the height region starts as ``memory`` (level 0 of the frame's map, the levels
above as an earlier build left them), the PYR registers describe the map and the dirty rectangle
(None: the whole map), ``CTRL.pyr_start``, the ``pyr_done`` interrupt; then the frame.  It returns
the height region's bytes after the build too, and ``stats["pyramid_cycles"]`` (CTRL.pyr_start to
the interrupt).

The harness is built on demand (:func:`build`) into ``build/harness/system/<variant>/``
(``fast`` or ``checked``, as :mod:`tb.harness.build` describes).  File formats:
``tb/harness/system_harness.h``.
"""
from __future__ import annotations

import dataclasses
import json
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from model import heightmap, shade
from model.camera import Camera, Fragments

from . import build as _build
from . import dm_pipeline, pidm_frame, pidm_regmap
from .build import BUILD, COMMON_SOURCES, HARNESS_DIR, ROOT, HarnessSpec, RtlEngineError

#: pidm_top parameters the harness is built with (-G and -DHARNESS_*).
PARAMS: dict[str, int] = {"DATA_W": 64}
#: pidm_top's pixel-id width (its default).
PIX_W = 24

SYSTEM = HarnessSpec(
    name="system", top="pidm_top",
    rtl_dirs=("common", "fp", "traverse", "cache", "mip", "pipe", "pyramid", "top"),
    sources=(HARNESS_DIR / "system_harness.cpp", HARNESS_DIR / "system_harness.h",
             ROOT / "sw" / "pidm_regs.h", *COMMON_SOURCES),
    binary="system_harness", params=PARAMS, build_dir=BUILD / "system",
    required=(ROOT / "rtl" / "top" / "pidm_top.sv",))

IN_MAGIC = b"SYSHIN01"
IN_VERSION = 2
OUT_MAGIC = b"SYSHOUT2"
PORTS = {"fragments": 0, "heights": 1, "textures": 2, "framebuffer": 3, "status": 4}


def build(variant: str = "fast", *, force: bool = False, quiet: bool = True) -> Path:
    """Build the system harness variant when its inputs changed; returns the binary."""
    return _build.build(SYSTEM, variant, force=force, quiet=quiet)


def is_built(variant: str = "fast") -> bool:
    return _build.is_built(SYSTEM, variant)


def register_writes(packed: pidm_frame.PackedFrame) -> list[tuple[int, int]]:
    """What the driver writes, in order: interrupts cleared and frame_done enabled, errors
    cleared, the configuration and triangle table, the frame descriptor, the statistics cleared,
    and last CTRL.start."""
    R = pidm_regmap.reg
    return ([(R("INTR_STATE").addr, R("INTR_STATE").value(frame_done=1, axi_error=1)),
             (R("INTR_ENABLE").addr, R("INTR_ENABLE").value(frame_done=1, axi_error=1)),
             (R("ERROR").addr, 0xFFFF_FFFF)]
            + list(packed.config) + list(packed.frame_writes)
            + [(R("CTRL").addr, R("CTRL").value(clear_stats=1)), packed.start])


def pyramid_writes(pyr: heightmap.Pyramid, base: int,
                   rect: tuple[int, int, int, int] | None) -> list[tuple[int, int]]:
    """A pyramid build's register writes as pidm_pyr_build makes them (level 0 and the pyramid
    image both at ``base``; ``rect`` None: the whole map), the last one CTRL.pyr_start."""
    R = pidm_regmap.reg
    x0, y0, x1, y1 = rect if rect is not None else (0, 0, pyr.width - 1, pyr.height - 1)
    n_off = sum(1 for k in pidm_regmap.registers() if k.startswith("PYR.LEVEL_OFF["))
    offs = pyr.level_offsets() + [0] * (n_off - pyr.n - 1)
    w: list[tuple[int, int]] = [
        (R("PYR.FORMAT").addr, R("PYR.FORMAT").value(bits16=int(pyr.bits == 16))),
        (R("PYR.SIZE").addr, R("PYR.SIZE").value(width=pyr.width, height=pyr.height))]
    for reg in ("PYR.SRC_BASE", "PYR.PYR_BASE"):
        w += [(R(f"{reg}.LO").addr, base & 0xFFFF_FFFF), (R(f"{reg}.HI").addr, base >> 32)]
    w += [(R("PYR.DIRTY0").addr, R("PYR.DIRTY0").value(x0=x0, y0=y0)),
          (R("PYR.DIRTY1").addr, R("PYR.DIRTY1").value(x1=x1, y1=y1))]
    w += [(R(f"PYR.LEVEL_OFF[{k}]").addr, off) for k, off in enumerate(offs)]
    return w + [(R("INTR_STATE").addr, R("INTR_STATE").value(pyr_done=1, axi_error=1)),
                (R("INTR_ENABLE").addr, R("INTR_ENABLE").value(pyr_done=1, axi_error=1)),
                (R("CTRL").addr, R("CTRL").value(pyr_start=1))]


def write_input(path: Path, packed: pidm_frame.PackedFrame,
                pyr_writes: list[tuple[int, int]] | None = None) -> None:
    """The harness input (system_harness.h): ``pyr_writes`` (a pyramid build) before the
    frame's writes."""
    fb = packed.region("framebuffer")
    st = next((r for r in packed.regions if r.name == "status"), None)
    pw = list(pyr_writes or [])
    writes = pw + register_writes(packed)
    for base in [r.base for r in packed.regions]:
        if base >> 32:
            raise RtlEngineError("the system harness takes 32-bit addresses")
    head = np.zeros(16, dtype="<u4")
    head[0:2] = np.frombuffer(IN_MAGIC, dtype="<u4")
    head[2:12] = [IN_VERSION, 64, len(packed.regions), len(writes), fb.base, len(fb.data),
                  st.base if st else 0, len(st.data) if st else 0,
                  packed.descriptor["frag_count"], len(pw)]
    with open(path, "wb") as f:
        f.write(head.tobytes())
        for r in packed.regions:
            f.write(np.array([PORTS[r.name], r.base, len(r.data)], dtype="<u4").tobytes())
            f.write(r.data)
            f.write(bytes(-len(r.data) % 4))
        f.write(np.array(writes, dtype="<u4").reshape(-1, 2).tobytes())


def read_output(path: Path) -> tuple[bytes, bytes, bytes]:
    """The framebuffer, the status buffer and the height region after the run."""
    raw = Path(path).read_bytes()
    if len(raw) < 32 or raw[:8] != OUT_MAGIC:
        raise RtlEngineError(f"{path}: not a system harness output file")
    nfb, nst, nh = (int(x) for x in np.frombuffer(raw[8:20], dtype="<u4"))
    o_st = 32 + nfb + (-nfb % 4)
    o_h = o_st + nst + (-nst % 4)
    if len(raw) != o_h + nh + (-nh % 4):
        raise RtlEngineError(f"{path}: {len(raw)} bytes for a {nfb}-byte framebuffer, a "
                             f"{nst}-byte status buffer and {nh} bytes of heights")
    return raw[32:32 + nfb], raw[o_st:o_st + nst], raw[o_h:o_h + nh]


def render_rtl(frame: shade.Frame, cam: Camera, *, tile: int = dm_pipeline.DEFAULT_TILE,
               blocks: str = dm_pipeline.DEFAULT_BLOCKS, frags: Fragments | None = None,
               latency: int | tuple[int, int] = dm_pipeline.DEFAULT_LATENCY, seed: int = 0,
               checked: bool | None = None, **_: Any) -> tuple[shade.Image, dict[str, Any]]:
    """Render the camera's image through pidm_top (see the module docstring)."""
    img, stats, _heights = _run(frame, cam, None, None, tile=tile, blocks=blocks, frags=frags,
                                latency=latency, seed=seed, checked=checked)
    return img, stats


def build_and_render(frame: shade.Frame, cam: Camera, memory: bytes,
                     rect: tuple[int, int, int, int] | None, *, build_pyramid: bool = True,
                     tile: int = dm_pipeline.DEFAULT_TILE,
                     blocks: str = dm_pipeline.DEFAULT_BLOCKS,
                     latency: int | tuple[int, int] = dm_pipeline.DEFAULT_LATENCY, seed: int = 0,
                     checked: bool | None = None
                     ) -> tuple[shade.Image, dict[str, Any], bytes]:
    """A pyramid build of ``frame.pyr`` through the registers on the height region ``memory``
    (``rect``: the dirty rectangle, None the whole map), then the frame (module docstring).
    ``build_pyramid`` False: no build, the frame reads ``memory`` as it is."""
    return _run(frame, cam, memory, rect, tile=tile, blocks=blocks, frags=None, latency=latency,
                seed=seed, checked=checked, build_pyramid=build_pyramid)


def _run(frame: shade.Frame, cam: Camera, memory: bytes | None,
         rect: tuple[int, int, int, int] | None, *, tile: int, blocks: str,
         frags: Fragments | None, latency: int | tuple[int, int], seed: int,
         checked: bool | None, build_pyramid: bool = True
         ) -> tuple[shade.Image, dict[str, Any], bytes]:
    variant = dm_pipeline.default_variant(checked)
    exe = build(variant)
    try:
        packed = pidm_frame.pack(frame, cam, tile=tile, blocks=blocks, pix_w=PIX_W, frags=frags)
    except pidm_frame.FrameError as e:
        raise RtlEngineError(str(e)) from None
    pw = None
    if memory is not None:
        h = packed.region("heights")
        if len(memory) != len(h.data):
            raise RtlEngineError(f"height memory of {len(memory)} bytes for a "
                                 f"{len(h.data)}-byte pyramid image")
        packed = dataclasses.replace(packed, regions=[
            dataclasses.replace(r, data=bytes(memory)) if r.name == "heights" else r
            for r in packed.regions])
        pw = pyramid_writes(frame.pyr, h.base, rect) if build_pyramid else None
    lo, hi = (latency, latency) if isinstance(latency, (int, np.integer)) else latency
    with tempfile.TemporaryDirectory(prefix="pidm_system_") as tmp:
        tdir = Path(tmp)
        write_input(tdir / "in.bin", packed, pw)
        cmd = [str(exe), "--in", str(tdir / "in.bin"), "--out", str(tdir / "out.bin"),
               "--stats", str(tdir / "stats.json"), "--latency", f"{int(lo)}:{int(hi)}",
               "--seed", str(int(seed)), "--quiet"]
        t0 = time.monotonic()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.monotonic() - t0
        if p.returncode != 0:
            raise RtlEngineError(f"system harness exit status {p.returncode}: "
                                 + (p.stderr.strip() or p.stdout.strip()))
        fb, stw, heights = read_output(tdir / "out.bin")
        stats: dict[str, Any] = json.loads((tdir / "stats.json").read_text())
    h, w = packed.image_h, packed.image_w
    img = np.frombuffer(fb, dtype=np.uint8).reshape(h, w, 4)[..., :3].copy()
    f = packed.frags
    words = np.frombuffer(stw, dtype="<u4").reshape(h, w)[f.row, f.col].astype(np.int64)
    hit = ((words >> pidm_frame.STW_HIT_BIT) & 1).astype(bool)
    inval = ((words >> pidm_frame.STW_INVALID_BIT) & 1).astype(bool)
    err = ((words >> pidm_frame.STW_ERR_BIT) & 1).astype(bool)
    iters = (words >> pidm_frame.STW_ITERS_LSB) & ((1 << pidm_frame.STW_ITERS_BITS) - 1)
    none = np.full(len(f), -1, dtype=np.int64)
    out = shade.PixelOutputs(img[f.row, f.col], hit, inval, iters, none, none.copy())
    stats.update(dm_pipeline.derived_stats(stats))
    stats.update({"hits": int(hit.sum()), "invalid": int(inval.sum()), "errors": int(err.sum()),
                  "harness_variant": f"system-{variant}", "harness_wall_seconds": round(wall, 3),
                  "tile": tile, "top": "pidm_top"})
    return shade.Image(img, f, out), stats, heights
