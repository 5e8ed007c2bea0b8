"""Approximate units (placeholder, being written)."""
RSQRT_MAX_ULP = None
LOG2_MAX_ABS_ERR = None
def rsqrt(*a, **k): raise NotImplementedError
def log2(*a, **k): raise NotImplementedError
