# SPDX-License-Identifier: Apache-2.0
"""The system top ``rtl/top/pidm_top.sv`` as a renderer: a frame packed by
:func:`tb.harness.pidm_frame.pack` (memory regions and register writes) runs in a Verilator C++
harness (``tb/harness/system_harness.cpp``) that plays the CPU (AXI4-Lite register writes, the
interrupt, the statistics registers) and the memory (the fragment, height and texture read ports
and the framebuffer write port).

    img, stats = render_rtl(frame, cam)            # like tb.harness.dm_pipeline.render_rtl

``img`` is read back from the framebuffer (RGBA8) and the status buffer (hit, invalid, error,
iterations per pixel): the same :class:`model.shade.Image` layout as the pipeline harness gives,
so the same comparison with the model applies (:func:`tb.harness.dm_pipeline.compare`).
``stats`` holds the harness's figures (``cycles``: clocks from the CTRL.start write to the
interrupt; the cache and memory counters read from the STATS registers) and the per-pixel ratios.

The harness is built on demand (:func:`build`) into ``build/harness/system/<variant>/``
(``fast`` or ``checked``, as :mod:`tb.harness.build` describes).  File formats:
``tb/harness/system_harness.h``.
"""
from __future__ import annotations

import json
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from model import shade
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
IN_VERSION = 1
OUT_MAGIC = b"SYSHOUT1"
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


def write_input(path: Path, packed: pidm_frame.PackedFrame) -> None:
    """The harness input (system_harness.h)."""
    fb = packed.region("framebuffer")
    st = next((r for r in packed.regions if r.name == "status"), None)
    writes = register_writes(packed)
    for base in [r.base for r in packed.regions]:
        if base >> 32:
            raise RtlEngineError("the system harness takes 32-bit addresses")
    head = np.zeros(16, dtype="<u4")
    head[0:2] = np.frombuffer(IN_MAGIC, dtype="<u4")
    head[2:11] = [IN_VERSION, 64, len(packed.regions), len(writes), fb.base, len(fb.data),
                  st.base if st else 0, len(st.data) if st else 0,
                  packed.descriptor["frag_count"]]
    with open(path, "wb") as f:
        f.write(head.tobytes())
        for r in packed.regions:
            f.write(np.array([PORTS[r.name], r.base, len(r.data)], dtype="<u4").tobytes())
            f.write(r.data)
            f.write(bytes(-len(r.data) % 4))
        f.write(np.array(writes, dtype="<u4").reshape(-1, 2).tobytes())


def read_output(path: Path) -> tuple[bytes, bytes]:
    raw = Path(path).read_bytes()
    if len(raw) < 16 or raw[:8] != OUT_MAGIC:
        raise RtlEngineError(f"{path}: not a system harness output file")
    nfb, nst = (int(x) for x in np.frombuffer(raw[8:16], dtype="<u4"))
    o_st = 16 + nfb + (-nfb % 4)
    if len(raw) != o_st + nst + (-nst % 4):
        raise RtlEngineError(f"{path}: {len(raw)} bytes for a {nfb}-byte framebuffer and a "
                             f"{nst}-byte status buffer")
    return raw[16:16 + nfb], raw[o_st:o_st + nst]


def render_rtl(frame: shade.Frame, cam: Camera, *, tile: int = dm_pipeline.DEFAULT_TILE,
               blocks: str = dm_pipeline.DEFAULT_BLOCKS, frags: Fragments | None = None,
               latency: int | tuple[int, int] = dm_pipeline.DEFAULT_LATENCY, seed: int = 0,
               checked: bool | None = None, **_: Any) -> tuple[shade.Image, dict[str, Any]]:
    """Render the camera's image through pidm_top (see the module docstring)."""
    variant = dm_pipeline.default_variant(checked)
    exe = build(variant)
    try:
        packed = pidm_frame.pack(frame, cam, tile=tile, blocks=blocks, pix_w=PIX_W, frags=frags)
    except pidm_frame.FrameError as e:
        raise RtlEngineError(str(e)) from None
    lo, hi = (latency, latency) if isinstance(latency, (int, np.integer)) else latency
    with tempfile.TemporaryDirectory(prefix="pidm_system_") as tmp:
        tdir = Path(tmp)
        write_input(tdir / "in.bin", packed)
        cmd = [str(exe), "--in", str(tdir / "in.bin"), "--out", str(tdir / "out.bin"),
               "--stats", str(tdir / "stats.json"), "--latency", f"{int(lo)}:{int(hi)}",
               "--seed", str(int(seed)), "--quiet"]
        t0 = time.monotonic()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.monotonic() - t0
        if p.returncode != 0:
            raise RtlEngineError(f"system harness exit status {p.returncode}: "
                                 + (p.stderr.strip() or p.stdout.strip()))
        fb, stw = read_output(tdir / "out.bin")
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
    return shade.Image(img, f, out), stats
