# SPDX-License-Identifier: Apache-2.0
"""Integer constants of the RTL's SystemVerilog packages (``rtl/**/*_pkg.sv``), read from the source
so that a number shared by the RTL and the Python (a latency, a port width, a table size) is
written once, in the package.

    value("traverse_pkg", "LOOKUP_LAT")      # 3
    values("pipe_pkg", "TEX_LEVELS", "TEX_DIM_W")

What is read: ``localparam int NAME = <expr>;`` and ``localparam int unsigned NAME = <expr>;`` at
any place of a package (one or several lines, comments ignored).  The expression may use integer
literals (``20``, ``'d7``, ``24'h00_8000``), ``+ - * / % << >> ( )``, ``$clog2(...)`` and other int
constants: of the same package, of a package it imports with ``import other_pkg::*;``, or named
``other_pkg::NAME``.  A name that is not there (or not an int localparam) raises
:class:`SvParamError` naming the package and its file.

Functions of one ``return`` (a latency as a function of the float units' depths) are read too:
``function automatic int [unsigned] name(int [unsigned] a, ...); return <expr>; endfunction``,
whose expression may use the arguments besides the constants above.  A constant may call one
(``localparam int unsigned X_LAT = x_lat(F24_ADD_LAT, F24_MUL_LAT);``) and the Python may too:

    call("pipe_pkg", "view_calc_lat", 3, 2)  # the latency at f24_add LAT 3, f24_mul LAT 2
"""
from __future__ import annotations

import ast
import functools
import operator
import re
from dataclasses import dataclass, field
from pathlib import Path

#: The RTL tree searched for ``*_pkg.sv``.
RTL = Path(__file__).resolve().parents[2] / "rtl"

_COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
_PACKAGE = re.compile(r"\bpackage\s+(\w+)\s*;(.*?)\bendpackage\b", re.S)
_IMPORT = re.compile(r"\bimport\s+(\w+)\s*::\s*\*\s*;")
_LOCALPARAM = re.compile(r"\blocalparam\s+int(?:\s+unsigned)?\s+(\w+)\s*=\s*([^;]+);")
_FUNCTION = re.compile(r"\bfunction\s+automatic\s+int(?:\s+unsigned)?\s+(\w+)\s*\(([^)]*)\)\s*;"
                       r"\s*return\s+([^;]+);\s*endfunction\b")
_LITERAL = re.compile(r"(\d*)\s*'\s*([sS]?)([hHdDbBoO])\s*([0-9a-fA-F_xXzZ]+)")
_BASES = {"h": 16, "d": 10, "b": 2, "o": 8}
_BINOPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod, ast.LShift: operator.lshift,
           ast.RShift: operator.rshift}


class SvParamError(LookupError):
    """A constant the caller asked for is not in the package, or cannot be evaluated."""


@dataclass
class Package:
    """One SystemVerilog package: its file, the packages it imports, its int localparams (the
    expression text, evaluated on demand) and its one-``return`` int functions (argument names,
    expression text)."""

    name: str
    path: Path
    imports: list[str] = field(default_factory=list)
    exprs: dict[str, str] = field(default_factory=dict)
    funcs: dict[str, tuple[list[str], str]] = field(default_factory=dict)


def parse(text: str, path: Path) -> list[Package]:
    """The packages of one source text (comments removed)."""
    out = []
    for m in _PACKAGE.finditer(_COMMENT.sub(" ", text)):
        body = m.group(2)
        pkg = Package(m.group(1), path, _IMPORT.findall(body))
        for fname, args, expr in _FUNCTION.findall(body):
            names = [a.split()[-1] for a in args.split(",") if a.strip()]
            pkg.funcs[fname] = (names, " ".join(expr.split()))
        for name, expr in _LOCALPARAM.findall(_FUNCTION.sub(" ", body)):
            pkg.exprs[name] = " ".join(expr.split())
        out.append(pkg)
    return out


@functools.lru_cache(maxsize=None)
def packages(rtl: Path = RTL) -> dict[str, Package]:
    """Every package of ``rtl/**/*_pkg.sv`` by name (read once per process)."""
    out: dict[str, Package] = {}
    for path in sorted(rtl.rglob("*_pkg.sv")):
        for pkg in parse(path.read_text(), path):
            out[pkg.name] = pkg
    return out


def _python_expr(expr: str) -> str:
    """The SystemVerilog expression as Python syntax (literals in decimal, ``/`` integer
    division, ``pkg::NAME`` as ``pkg__NAME``, ``$clog2`` as ``clog2``)."""
    def lit(m: re.Match[str]) -> str:
        digits = m.group(4).replace("_", "")
        if re.search(r"[xXzZ]", digits):
            raise SvParamError(f"literal {m.group(0)!r} has x or z bits")
        return str(int(digits, _BASES[m.group(3).lower()]))

    py = _LITERAL.sub(lit, expr)
    py = re.sub(r"(\w+)\s*::\s*(\w+)", r"\1__\2", py)
    py = py.replace("$clog2", "clog2")
    return re.sub(r"(?<![/])/(?![/])", "//", py)


