"""Bracketed root finding for monotone scalar functions (no scipy import on the hot path)."""

from __future__ import annotations

from typing import Callable


def bisect_increasing(f: Callable[[float], float], lo: float, hi: float,
                      xtol: float = 1e-13, max_iter: int = 200) -> float:
    """Root of an increasing function ``f`` with f(lo) <= 0 <= f(hi), to ``xtol``."""
    flo, fhi = f(lo), f(hi)
    if flo > 0 or fhi < 0:
        raise ValueError(f"root not bracketed: f({lo})={flo}, f({hi})={fhi}")
    for _ in range(max_iter):
        mid = 0.5 * (lo + hi)
        if f(mid) <= 0:
            lo = mid
        else:
            hi = mid
        if hi - lo <= xtol * max(1.0, abs(mid)):
            break
    return 0.5 * (lo + hi)
