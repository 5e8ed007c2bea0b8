# SPDX-License-Identifier: Apache-2.0
"""Generate a wrapper that holds one float unit at several latencies (its ``LAT`` parameter).

A fixed-latency unit of ``rtl/fp`` is checked at every LAT under test (:mod:`tb.common.fp_unit`).
Instead of one Verilator build per LAT, the testbench builds one wrapper, ``<unit>_lats``, that
instantiates the unit once per LAT, every instance fed from the same inputs (``clk_i``, ``en_i``
and the unit's operands, the wrapper's ports of the same names) and each instance's outputs
brought out as ``<name>_lat<n>_o`` (``y_o`` of the LAT 3 instance: ``y_lat3_o``).  The instance
at the unit's default latency is given no LAT parameter at all (so the run also checks that
default), the others ``LAT`` = n; the unit's other parameters (``W``, ...) are the wrapper's,
with the unit's defaults, passed on to every instance.  The instances are ordinary instances of
the unit, so the bound assertion checkers (``rtl/**/<unit>_assert.sv``) apply to each.

The wrapper's ports are the unit's own declarations (types as written, e.g. ``logic signed
[W-1:0]``), read from the unit's header in ``rtl/``: the parameter list ``#( ... )`` and the port
list ``( ... );``, one declaration per item, ``//`` comments allowed.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

from tb.common import runner

_DIRECTION_RE = re.compile(r"^(input|output)\s+(.*\S)\s+(\w+)$", re.S)
_PARAM_RE = re.compile(r"^parameter\s+(.*\S)\s+(\w+)\s*=\s*(.+)$", re.S)


@dataclass(frozen=True)
class Port:
    """One port of the unit: direction (``input`` / ``output``), type as written, name."""

    direction: str
    type: str
    name: str


@dataclass(frozen=True)
class Header:
    """What the wrapper copies from the unit: its package imports, parameters other than LAT
    (``(type, name, default)``, as written) and ports."""

    imports: tuple[str, ...]
    params: tuple[tuple[str, str, str], ...]
    ports: tuple[Port, ...]


def _strip_comments(text: str) -> str:
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def _split_top(text: str) -> list[str]:
    """``text`` split at the commas outside brackets and parentheses, items stripped."""
    items, depth, cur = [], 0, []
    for ch in text:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == "," and depth == 0:
            items.append("".join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    if "".join(cur).strip():
        items.append("".join(cur).strip())
    return items


def _balanced(text: str, start: int) -> int:
    """The index just past the parenthesis that closes the one at ``text[start]``."""
    depth = 0
    for i in range(start, len(text)):
        if text[i] == "(":
            depth += 1
        elif text[i] == ")":
            depth -= 1
            if depth == 0:
                return i + 1
    raise ValueError("unbalanced parentheses")


def parse_header(unit: str, source: Path | None = None) -> Header:
    """The imports, parameters (LAT left out) and ports of module ``unit`` (its file under
    ``rtl/`` unless ``source`` is given)."""
    text = _strip_comments((source or runner.rtl_index()[unit]).read_text())
    m = re.search(rf"\bmodule\s+{re.escape(unit)}\b", text)
    if m is None:
        raise ValueError(f"no module {unit} in its file")
    pos = m.end()
    hash_at = text.index("#", pos)
    paren_at = text.index("(", pos)
    imports: list[str] = re.findall(r"\bimport\s+[\w:*]+\s*;", text[pos:min(hash_at, paren_at)])
    params: list[tuple[str, str, str]] = []
    if hash_at < paren_at:
        p_open = text.index("(", hash_at)
        p_close = _balanced(text, p_open)
        for item in _split_top(text[p_open + 1:p_close - 1]):
            pm = _PARAM_RE.match(" ".join(item.split()))
            if pm is None:
                raise ValueError(f"{unit}: parameter declaration not understood: {item!r}")
            if pm.group(2) != "LAT":
                params.append((pm.group(1), pm.group(2), pm.group(3)))
        paren_at = text.index("(", p_close)
    ports: list[Port] = []
    for item in _split_top(text[paren_at + 1:_balanced(text, paren_at) - 1]):
        dm = _DIRECTION_RE.match(" ".join(item.split()))
        if dm is None:
            raise ValueError(f"{unit}: port declaration not understood: {item!r}")
        ports.append(Port(dm.group(1), dm.group(2), dm.group(3)))
    names = {p.name for p in ports}
    if not {"clk_i", "en_i"} <= names:
        raise ValueError(f"{unit}: no clk_i / en_i")
    return Header(tuple(imports), tuple(params), tuple(ports))


def lane_port(name: str, lat: int) -> str:
    """The wrapper's port for output ``name`` of the LAT ``lat`` instance: ``y_o`` ->
    ``y_lat3_o``."""
    if not name.endswith("_o"):
        raise ValueError(f"output {name} does not end in _o")
    return f"{name[:-2]}_lat{lat}_o"


def module_name(unit: str) -> str:
    """The wrapper module of ``unit``."""
    return f"{unit}_lats"


def generate(unit: str, lats: Sequence[int], default: int, header: Header | None = None) -> str:
    """The SystemVerilog text of ``<unit>_lats``: ``unit`` at every LAT of ``lats`` (the default
    one with no LAT parameter), sharing the inputs, each instance's outputs on its own ports."""
    if not lats or len(set(lats)) != len(lats):
        raise ValueError(f"{unit}: LATs {list(lats)}: none, or one twice")
    h = header or parse_header(unit)
    top = module_name(unit)
    inputs = [p for p in h.ports if p.direction == "input"]
    outputs = [p for p in h.ports if p.direction == "output"]
    decls = [f"  input  {p.type} {p.name}" for p in inputs]
    decls += [f"  output {p.type} {lane_port(p.name, lat)}" for lat in lats for p in outputs]
    lines = [
        "// SPDX-License-Identifier: Apache-2.0",
        f"// {top}: {unit} at LAT {', '.join(str(x) for x in lats)}, one instance each, on the",
        "// same inputs; each instance's outputs on <name>_lat<LAT>_o.  Generated by",
        "// tb/common/lat_wrapper.py for tb/common/fp_unit.py (a testbench wrapper, not RTL).",
        f"module {top}",
        *(f"  {i}" for i in h.imports),
    ]
    if h.params:
        lines.append("#(")
        lines.append(",\n".join(f"  parameter {t} {n} = {d}" for t, n, d in h.params))
        lines.append(") (")
    else:
        lines.append("(")
    lines.append(",\n".join(decls))
    lines.append(");")
    for lat in lats:
        overrides = [f".{n}({n})" for _, n, _ in h.params]
        if lat != default:
            overrides.append(f".LAT({lat})")
        inst = f"  {unit} " + (f"#({', '.join(overrides)}) " if overrides else "")
        conns = [f".{p.name}" for p in inputs]
        conns += [f".{p.name}({lane_port(p.name, lat)})" for p in outputs]
        lines.append(f"{inst}u_lat{lat} (")
        lines.append(",\n".join(f"    {c}" for c in conns))
        lines.append("  );")
    lines.append("endmodule")
    return "\n".join(lines) + "\n"


def write(unit: str, lats: Sequence[int], default: int, directory: Path) -> Path:
    """Write :func:`generate`'s text to ``directory/<unit>_lats.sv`` (only when it changed, so a
    finished build stays up to date) and return the path."""
    path = directory / f"{module_name(unit)}.sv"
    text = generate(unit, lats, default)
    if not path.is_file() or path.read_text() != text:
        directory.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return path
