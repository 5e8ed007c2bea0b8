# SPDX-License-Identifier: Apache-2.0
"""The host C driver (sw/pidm.c, over the generated sw/pidm_regs.h) builds with the machine's C
compiler (-Wall -Wextra -Werror -std=c11) and passes its unit test (sw/test_pidm.c: the driver
against a register file in memory, every write checked by address and value); a driver with a
wrong bit fails that test."""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SW = ROOT / "sw"
CFLAGS = ["-Wall", "-Wextra", "-Werror", "-std=c11"]


def cc() -> str:
    """The C compiler: $CC, else cc, else gcc."""
    for c in (os.environ.get("CC"), "cc", "gcc"):
        if c and shutil.which(c):
            return c
    pytest.fail("no C compiler (cc) on PATH")


def build_and_run(tmp: Path, driver: Path, opt: str) -> subprocess.CompletedProcess[str]:
    exe = tmp / f"test_pidm{opt}"
    b = subprocess.run([cc(), *CFLAGS, opt, "-I", str(SW), "-o", str(exe), str(driver),
                        str(SW / "test_pidm.c")], capture_output=True, text=True)
    assert b.returncode == 0, b.stderr
    return subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)


@pytest.mark.parametrize("opt", ["-O0", "-O2"])
def test_driver_unit_test_passes(tmp_path, opt):
    r = build_and_run(tmp_path, SW / "pidm.c", opt)
    print(r.stdout, r.stderr)
    assert r.returncode == 0, r.stdout + r.stderr
    line = r.stdout.strip().splitlines()[-1]
    assert line.startswith("test_pidm: ") and line.endswith(" checks, 0 failed"), line
    assert int(line.split()[1]) >= 60


@pytest.mark.parametrize("old,new", [
    ("PIDM_REGS__CTRL__START_bm);", "PIDM_REGS__CTRL__SOFT_RESET_bm);"),   # start pulses reset
    ("pidm_wr(dev, PIDM_OFF(INTR_STATE), st);", "pidm_wr(dev, PIDM_OFF(INTR_STATE), 0);"),
    ("off + 4u, (uint32_t)(v >> 32)", "off + 4u, (uint32_t)v"),            # 64-bit address
])
def test_a_wrong_driver_fails(tmp_path, old, new):
    text = (SW / "pidm.c").read_text()
    assert old in text
    bad = tmp_path / "pidm.c"
    bad.write_text(text.replace(old, new, 1))
    r = build_and_run(tmp_path, bad, "-O0")
    assert r.returncode != 0 and " failed" in r.stdout.strip().splitlines()[-1]
    assert "check failed" in r.stderr or "write log differs" in r.stderr
