"""Optional numba compilation of the scalar aerodynamic kernels.

The kernels are plain Python functions on floats and numpy arrays. With numba (a dependency) they are compiled
with ``@njit(cache=True)`` (the cache made stale by any kernel source change, :mod:`bladefem.numba_cache`) and
without numba's reference counting (``_nrt=False``): they read and write the arrays they are given and allocate
none, and the counting's atomic increments and decrements around every array argument of every call took about half
of a BEM node solve's time (the polar tables and option vector passed down to each residual); without
it, or with the environment variable ``BLADEFEM_NO_NUMBA`` set, the same functions run as Python (same results,
about a hundred times slower). Calls between kernels go through the
module globals, so a compiled kernel calls compiled kernels and a Python kernel calls Python kernels.
"""

from __future__ import annotations

import os

from ..numba_cache import cached_njit

njit = cached_njit()

#: True when the kernels of :mod:`bladefem.aero` are compiled.
COMPILED = njit is not None and not os.environ.get("BLADEFEM_NO_NUMBA")


def kernel(function):
    """``function`` compiled by numba (cached on disk; no reference counting: it must not allocate arrays) when
    available, else unchanged."""
    if not COMPILED:
        return function
    return njit(cache=True, _nrt=False)(function)
