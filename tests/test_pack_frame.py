# SPDX-License-Identifier: Apache-2.0
"""The frame packer (scripts/pack_frame.py, tb/harness/pidm_frame.py): its memory images and its
register writes round-trip to the model's arrays and to the configuration ports the pipeline
harness drives (tb/harness/pipeline_words.config), its fragment records to the model's fragment
words, pixel ids to pixels; the C form compiles against the driver; bad input is one line, exit 2."""
from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from model import f24, heightmap, shade
from scripts import pack_frame
from tb.harness import dm_pipeline, pidm_frame, pidm_regmap, pipeline_words

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def scene():
    frame, cam = dm_pipeline.scene_frame("rocks", 32, "oblique", 24, "park")
    return frame, cam, pidm_frame.pack(frame, cam, tile=8)


def regs_of(writes):
    """The last value written to each register path."""
    by = pidm_regmap.by_address()
    return {by[a].path: v for a, v in writes}


def test_config_writes_round_trip_to_the_ports(scene):
    frame, _, packed = scene
    cfg = pipeline_words.config(frame, pipeline_words.HEIGHT_BASE, pipeline_words.COLOUR_BASE,
                                dm_pipeline._normal_base(frame))
    ports, tri, lvt = pidm_frame.ports_from_writes(packed.config)
    for name, _bits in dm_pipeline.CFG_PORTS:
        assert ports[name] == cfg.ports[name], name
    assert tri == cfg.tri_writes and len(tri) == 2 * len(frame.log2pb_colour)
    assert lvt == cfg.lvt_writes and len(lvt) == (1 + 2 * 2) * pipeline_words.TEX_LEVELS
    # every configuration register is written once, in address order, then the table
    addrs = [a for a, _ in packed.config]
    tt = pidm_regmap.reg("TT_WRITE").addr
    cfg_addrs = [a for a in addrs if a != tt]
    assert cfg_addrs == sorted(set(cfg_addrs))
    expect = sorted(r.addr for p, r in pidm_regmap.registers().items()
                    if p.split(".")[0] in ("HEIGHT", "SHADE", "TEX[0]", "TEX[1]"))
    assert cfg_addrs == expect


def test_a_changed_port_changes_the_writes(scene):
    """The inverse is not trivially the identity: one bit of a level-table write moves one
    register."""
    frame, _, packed = scene
    cfg = dm_pipeline.frame_image(frame).cfg
    i = cfg.lvt_writes.index(next(w for w in cfg.lvt_writes
                                  if w[0] == pipeline_words.lvt_addr(pipeline_words.LVT_TEX_OFF,
                                                                     1, 3)))
    a, d = cfg.lvt_writes[i]
    cfg.lvt_writes[i] = (a, d ^ 64)                                       # TEX[1].LEVEL_OFF[3] bit 6
    diff = [(a, v, w) for (a, v), (_, w) in zip(packed.config, pidm_frame.config_writes(cfg))
            if v != w]
    assert diff == [(pidm_regmap.reg("TEX[1].LEVEL_OFF[3]").addr, diff[0][1], diff[0][1] ^ 64)]


def test_height_image_round_trips(scene):
    frame, _, packed = scene
    r = regs_of(packed.config)
    img = packed.region("heights")
    assert r["HEIGHT.BASE"] == img.base
    mode = pidm_regmap.reg("HEIGHT.MODE").fields_of(r["HEIGHT.MODE"])
    pyr = frame.pyr
    assert mode["root_level"] == pyr.n and mode["bits16"] == 0
    n = 1 << pyr.n
    for k in range(pyr.n + 1):
        side = n >> k
        off = r[f"HEIGHT.LEVEL_OFF[{k}]"]
        lv = np.frombuffer(img.data, dtype=np.uint8, count=side * side, offset=off)
        assert np.array_equal(lv.reshape(side, side), pyr.levels[k]), k


