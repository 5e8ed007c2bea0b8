"""Conversions (placeholder, being written)."""
def from_unorm(*a, **k): raise NotImplementedError
def from_int(*a, **k): raise NotImplementedError
def to_index(*a, **k): raise NotImplementedError
