#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Pack a frame for the system top pidm_top: memory images and the register write list.

  pack_frame.py [--scene NAME | --heightmap FILE [--texture FILE]] [--angle A] [--method NAME]
                [--size N] [--map-size N] [--bits 8|16] [--no-mip] [--tile N] [--blocks rows|morton]
                [--frag-base ADDR] [--fb-base ADDR] [--status-base ADDR] [--no-status]
                [--expected] --out DIR

The scene, camera and fragments are the model's, built as ``make render`` builds them
(tb.harness.dm_pipeline.scene_frame; a user height map as scripts/render.py does), and packed by
tb.harness.pidm_frame.  DIR receives:
  heights.bin, textures.bin        the height pyramid and the colour + normal MIP chains
  fragments.bin                    the fragment buffer (64-byte records, docs/system.md)
  framebuffer.bin                  the framebuffer's initial contents (the background colour)
  status.bin                       the status-word buffer's initial contents (zeros; not with
                                   --no-status)
  frame.json                       every region (file, base address, bytes), the configuration
                                   writes (HEIGHT, SHADE, TEX, TT_WRITE), the frame descriptor
                                   and its FRAME writes, the CTRL write that starts the frame
  frame_regs.h                     the same writes and descriptor for C (sw/pidm.h types):
                                   pidm_load_config(dev, pidm_frame_config, PIDM_FRAME_CONFIG_COUNT);
                                   pidm_start(dev, &pidm_frame_desc);
  expected_framebuffer.bin, expected_status.bin   with --expected: what the buffers hold after the
                                   frame (the model's f24 render)
Bad input: one line naming the problem, exit status 2.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
from model import camera, heightmap, scenes, shade, texture, traverse
from model.cli import Parser, fail

PROG = "pack_frame.py"
MAX_SIZE = 4096


def parse_int(what: str, text: str, lo: int, hi: int) -> int:
    """An integer (decimal or 0x hex) in [lo, hi], else a one-line error."""
    try:
        v = int(text, 0)
    except ValueError:
        fail(PROG, f"{what} must be an integer, got {text!r}")
    if not lo <= v <= hi:
        fail(PROG, f"{what} must be in {lo:#x}..{hi:#x}, got {text!r}")
    return v


def parse_angle(text: str) -> str | float:
    """A named view (front, oblique, grazing) or an elevation in degrees."""
    if text in camera.VIEWS:
        return text
    try:
        deg = float(text)
    except ValueError:
        fail(PROG, f"unknown angle {text!r} (front, oblique, grazing or an elevation in degrees)")
    if not 0 < deg <= 90:
        fail(PROG, f"elevation must be in (0, 90] degrees, got {text!r}")
    return deg


def build_frame(args: Any) -> tuple[shade.Frame, camera.Camera, str]:
    """The model frame and camera, as make render builds them."""
    from tb.harness import dm_pipeline

    angle = parse_angle(args.angle)
    size = parse_int("--size", args.size, 2, MAX_SIZE)
    if args.method not in traverse.EXACT_METHODS:
        fail(PROG, f"method {args.method!r} has no RTL (exact methods: "
                   f"{', '.join(traverse.EXACT_METHODS)})")
    if args.heightmap is None:
        if args.texture is not None:
            fail(PROG, "--texture goes with --heightmap (a scene has its own)")
        name = args.scene or "rocks"
        if name not in scenes.SCENES:
            fail(PROG, f"unknown scene {name!r} (valid scenes: {', '.join(scenes.SCENES)})")
        msize = parse_int("--map-size", args.map_size or str(size), 2, MAX_SIZE)
        if args.bits != 8:
            fail(PROG, "--bits 16 goes with --heightmap (scenes are unorm8, as make render)")
        frame, cam = dm_pipeline.scene_frame(name, msize, angle, size, args.method,
                                             mip=not args.no_mip)
        return frame, cam, name
    if args.map_size is not None:
        fail(PROG, "--map-size applies to --scene only (a height map file has its own size)")
    from scripts.render import height_ramp, load_map_image
    try:
        h = heightmap.load(args.heightmap)
    except heightmap.HeightMapError as e:
        fail(PROG, str(e).splitlines()[0])
    except Exception as e:  # OpenImageIO reports some problems as exceptions
        fail(PROG, f"cannot read {args.heightmap}: {e}".splitlines()[0])
    depth = camera.depth_scale(h.shape[1], h.shape[0])
    colour = (load_map_image("--texture", args.texture) if args.texture is not None
              else height_ramp(h))
    normal_codes = scenes.encode_normals(scenes.normal_map(h, depth))
    pyr = heightmap.build(h, bits=args.bits)
    tex, ntex = texture.build(colour), texture.build(normal_codes)
    try:
        cam = camera.Camera.for_view(angle, pyr.width, pyr.height, size, size, depth_scale=depth)
    except ValueError as e:
        fail(PROG, str(e))
    frame = shade.Frame(pyr=pyr, colour=tex, normals=ntex, depth_scale=depth,
                        log2pb_colour=cam.log2_pb(tex.width, tex.height),
                        log2pb_normal=cam.log2_pb(ntex.width, ntex.height),
                        method=args.method, engine="f24", mip=not args.no_mip)
    return frame, cam, str(args.heightmap)


def c_header(packed: Any, source: str) -> str:
    """frame_regs.h: the writes and the descriptor as C (sw/pidm.h types)."""
    lines = ["// SPDX-License-Identifier: Apache-2.0",
             f"// Generated by scripts/pack_frame.py ({source}, {packed.image_w} x "
             f"{packed.image_h}): the register writes of one frame for sw/pidm.h.",
             "#ifndef PIDM_FRAME_REGS_H", "#define PIDM_FRAME_REGS_H", "",
             '#include "pidm.h"', ""]
    lines.append(f"#define PIDM_FRAME_IMAGE_W {packed.image_w}u")
    lines.append(f"#define PIDM_FRAME_IMAGE_H {packed.image_h}u")
    for r in packed.regions:
        n = r.name.upper()
        lines.append(f"#define PIDM_FRAME_{n}_BASE 0x{r.base:x}ull")
        lines.append(f"#define PIDM_FRAME_{n}_BYTES {len(r.data)}u")
    lines += ["", "static const struct pidm_reg_write pidm_frame_config[] = {"]
    lines += [f"    {{0x{a:03x}u, 0x{v:08x}u}}," for a, v in packed.config]
    lines += ["};", "#define PIDM_FRAME_CONFIG_COUNT "
              "(sizeof pidm_frame_config / sizeof pidm_frame_config[0])", ""]
    d = packed.descriptor
    lines += ["static const struct pidm_frame pidm_frame_desc = {",
              f"    .frag_base = 0x{d['frag_base']:x}ull, .frag_count = {d['frag_count']}u,",
              f"    .fb_base = 0x{d['fb_base']:x}ull, .fb_pitch = {d['fb_pitch']}u, "
              f".xbits = {d['xbits']}u,",
              f"    .status_base = 0x{d['status_base']:x}ull, .status_en = {d['status_en']},",
              "};", "", "#endif  // PIDM_FRAME_REGS_H", ""]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    src = ap.add_mutually_exclusive_group()
    src.add_argument("--scene", help=f"procedural scene: {', '.join(scenes.SCENES)} (default rocks)")
    src.add_argument("--heightmap", type=Path, help="height map: image (OpenImageIO) or .npy")
    ap.add_argument("--texture", type=Path, help="colour texture for --heightmap")
    ap.add_argument("--angle", default="oblique", help="front | oblique | grazing | degrees")
    ap.add_argument("--method", default="park", help="exact method (default park)")
    ap.add_argument("--size", default="64", help="image N x N pixels (default 64)")
    ap.add_argument("--map-size", help="map N x N texels of a scene (default: --size)")
    ap.add_argument("--bits", type=int, default=8, choices=(8, 16), help="height storage")
    ap.add_argument("--no-mip", action="store_true", help="texture level 0 only")
    ap.add_argument("--tile", default="16", help="fragments in N x N pixel blocks (default 16)")
    ap.add_argument("--blocks", default="rows", choices=("rows", "morton"))
    ap.add_argument("--frag-base", default="0x60000000", help="fragment buffer address")
    ap.add_argument("--fb-base", default="0x70000000", help="framebuffer address")
    ap.add_argument("--status-base", default="0x78000000", help="status-word buffer address")
    ap.add_argument("--no-status", action="store_true", help="no per-pixel status words")
    ap.add_argument("--expected", action="store_true",
                    help="also write the buffers' expected contents (the model's render)")
    ap.add_argument("--out", type=Path, required=True, help="output directory")
    args = ap.parse_args(argv)

    from tb.harness import pidm_frame

    a64 = (1 << 64) - 1
    bases = {k: parse_int(f"--{k.replace('_', '-')}", getattr(args, k), 0, a64)
             for k in ("frag_base", "fb_base", "status_base")}
    tile = parse_int("--tile", args.tile, 1, MAX_SIZE)
    if args.out.exists() and not args.out.is_dir():
        fail(PROG, f"--out {args.out} exists and is not a directory")
    frame, cam, source = build_frame(args)
    try:
        packed = pidm_frame.pack(frame, cam, tile=tile, blocks=args.blocks,
                                 status_en=not args.no_status, **bases)
    except pidm_frame.FrameError as e:
        fail(PROG, str(e))
    try:
        args.out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        fail(PROG, f"cannot create {args.out}: {e.strerror or e}")
    regions = []
    for r in packed.regions:
        (args.out / f"{r.name}.bin").write_bytes(r.data)
        regions.append({"name": r.name, "file": f"{r.name}.bin", "base": r.base,
                        "bytes": len(r.data)})
    expected = []
    if args.expected:
        ref = shade.render(frame, cam)
        for name, data in pidm_frame.expected_memory(packed, ref).items():
            (args.out / f"expected_{name}.bin").write_bytes(data)
            expected.append({"name": name, "file": f"expected_{name}.bin",
                             "base": packed.region(name).base, "bytes": len(data)})
    rec = {k: getattr(pidm_frame, k) for k in (
        "FRAG_BYTES", "FRAG_WORDS", "FRAG_U0_WORD", "FRAG_V0_WORD", "FRAG_PL0_WORD",
        "FRAG_TRI_WORD", "FRAG_TRI_LSB", "FRAG_TRI_BITS", "FRAG_ID_WORD", "FRAG_ID_LSB",
        "FRAG_ID_BITS", "FRAG_TBN_WORD", "FRAG_VIEW_WORD")}
    doc = {"format": "pidm-frame", "version": 1, "source": source,
           "method": frame.method, "mip": bool(frame.mip),
           "image": {"width": packed.image_w, "height": packed.image_h},
           "regions": regions, "expected": expected,
           "config_writes": [[a, v] for a, v in packed.config],
           "descriptor": packed.descriptor,
           "frame_writes": [[a, v] for a, v in packed.frame_writes],
           "start": list(packed.start), "fragment_record": rec}
    (args.out / "frame.json").write_text(json.dumps(doc, indent=1) + "\n")
    (args.out / "frame_regs.h").write_text(c_header(packed, source))
    print(f"pack_frame: {packed.descriptor['frag_count']} fragments, "
          f"{len(packed.config)} configuration writes, {len(regions)} regions -> {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