def test_unorm16_heights_round_trip(tmp_path):
    rng = np.random.default_rng(5)
    h = rng.random((12, 20))
    pyr = heightmap.build(h, bits=16)
    frame, cam = dm_pipeline.scene_frame("rocks", 16, "front", 8, "park")
    frame = shade.Frame(pyr=pyr, colour=frame.colour, normals=frame.normals,
                        depth_scale=frame.depth_scale, log2pb_colour=frame.log2pb_colour,
                        log2pb_normal=frame.log2pb_normal, method="tevs", engine="f24", mip=False)
    packed = pidm_frame.pack(frame, cam)
    r = regs_of(packed.config)
    mode = pidm_regmap.reg("HEIGHT.MODE").fields_of(r["HEIGHT.MODE"])
    size = pidm_regmap.reg("HEIGHT.SIZE").fields_of(r["HEIGHT.SIZE"])
    assert mode["bits16"] == 1 and mode["method"] == 1 and (size["width"], size["height"]) == (20, 12)
    assert pidm_regmap.reg("SHADE.MIP").fields_of(r["SHADE.MIP"])["mip_en"] == 0
    data = packed.region("heights").data
    n = 1 << pyr.n
    for k in range(pyr.n + 1):
        side = n >> k
        lv = np.frombuffer(data, dtype="<u2", count=side * side, offset=r[f"HEIGHT.LEVEL_OFF[{k}]"])
        assert np.array_equal(lv.reshape(side, side), pyr.levels[k]), k


def test_texture_images_round_trip(scene):
    frame, _, packed = scene
    r = regs_of(packed.config)
    img = packed.region("textures")
    for x, tex in enumerate((frame.colour, frame.normals)):
        base = r[f"TEX[{x}].BASE"] - img.base
        assert base >= 0
        mip = pidm_regmap.reg("SHADE.MIP").fields_of(r["SHADE.MIP"])
        assert mip["levels_colour" if x == 0 else "levels_normal"] == tex.n_levels
        for k in range(tex.n_levels):
            sz = pidm_regmap.reg(f"TEX[{x}].LEVEL_SIZE[{k}]").fields_of(r[f"TEX[{x}].LEVEL_SIZE[{k}]"])
            w, h = sz["width"], sz["height"]
            lv = np.frombuffer(img.data, dtype=np.uint8, count=w * h * 4,
                               offset=base + r[f"TEX[{x}].LEVEL_OFF[{k}]"])
            assert np.array_equal(lv.reshape(h, w, 4), tex.levels[k]), (x, k)


def test_fragment_records_round_trip(scene):
    frame, cam, packed = scene
    buf = packed.region("fragments").data
    d = pidm_frame.decode_records(buf)
    f, inp = shade.pixel_inputs(cam)
    sub = inp.subset(packed.order)
    ref = pipeline_words.fragment_words(sub)       # the cocotb driver's packing of the ports
    assert len(buf) == pidm_frame.FRAG_BYTES * len(f) == pidm_frame.FRAG_BYTES * packed.descriptor["frag_count"]
    for key, port in (("u0", "frag_u0_i"), ("v0", "frag_v0_i"), ("pl0", "frag_pl0_i"),
                      ("tri", "frag_tri_i")):
        assert np.array_equal(d[key], ref[port]), key
    assert [pipeline_words.pack(row, 24) for row in d["tbn"]] == list(ref["frag_tbn_i"])
    assert [pipeline_words.pack(row, 24) for row in d["view"]] == list(ref["frag_view_i"])
    # the f24 words are the model's numbers rounded
    with np.errstate(invalid="ignore"):
        assert np.array_equal(d["u0"], f24.from_float(sub.u0).astype(np.int64))
    # pixel ids: (row << xbits) | col of the fragment's pixel, each pixel once
    xb = packed.descriptor["xbits"]
    assert xb == 5  # a 24-pixel row
    assert np.array_equal(d["id"] >> xb, f.row[packed.order])
    assert np.array_equal(d["id"] & ((1 << xb) - 1), f.col[packed.order])
    assert len(set(d["id"].tolist())) == len(f)
    assert sorted(packed.order.tolist()) == list(range(len(f)))
    # bits 31:24 of the f24 words are zero
    w = np.frombuffer(buf, dtype="<u4").reshape(-1, pidm_frame.FRAG_WORDS)
    f24_words = [i for i in range(pidm_frame.FRAG_WORDS) if i != pidm_frame.FRAG_ID_WORD]
    assert not (w[:, f24_words] >> 24).any()


def test_descriptor_and_framebuffer(scene):
    _, cam, packed = scene
    d = packed.descriptor
    assert d["fb_pitch"] == 4 * cam.image_w and d["status_en"] == 1
    r = regs_of(packed.frame_writes)
    assert r["FRAME.FRAG_BASE.LO"] == pidm_frame.FRAG_BASE and r["FRAME.FRAG_BASE.HI"] == 0
    assert r["FRAME.FRAG_COUNT"] == d["frag_count"] and r["FRAME.FB_PITCH"] == d["fb_pitch"]
    assert r["FRAME.FB_LAYOUT"] == (1 << 8) | d["xbits"]
    assert packed.start == (pidm_regmap.reg("CTRL").addr, 1)
    fb = np.frombuffer(packed.region("framebuffer").data, np.uint8).reshape(cam.image_h, cam.image_w, 4)
    assert (fb[..., :3] == shade.BACKGROUND).all() and (fb[..., 3] == 255).all()


