# SPDX-License-Identifier: Apache-2.0
"""The arithmetic injected into the traversal: ``f64`` (reference) and ``f24`` (the hardware's).

Both engines hold numbers as float64 arrays.  The f24 engine rounds the result of every operation
to the 24-bit format (:func:`model.f24.round_value`), so its values are always exactly the ones the
hardware's units produce (each unit is correctly rounded, see ``model/f24.py``), and compares them
with the ordinary float64 comparisons (which equal ``f24_cmp`` on such values).  Conversions are
the hardware's: unorm codes through ``f24_from_unorm``, integers through ``f24_from_int``, and
positions to texel indices through ``f24_to_index`` (floor, saturating to ``INDEX_W`` bits).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
import numpy.typing as npt

from . import f24

F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

#: Width of the hardware's texel-index conversion (signed): indices saturate to +-2^(INDEX_W-1).
INDEX_W = 20


class Arith:
    """Operations of one engine; subclasses set :meth:`r` (the rounding after each operation).

    NaN and Inf are ordinary values here (Inf - Inf = NaN by design): callers run the operations
    under ``np.errstate(all="ignore")``.
    """

    name = "abstract"
    index_lo = -(1 << 40)
    index_hi = (1 << 40) - 1

    def r(self, x: F64) -> F64:  # pragma: no cover - overridden
        raise NotImplementedError

    def add(self, a: F64, b: F64) -> F64:
        return self.r(a + b)

    def sub(self, a: F64, b: F64) -> F64:
        return self.r(a - b)

    def mul(self, a: F64, b: F64) -> F64:
        return self.r(a * b)

    def div(self, a: F64, b: F64) -> F64:
        return self.r(a / b)

    def from_int(self, k: npt.ArrayLike) -> F64:
        return self.r(np.asarray(k, dtype=np.float64))

    def from_unorm(self, codes: npt.ArrayLike, bits: int) -> F64:
        raise NotImplementedError

    def to_index(self, x: F64) -> I64:
        """floor(x), saturating (NaN gives 0), as int64."""
        f = np.floor(np.clip(x, self.index_lo, self.index_hi))
        return np.where(np.isnan(f), 0, f).astype(np.int64)


class F64Arith(Arith):
    """float64: the exact reference."""

    name = "f64"

    def r(self, x: F64) -> F64:
        return x

    def from_unorm(self, codes: npt.ArrayLike, bits: int) -> F64:
        return _unorm_table_f64(bits)[np.asarray(codes, dtype=np.int64)]


class F24Arith(Arith):
    """The 24-bit format of the hardware datapath."""

    name = "f24"
    index_lo = -(1 << (INDEX_W - 1))
    index_hi = (1 << (INDEX_W - 1)) - 1

    def r(self, x: F64) -> F64:
        return f24.round_value(x)

    def from_unorm(self, codes: npt.ArrayLike, bits: int) -> F64:
        return _unorm_table_f24(bits)[np.asarray(codes, dtype=np.int64)]


@lru_cache(maxsize=None)
def _unorm_table_f64(bits: int) -> F64:
    return np.arange(1 << bits, dtype=np.float64) / ((1 << bits) - 1)


@lru_cache(maxsize=None)
def _unorm_table_f24(bits: int) -> F64:
    return f24.to_float(f24.from_unorm(np.arange(1 << bits, dtype=np.uint32), bits))


ENGINES: dict[str, Arith] = {"f64": F64Arith(), "f24": F24Arith()}
