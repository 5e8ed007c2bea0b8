# SPDX-License-Identifier: Apache-2.0
"""The bus bound of the hardware pyramid builder (``rtl/pyramid/pyr_build.sv``).

A full rebuild reads level 0 once (the map's own W x H codes) and writes levels 1..n of the
pyramid (``model.heightmap``: the padded N x N square halved down to the root, padding included).
Read and write channels run at once, so no builder can finish in fewer clocks than the larger of
the two byte counts over the bus's bytes per clock: that is the bound the builder is held to
(``docs/pyramid.md``).  Example: a 256 x 256 unorm8 map on a 64-bit bus reads 65,536 bytes,
writes 21,845 and is bound by 8,192 clocks.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass

from model.cli import Parser


@dataclass(frozen=True)
class BusBound:
    """Bytes a full rebuild moves and the clocks they take at least."""

    bytes_read: int
    bytes_written: int
    bus_bytes: int

    @property
    def clocks(self) -> int:
        """max(bytes read, bytes written) / bytes per clock, rounded up."""
        return -(-max(self.bytes_read, self.bytes_written) // self.bus_bytes)


def root_level(width: int, height: int) -> int:
    """n: the padded side is N = 2^n >= max(W, H) (as ``model.heightmap.build``)."""
    if width < 1 or height < 1:
        raise ValueError("a height map is at least 1 x 1")
    return (max(width, height) - 1).bit_length()


def full_rebuild(width: int, height: int, bits: int = 8, bus_bits: int = 64) -> BusBound:
    """The bound of a full rebuild of a W x H map of unorm``bits`` codes on a ``bus_bits`` bus."""
    if bits not in (8, 16):
        raise ValueError("height storage is unorm8 or unorm16")
    if bus_bits < 8 or bus_bits & (bus_bits - 1):
        raise ValueError("the bus width is a power of two of at least 8 bits")
    bpt = bits // 8
    n = root_level(width, height)
    written = sum(((1 << (n - k)) ** 2) * bpt for k in range(1, n + 1))
    return BusBound(width * height * bpt, written, bus_bits // 8)


def main(argv: list[str] | None = None) -> int:
    """Print the bound of one map size."""
    ap = Parser(prog="pyramid_bus", description="bus bound of a full pyramid rebuild")
    ap.add_argument("width", type=int)
    ap.add_argument("height", type=int)
    ap.add_argument("--bits", type=int, default=8, choices=(8, 16))
    ap.add_argument("--bus-bits", type=int, default=64)
    a = ap.parse_args(argv)
    try:
        b = full_rebuild(a.width, a.height, a.bits, a.bus_bits)
    except ValueError as e:
        print(f"pyramid_bus: {e}", file=sys.stderr)
        return 2
    print(f"read {b.bytes_read} B, written {b.bytes_written} B, bound {b.clocks} clocks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
