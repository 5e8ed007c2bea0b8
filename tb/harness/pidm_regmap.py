# SPDX-License-Identifier: Apache-2.0
"""The register map of pidm_top read from its one description, ``rtl/top/pidm_regs.rdl``
(systemrdl-compiler, pinned in requirements.txt), so that the Python that writes registers (the
frame packer ``scripts/pack_frame.py``, a system test) never restates an address or a bit.

    regs = registers()                    # {"HEIGHT.MODE": Register, "TEX[1].LEVEL_OFF[3]": ...}
    r = reg("HEIGHT.MODE")
    r.addr                                # 0x200
    r.value(method=7, root_level=8)       # the 32-bit word with those fields (others 0)
    r.fields_of(0x87)                     # {"method": 7, "root_level": 8, "bits16": 0}

Paths are the register's path below the top addrmap, array indices written ``[k]``.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: The register map's SystemRDL source.
RDL = ROOT / "rtl" / "top" / "pidm_regs.rdl"


class RegMapError(LookupError):
    """An unknown register or field, or a field value that does not fit."""


@dataclass(frozen=True)
class Field:
    """A field: its lowest bit and width."""

    lsb: int
    width: int

    @property
    def mask(self) -> int:
        return ((1 << self.width) - 1) << self.lsb


@dataclass(frozen=True)
class Register:
    """A 32-bit register: its path, byte address, fields (name -> :class:`Field`) and whether
    software can read it (False: a write-only register, which reads 0)."""

    path: str
    addr: int
    fields: dict[str, Field]
    readable: bool = True

    def value(self, **values: int) -> int:
        """The register word with the named fields set (unnamed fields 0)."""
        word = 0
        for name, v in values.items():
            f = self.fields.get(name)
            if f is None:
                raise RegMapError(f"{self.path} has no field {name!r} "
                                  f"(fields: {', '.join(self.fields)})")
            v = int(v)
            if v < 0 or v >> f.width:
                raise RegMapError(f"{self.path}.{name} = {v:#x} does not fit {f.width} bits")
            word |= v << f.lsb
        return word

    def fields_of(self, word: int) -> dict[str, int]:
        """Every field's value in ``word``."""
        return {n: (word >> f.lsb) & ((1 << f.width) - 1) for n, f in self.fields.items()}


@functools.lru_cache(maxsize=None)
def registers(rdl: Path = RDL) -> dict[str, Register]:
    """Every register of the map by path (compiled once per process)."""
    from systemrdl import RDLCompileError, RDLCompiler
    from systemrdl.node import RegNode

    comp = RDLCompiler()
    try:
        comp.compile_file(str(rdl))
        root = comp.elaborate()
    except RDLCompileError as e:
        raise RegMapError(f"{rdl}: the SystemRDL compiler rejected it") from e
    top = root.top
    out: dict[str, Register] = {}
    prefix = top.inst_name + "."
    for node in top.descendants(unroll=True):
        if isinstance(node, RegNode):
            path = node.get_path()
            path = path[len(prefix):] if path.startswith(prefix) else path
            out[path] = Register(path, int(node.absolute_address),
                                 {f.inst_name: Field(int(f.lsb), int(f.width))
                                  for f in node.fields()},
                                 any(f.is_sw_readable for f in node.fields()))
    return out


def reg(path: str) -> Register:
    """The register at ``path`` (e.g. ``"TEX[0].LEVEL_SIZE[3]"``)."""
    r = registers().get(path)
    if r is None:
        raise RegMapError(f"no register {path!r} in {RDL.name}")
    return r


def by_address() -> dict[int, Register]:
    """Every register by byte address."""
    return {r.addr: r for r in registers().values()}
