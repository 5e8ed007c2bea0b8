# SPDX-License-Identifier: Apache-2.0
"""Run the hardware pyramid builder (``rtl/pyramid/pyr_build.sv``) on a sequence of height maps.

One simulation, one memory, one build per map, in order, as a frame loop does it: the driver writes
map k's level 0 (its padded square, padding zero, as ``Pyramid.memory_image``) over the pyramid's
level 0; map 0 gets a full build, every later map a dirty-rectangle rebuild of the bounding box of
the texels that changed since map k-1, on the memory that still holds the pyramid built for map
k-1 (no change: no build).  After each build the whole pyramid image (level 0 and levels 1..n, as
many bytes as ``Pyramid.memory_image()``) is read back from the memory and stored with the build's
clocks (start_i to done_o, :meth:`tb.pyr_build.test_pyr_build.Harness.build`).  No comparison
here: the caller (``scripts/animate.py``) compares the images with ``model.heightmap``.

    result = run_builds(codes, bits, work_dir)   # from Python (builds the simulation once)

Files (``.npz``): input ``codes`` (F, H, W) uint16, ``bits``; output ``image_<k>`` (uint8 bytes),
``clocks`` (F,), ``rects`` (F, 4) (x0, y0, x1, y1; -1 when no build ran).  Environment of the
cocotb module: PYR_RUN_IN, PYR_RUN_OUT.  The builder is pyr_build with the default test
configuration (64-bit AXI, maps up to 1024 a side, 16-beat bursts), the simulation is shared with
``tb/pyr_build``'s default build.
"""
from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import numpy as np
import numpy.typing as npt

ROOT = Path(__file__).resolve().parents[2]
#: The builder's parameters (tb/pyr_build's "default" configuration).
PYR_PARAMS: dict[str, int] = {"AXI_DATA_W": 64, "MAX_LG": 10, "BURST": 16}
#: Where the pyramid (level 0 first) sits in the simulated memory.
PYR_BASE = 0x4000_0000


@dataclass(frozen=True)
class BuildResult:
    """Per map: the pyramid image read back, the build's clocks (0: no build), the rectangle."""

    images: list[bytes]
    clocks: list[int]
    rects: list[tuple[int, int, int, int] | None]


def dirty_rect(old: npt.NDArray[np.uint16],
               new: npt.NDArray[np.uint16]) -> tuple[int, int, int, int] | None:
    """Bounding box (x0, y0, x1, y1) of the texels that differ, None when none does."""
    ys, xs = np.nonzero(old != new)
    if len(xs) == 0:
        return None
    return int(xs.min()), int(ys.min()), int(xs.max()), int(ys.max())


# ---- the cocotb side (runs inside the simulation) ----------------------------------------------

try:
    import cocotb
    from cocotb.triggers import RisingEdge  # noqa: F401 (the harness awaits it)
except ImportError:  # pragma: no cover - cocotb is part of the project's environment
    cocotb = None  # type: ignore[assignment]

if cocotb is not None:
    @cocotb.test()
    async def build_sequence(dut) -> None:  # type: ignore[no-untyped-def]
        """Build every map of PYR_RUN_IN in turn; write the images and clocks to PYR_RUN_OUT."""
        import random

        from model import heightmap
        from tb.pyr_build.test_pyr_build import Harness

        data = np.load(os.environ["PYR_RUN_IN"])
        codes, bits = data["codes"], int(data["bits"])
        h = Harness(dut, random.Random(0))   # no pauses: clocks of an idle bus
        h.pyr_base = PYR_BASE
        await h.reset()
        images: dict[str, npt.NDArray[np.uint8]] = {}
        clocks: list[int] = []
        rects: list[list[int]] = []
        prev = None
        for k in range(codes.shape[0]):
            pyr = heightmap.build(codes[k], bits)
            img = pyr.memory_image()
            lv0 = pyr.levels[0].astype("<u1" if bits == 8 else "<u2").tobytes()
            h.mem.write(PYR_BASE, lv0)
            rect = (0, 0, pyr.width - 1, pyr.height - 1) if prev is None else \
                dirty_rect(prev, codes[k])
            if rect is None:
                n = 0
            else:
                n, err = await h.build(pyr, PYR_BASE, rect)
                assert err == 0, f"map {k}: err_code {err}"
            dut._log.info("map %d: rectangle %s, %d clocks", k, rect, n)
            images[f"image_{k}"] = np.frombuffer(h.mem.read(PYR_BASE, len(img)), dtype=np.uint8)
            clocks.append(n)
            rects.append(list(rect) if rect is not None else [-1, -1, -1, -1])
            prev = codes[k]
        np.savez(os.environ["PYR_RUN_OUT"], clocks=np.array(clocks, dtype=np.int64),
                 rects=np.array(rects, dtype=np.int64).reshape(-1, 4), **images)


# ---- the host side -----------------------------------------------------------------------------

def run_builds(codes: Sequence[npt.NDArray[np.uint16]] | npt.NDArray[np.uint16], bits: int,
               work_dir: Path, log: Path | None = None) -> BuildResult:
    """Run the builder on ``codes`` (F maps of one size) in one simulation; returns what it wrote.

    The simulation's output (build and run) goes to ``log`` (default ``work_dir/pyr_run.log``);
    raises RuntimeError (one line, naming the log) when it fails.
    """
    arr = np.asarray(codes, dtype=np.uint16)
    if arr.ndim != 3 or arr.shape[0] < 1:
        raise ValueError(f"codes are (F, H, W) maps, got shape {arr.shape}")
    work_dir.mkdir(parents=True, exist_ok=True)
    inp, out = work_dir / "pyr_run_in.npz", work_dir / "pyr_run_out.npz"
    log = log or work_dir / "pyr_run.log"
    out.unlink(missing_ok=True)
    np.savez(inp, codes=arr, bits=np.int64(bits))
    env = dict(os.environ, PYR_RUN_IN=str(inp.resolve()), PYR_RUN_OUT=str(out.resolve()))
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    with open(log, "w") as f:
        p = subprocess.run([sys.executable, "-m", "tb.harness.pyr_run"], stdout=f,
                           stderr=subprocess.STDOUT, env=env, cwd=ROOT)
    if p.returncode != 0 or not out.is_file():
        raise RuntimeError(f"pyr_build simulation failed (exit status {p.returncode}), log {log}")
    with np.load(out) as r:
        images = [r[f"image_{k}"].tobytes() for k in range(arr.shape[0])]
        clocks = [int(c) for c in r["clocks"]]
        rects: list[tuple[int, int, int, int] | None] = [
            None if int(q[0]) < 0 else (int(q[0]), int(q[1]), int(q[2]), int(q[3]))
            for q in r["rects"]]
    return BuildResult(images, clocks, rects)


def _simulate() -> None:
    """Build (once per parameter set) and run the cocotb module (PYR_RUN_IN / PYR_RUN_OUT set)."""
    import json

    from tb.common import runner

    env = {"PYR_CFG": json.dumps(PYR_PARAMS), "PYR_RUN_IN": os.environ["PYR_RUN_IN"],
           "PYR_RUN_OUT": os.environ["PYR_RUN_OUT"]}
    runner.run("pyr_build", "pyr_run", Path(__file__).parent, parameters=PYR_PARAMS,
               name="pyr_build-default", extra_env=env)


if __name__ == "__main__":
    _simulate()
