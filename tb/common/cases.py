# SPDX-License-Identifier: Apache-2.0
"""Several configurations of one unit in one build and one simulation.

A wrapper ``tb/<unit>/<unit>_tb.sv`` instantiates the unit once per configuration, in a generate
loop ``g_case[i]`` that holds the instance and its own copy of the unit's ports (named as the
ports: ``rst_ni``, ``valid_i``, ...); only ``clk_i`` is shared.  The cocotb test starts the
clock, then one coroutine per instance (:func:`check_all`), each with its own random stream
(:func:`streams`) and its own checker, driving and reading ``dut.g_case[i]`` as the test of a
lone unit drives its top.  A coroutine returns its failure messages; :func:`check_all` fails the
test with those of every failing configuration, each under the configuration's name.  A checker
written as a lone unit's test, which stops at its first failed ``assert``, takes part through
:func:`asserts`.

One Verilator build (a small unit's C++ compile takes about 6 s, a medium one's such as
traverse_unit's about 30 s) and one simulator launch, not one per configuration; the instances
advance in the same clocks, so the cocotb scheduler's work per clock is shared too.
"""
from __future__ import annotations

import logging
import random
from typing import Any, Callable, Coroutine, Mapping, Sequence, TypeVar

import cocotb
import numpy as np
from cocotb.clock import Clock

from tb.common import fp_unit


def streams(count: int) -> list[np.random.Generator]:
    """``count`` independent random streams from one seed (:func:`fp_unit.seed`: printed, set
    with SEED=...): stream i is ``SeedSequence(seed).spawn(count)[i]``, so one SEED reproduces
    every instance's stimulus."""
    return [np.random.default_rng(s) for s in np.random.SeedSequence(fp_unit.seed()).spawn(count)]


def randoms(count: int) -> list[random.Random]:
    """:func:`streams` for a checker written with Python's ``random.Random``: instance i's
    generator is seeded from stream i (one SEED reproduces every instance's stimulus)."""
    return [random.Random(int(g.integers(1 << 63))) for g in streams(count)]


def logger(name: str) -> logging.LoggerAdapter:
    """cocotb's log with every message under the configuration's ``name`` (``name: message``),
    for a checker whose log lines would otherwise not tell the instances apart."""
    class _Named(logging.LoggerAdapter):
        def process(self, msg: Any, kwargs: Any) -> tuple[Any, Any]:
            return f"{name}: {msg}", kwargs
    return _Named(cocotb.log, {})


def param_mismatches(inst: Any, expected: Mapping[str, int]) -> list[str]:
    """The parameters of ``inst`` (a ``g_case[i]`` scope: localparams read through the
    hierarchy) that differ from ``expected``: the wrapper's table and the test's must agree."""
    got = {k: int(getattr(inst, k).value) for k in expected}
    return [] if got == dict(expected) else [
        f"the wrapper builds {inst._path} with {got}, the test expects {dict(expected)}"]


async def check_all(cases: Sequence[tuple[str, Coroutine[Any, Any, list[str]]]]) -> None:
    """Run every ``(name, coroutine)`` concurrently (each a checker of one instance that
    returns its failure messages) and wait for all; then raise one AssertionError listing the
    messages of every configuration that failed, each under its ``name``."""
    tasks = [(name, cocotb.start_soon(c)) for name, c in cases]
    failed: list[str] = []
    for name, task in tasks:
        msgs = await task
        if msgs:
            failed.append(f"{name}:\n  " + "\n  ".join(msgs))
    if failed:
        raise AssertionError(f"{len(failed)} of {len(tasks)} configurations failed\n"
                             + "\n".join(failed))


async def asserts(coro: Coroutine[Any, Any, Any]) -> list[str]:
    """Run ``coro`` (a checker that raises AssertionError at its first failure) as a checker for
    :func:`check_all`: its failure message, or none when it returns."""
    try:
        await coro
    except AssertionError as e:
        return [str(e) or "assertion failed"]
    return []


C = TypeVar("C")


def upper_fields(case: Any) -> dict[str, int]:
    """The fields of a NamedTuple configuration named in capitals: the unit's parameters (its
    other fields, e.g. ``vectors``, are the test's)."""
    return {k: v for k, v in case._asdict().items() if k.isupper()}


async def run_each(top: Any, configs: Sequence[C], name: Callable[[C], str],
                   body: Callable[[Any, C, Any], Coroutine[Any, Any, Any]],
                   params: Callable[[C], Mapping[str, int]] = upper_fields,
                   rngs: Callable[[int], Sequence[Any]] = streams) -> None:
    """The whole test of a wrapper whose ``NCASE`` instances ``g_case[i]`` are ``configs``:
    start ``top.clk_i`` (10 ns), check ``NCASE`` against the configurations, then on every
    instance at once read its parameters back (:func:`param_mismatches` against
    ``params(case)``) and run ``body(inst, case, rng)`` (its own stream: ``rngs``, :func:`streams`
    or :func:`randoms`; an
    AssertionError is that configuration's failure, :func:`asserts`); fail naming every
    configuration that failed (``name(case)``, :func:`check_all`)."""
    cocotb.start_soon(Clock(top.clk_i, 10, unit="ns").start())
    n = int(top.NCASE.value)
    assert n == len(configs), \
        f"{top._name} holds {n} instances, the test expects {len(configs)}"
    gens = rngs(len(configs))

    async def one(i: int, case: C) -> list[str]:
        inst = top.g_case[i]
        if mism := param_mismatches(inst, params(case)):
            return mism
        return await asserts(body(inst, case, gens[i]))

    await check_all([(name(c), one(i, c)) for i, c in enumerate(configs)])
