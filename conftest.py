# SPDX-License-Identifier: Apache-2.0
"""The order in which ``make test``'s pytest-xdist workers take the tests: longest first.

pytest-xdist hands the tests to its two workers in collection order (``--dist loadgroup``: one
work unit per test, or per ``xdist_group``, whose tests stay together; with
``--no-loadscope-reorder`` in that order, not by the units' test counts).  A test of minutes
that comes late in the collection ends the run alone on one worker while the other is idle, so
on a worker this hook sorts the units by their duration in the last measured run, longest
first (a unit's duration: the sum of its tests'; ``tests/durations.json``).  A test that file
does not name keeps its place among the others, after the ones it names.  The tests within a
group keep their order (a group's later tests may use what its first test built).  Nothing is
reordered outside a pytest-xdist worker: a serial run keeps the collection order.

``TEST_DURATIONS_UPDATE=1`` (with or without pytest-xdist) rewrites ``tests/durations.json``
with the run's setup + call + teardown times (the tests it did not run keep theirs), keeping
the tests of at least ``MIN_SECONDS``: done after a change that moves the long tests (the order
is only a schedule; a stale file costs wall time, never a check).
"""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent
DURATIONS = ROOT / "tests" / "durations.json"
#: Tests shorter than this are left out of the file (their order does not matter).
MIN_SECONDS = 2.0

_measured: dict[str, float] = {}


def _plain_id(nodeid: str) -> str:
    """The node id without pytest-xdist's ``@group`` suffix (loadgroup adds it)."""
    at, bracket = nodeid.rfind("@"), nodeid.rfind("]")
    return nodeid[:at] if at > bracket else nodeid


def _known() -> dict[str, float]:
    try:
        data = json.loads(DURATIONS.read_text())
        return {str(k): float(v) for k, v in data["seconds"].items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return {}                       # no file or a broken one: the collection order


def _unit(item: pytest.Item) -> str:
    """The xdist work unit of ``item``: its group's name, or its own node id."""
    mark = item.get_closest_marker("xdist_group")
    if mark is None:
        return _plain_id(item.nodeid)
    name = mark.args[0] if mark.args else mark.kwargs.get("name", "default")
    return f"@{name}"


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if "PYTEST_XDIST_WORKER" not in os.environ:
        return
    known = _known()
    if not known:
        return
    total: dict[str, float] = {}
    first: dict[str, int] = {}
    for i, item in enumerate(items):
        u = _unit(item)
        total[u] = total.get(u, 0.0) + known.get(_plain_id(item.nodeid), 0.0)
        first.setdefault(u, i)
    # Sort by (unit duration, descending), then the unit's first place, then the item's place:
    # deterministic, so every worker collects the same order (pytest-xdist requires it).
    order = sorted(range(len(items)), key=lambda i: (-total[_unit(items[i])],
                                                     first[_unit(items[i])], i))
    items[:] = [items[i] for i in order]


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    if os.environ.get("TEST_DURATIONS_UPDATE") != "1" or "PYTEST_XDIST_WORKER" in os.environ:
        return
    nodeid = _plain_id(report.nodeid)
    _measured[nodeid] = _measured.get(nodeid, 0.0) + report.duration


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    if os.environ.get("TEST_DURATIONS_UPDATE") != "1" or "PYTEST_XDIST_WORKER" in os.environ:
        return
    merged = {**_known(), **_measured}      # tests this run did not run keep their time
    keep = {k: round(v, 1) for k, v in sorted(merged.items(), key=lambda kv: -kv[1])
            if v >= MIN_SECONDS}
    DURATIONS.write_text(json.dumps({
        "about": "seconds (setup + call + teardown) per test in one make test run, for the "
                 "order of the workers (conftest.py); TEST_DURATIONS_UPDATE=1 rewrites it",
        "seconds": keep}, indent=1) + "\n")
    print(f"\ntest durations: {len(keep)} tests of {MIN_SECONDS:g} s or more in "
          f"{DURATIONS.relative_to(ROOT)}")
