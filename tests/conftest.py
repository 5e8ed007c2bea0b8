# SPDX-License-Identifier: Apache-2.0
"""Report random seeds and set the test environment (the project itself imports as an installed
package: `make setup` runs `pip install -e .`; pytest puts tests/ on the path for the helpers
here, reference_walk and f24_mpfr)."""
import os
import random

import numpy as np
import pytest


# The Verilator harnesses with the RTL's SVA assertions compiled in (tb/harness/build.py), also
# for the scripts the tests start as subprocesses.
os.environ.setdefault("RTL_ENGINE_CHECKED", "1")


def pytest_collection_finish(session: pytest.Session) -> None:
    """Under ``--dist loadgroup`` every test with an ``xdist_group`` mark must carry its group in
    its node id (``...@group``), or pytest-xdist spreads the group over the workers: tests that
    wait for a harness another test builds then skip or build it twice.  pytest 9.2 with
    pytest-xdist 3.8 is such a pair (requirements.txt pins pytest 9.1.1)."""
    if not session.config.getoption("loadgroup", default=False):
        return
    lost = [i.nodeid for i in session.items
            if i.get_closest_marker("xdist_group") is not None and "@" not in i.nodeid]
    if lost:
        msg = (f"--dist loadgroup does not group on this pytest / pytest-xdist pair ({lost[0]} has "
               f"no @group suffix): install requirements.txt (make setup)")
        os.write(2, f"\nERROR: {msg}\n".encode())  # a worker's exception reaches the controller
        raise pytest.UsageError(msg)                  # only as an INTERNALERROR without its text


@pytest.fixture
def rng(request) -> np.random.Generator:
    """A numpy Generator with a printed seed (SEED=... reproduces a run)."""
    seed = int(os.environ.get("SEED", random.randrange(1 << 31)))
    print(f"\n{request.node.name}: SEED={seed}")
    return np.random.default_rng(seed)