def test_expected_memory_is_the_model_render(scene):
    frame, cam, packed = scene
    ref = shade.render(frame, cam)
    exp = pidm_frame.expected_memory(packed, ref)
    img = np.frombuffer(exp["framebuffer"], np.uint8).reshape(cam.image_h, cam.image_w, 4)
    assert np.array_equal(img[..., :3], ref.rgb)
    st = np.frombuffer(exp["status"], "<u4").reshape(cam.image_h, cam.image_w)
    f = ref.frags
    assert np.array_equal(st[f.row, f.col] & 0xFFFF, ref.out.iterations)
    assert np.array_equal((st[f.row, f.col] >> 16) & 1, ref.out.hit)
    assert np.array_equal((st[f.row, f.col] >> 17) & 1, ref.out.invalid)
    assert ref.out.hit.any()


def test_cli_writes_consistent_files(tmp_path):
    out = tmp_path / "f"
    assert pack_frame.main(["--scene", "rocks", "--size", "16", "--angle", "front",
                            "--frag-base", "0x1_0000_0000", "--no-status", "--out", str(out)]) == 0
    doc = json.loads((out / "frame.json").read_text())
    names = [r["name"] for r in doc["regions"]]
    assert names == ["heights", "textures", "fragments", "framebuffer"]
    for r in doc["regions"]:
        assert (out / r["file"]).stat().st_size == r["bytes"]
    assert doc["descriptor"]["frag_base"] == 1 << 32 and doc["descriptor"]["status_en"] == 0
    fr = {a: v for a, v in doc["frame_writes"]}
    assert fr[pidm_regmap.reg("FRAME.FRAG_BASE.HI").addr] == 1
    assert doc["fragment_record"]["FRAG_BYTES"] == 64
    # The C form compiles with the driver and holds the same writes.
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.fail("no C compiler")
    main_c = tmp_path / "m.c"
    main_c.write_text('#include <stdio.h>\n#include "frame_regs.h"\n'
                      "int main(void) { unsigned long s = 0;\n"
                      "  for (size_t i = 0; i < PIDM_FRAME_CONFIG_COUNT; i++)\n"
                      "    s = s * 31u + pidm_frame_config[i].off * 7u + pidm_frame_config[i].value;\n"
                      '  printf("%zu %lu %u %llx\\n", PIDM_FRAME_CONFIG_COUNT, s & 0xffffffffu,\n'
                      "         pidm_frame_desc.frag_count, (unsigned long long)pidm_frame_desc.frag_base);\n"
                      "  return 0; }\n")
    exe = tmp_path / "m"
    b = subprocess.run([cc, "-Wall", "-Wextra", "-Werror", "-std=c11", "-I", str(out),
                        "-I", str(ROOT / "sw"), "-o", str(exe), str(main_c), str(ROOT / "sw/pidm.c")],
                       capture_output=True, text=True)
    assert b.returncode == 0, b.stderr
    got = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout.split()
    s = 0
    for a, v in doc["config_writes"]:
        s = (s * 31 + a * 7 + v) & 0xFFFFFFFFFFFFFFFF
    assert got == [str(len(doc["config_writes"])), str(s & 0xFFFFFFFF),
                   str(doc["descriptor"]["frag_count"]), "100000000"]


@pytest.mark.parametrize("argv,msg", [
    (["--scene", "nope"], "unknown scene"),
    (["--method", "relief"], "has no RTL"),
    (["--size", "1"], "--size must be in"),
    (["--fb-base", "0x70000002"], "aligned to 4"),
    (["--frag-base", "0x60000020"], "aligned to 64"),
    (["--fb-base", "0x60000000"], "overlap"),
    (["--angle", "sideways"], "unknown angle"),
    (["--heightmap", "/nonexistent.png"], ""),
    (["--texture", "x.png"], "goes with --heightmap"),
])
def test_bad_input_is_one_line_exit_2(tmp_path, capsys, argv, msg):
    with pytest.raises(SystemExit) as e:
        pack_frame.main([*argv, "--size", "8", "--out", str(tmp_path / "o")] if "--size" not in argv
                        else [*argv, "--out", str(tmp_path / "o")])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("pack_frame.py: error:") and msg in err[0]
