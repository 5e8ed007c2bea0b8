# SPDX-License-Identifier: Apache-2.0
"""cocotbext-axi memories with random latency, back-pressure and injected error responses, for
the DMA engines' and the system top's tests (the machinery of tb/traverse_system's MapRam, for
reads and writes).

* :class:`FaultRead` / :class:`FaultWrite`: AxiRamRead / AxiRamWrite whose word accesses wait a
  random number of clocks (probability ``lat_p`` per word, ``lat`` = (min, max) clocks), that
  record accesses outside the ``regions`` they are given (and answer them SLVERR), and that
  answer SLVERR for any word touching an ``err_ranges`` byte range (AxiSlaveRead turns the
  exception into RRESP = SLVERR for that beat, AxiSlaveWrite into BRESP = SLVERR for the burst).
* :func:`pauses`: a pause generator (cocotbext-axi ``set_pause_generator``) pausing with
  probability ``p`` per clock.
* :func:`set_pauses`: pause generators on every channel of a read or write slave.
"""
from __future__ import annotations

import random
from typing import Iterator

from cocotb.triggers import ClockCycles
from cocotbext.axi import AxiRamRead, AxiRamWrite


def pauses(rng: random.Random, p: float) -> Iterator[bool]:
    """Pause with probability ``p`` in each clock."""
    while True:
        yield rng.random() < p


class _Faults:
    """The fault state shared by :class:`FaultRead` and :class:`FaultWrite`."""

    def _init_faults(self, rng: random.Random) -> None:
        self.rng = rng
        self.lat: tuple[int, int] = (0, 0)
        self.lat_p = 0.0
        self.regions: list[tuple[int, int]] = []     # [lo, hi): accesses allowed (empty: any)
        self.err_ranges: list[tuple[int, int]] = []  # [lo, hi): answered SLVERR
        self.outside: list[int] = []                 # addresses accessed outside every region
        self.err_words = 0                           # words answered SLVERR (err_ranges)

    async def _fault(self, address: int, length: int) -> None:
        if self.lat[1] > 0 and self.rng.random() < self.lat_p:
            n = self.rng.randint(*self.lat)
            if n:
                await ClockCycles(self.clock, n)
        if self.regions and not any(lo <= address and address + length <= hi
                                    for lo, hi in self.regions):
            self.outside.append(address)
            raise IOError("access outside the regions")
        if any(lo < address + length and address < hi for lo, hi in self.err_ranges):
            self.err_words += 1
            raise IOError("injected SLVERR")


class FaultRead(AxiRamRead, _Faults):
    """AxiRamRead with latency, a region check and SLVERR ranges (see the module docstring)."""

    def __init__(self, *args, rng: random.Random, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._init_faults(rng)

    async def _read(self, address: int, length: int) -> bytes:
        await self._fault(address, length)
        return await super()._read(address, length)


class FaultWrite(AxiRamWrite, _Faults):
    """AxiRamWrite with latency, a region check and SLVERR ranges (see the module docstring)."""

    def __init__(self, *args, rng: random.Random, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self._init_faults(rng)
        self.writes = 0                              # write operations performed

    async def _write(self, address: int, data: bytes) -> None:
        await self._fault(address, len(data))
        self.writes += 1
        await super()._write(address, data)


def set_pauses(slave: AxiRamRead | AxiRamWrite, rng: random.Random, p: float) -> None:
    """Pause generators with probability ``p`` on every channel of ``slave`` (a generator even
    for p = 0: cocotbext-axi's set_pause_generator(None) leaves the channel's last pause value,
    which may be a pause for ever)."""
    if isinstance(slave, AxiRamRead):
        chans = (slave.ar_channel, slave.r_channel)
    else:
        chans = (slave.aw_channel, slave.w_channel, slave.b_channel)
    for ch in chans:
        ch.set_pause_generator(pauses(rng, p))