def _clog2(x: int) -> int:
    return 0 if x <= 1 else (x - 1).bit_length()


def value(pkg: str, name: str, rtl: Path = RTL) -> int:
    """The value of ``localparam int [unsigned] name`` in package ``pkg``."""
    return _value(pkg, name, rtl, ())


def values(pkg: str, *names: str, rtl: Path = RTL) -> tuple[int, ...]:
    """Several constants of one package, in the order asked."""
    return tuple(value(pkg, n, rtl) for n in names)


def call(pkg: str, func: str, *args: int, rtl: Path = RTL) -> int:
    """The value of package ``pkg``'s function ``func`` at the integer arguments ``args``."""
    return _call(pkg, func, list(args), rtl, ())


def _lookup(pkg: Package, name: str, rtl: Path, seen: tuple[str, ...]) -> int | None:
    """``name`` seen from inside ``pkg``: its own constant, else one of a wildcard import."""
    if name in pkg.exprs:
        return _value(pkg.name, name, rtl, seen)
    for imp in pkg.imports:
        other = packages(rtl).get(imp)
        if other is not None and name in other.exprs:
            return _value(imp, name, rtl, seen)
    return None


def _package(pkg_name: str, rtl: Path) -> Package:
    pkgs = packages(rtl)
    pkg = pkgs.get(pkg_name)
    if pkg is None:
        raise SvParamError(f"no package {pkg_name} in {rtl}/**/*_pkg.sv "
                           f"(packages: {', '.join(sorted(pkgs))})")
    return pkg


def _value(pkg_name: str, name: str, rtl: Path, seen: tuple[str, ...]) -> int:
    pkg = _package(pkg_name, rtl)
    where = f"{pkg_name}::{name}"
    if name not in pkg.exprs:
        raise SvParamError(f"{where}: no 'localparam int {name} = ...;' in {pkg.path}")
    if where in seen:
        raise SvParamError(f"{where}: defined in terms of itself ({' -> '.join(seen)})")
    return _eval(pkg, where, pkg.exprs[name], rtl, (*seen, where), {})


def _call(pkg_name: str, func: str, args: list[int], rtl: Path, seen: tuple[str, ...]) -> int:
    pkg = _package(pkg_name, rtl)
    where = f"{pkg_name}::{func}()"
    if func not in pkg.funcs:
        raise SvParamError(f"{where}: no 'function automatic int {func}(...); return ...; "
                           f"endfunction' in {pkg.path}")
    if where in seen:
        raise SvParamError(f"{where}: defined in terms of itself ({' -> '.join(seen)})")
    names, expr = pkg.funcs[func]
    if len(names) != len(args):
        raise SvParamError(f"{where}: {len(names)} arguments, called with {len(args)}")
    return _eval(pkg, where, expr, rtl, (*seen, where), dict(zip(names, args)))


def _eval(pkg: Package, where: str, expr: str, rtl: Path, seen: tuple[str, ...],
          env: dict[str, int]) -> int:
    """``expr`` evaluated inside ``pkg`` (``env``: a function's arguments)."""
    try:
        tree = ast.parse(_python_expr(expr), mode="eval")
    except SyntaxError:
        raise SvParamError(f"{where} = {expr}: not an integer expression this reader knows") \
            from None

    def function(fname: str) -> tuple[str, str] | None:
        """(package, function) of a call's name seen from ``pkg``."""
        if "__" in fname:                             # other_pkg::func
            other, _, ref = fname.partition("__")
            return other, ref
        for cand in [pkg.name, *pkg.imports]:
            other = packages(rtl).get(cand)
            if other is not None and fname in other.funcs:
                return cand, fname
        return None

    def ev(node: ast.AST) -> int:
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, int):
            return node.value
        if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
            return _BINOPS[type(node.op)](ev(node.left), ev(node.right))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            return -ev(node.operand) if isinstance(node.op, ast.USub) else ev(node.operand)
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                and node.func.id == "clog2" and len(node.args) == 1):
            return _clog2(ev(node.args[0]))
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                and not node.keywords):
            target = function(node.func.id)
            if target is None:
                raise SvParamError(f"{where} = {expr}: {node.func.id} is not a function of "
                                   f"{pkg.name} or of the packages it imports")
            return _call(target[0], target[1], [ev(a) for a in node.args], rtl, seen)
        if isinstance(node, ast.Name):
            if node.id in env:                        # a function's argument
                return env[node.id]
            if "__" in node.id:                       # other_pkg::NAME
                other, _, ref = node.id.partition("__")
                return _value(other, ref, rtl, seen)
            got = _lookup(pkg, node.id, rtl, seen)
            if got is None:
                raise SvParamError(f"{where} = {expr}: {node.id} is not an int constant of "
                                   f"{pkg.name} or of the packages it imports")
            return got
        raise SvParamError(f"{where} = {expr}: not an integer expression this reader knows")

    return ev(tree)
