"""Make the project root importable (model/, tb/) and report random seeds."""
import os
import random
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

# The RTL engine's harness with the RTL's SVA assertions compiled in (model/rtl_engine.py), also
# for the scripts the tests start as subprocesses.
os.environ.setdefault("RTL_ENGINE_CHECKED", "1")


@pytest.fixture
def rng(request) -> np.random.Generator:
    """A numpy Generator with a printed seed (SEED=... reproduces a run)."""
    seed = int(os.environ.get("SEED", random.randrange(1 << 31)))
    print(f"\n{request.node.name}: SEED={seed}")
    return np.random.default_rng(seed)
