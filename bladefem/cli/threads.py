"""BLAS held to one thread for a command whose matrices are small.

The turbine command's linear algebra (the blade's and tower's finite-element modes, the Kane model's few dozen
coordinates, the linearization's state matrix) is too small for OpenBLAS's threads to gain anything: they start,
and then spin, waiting for the next call, on the other core. Held to one thread, a 0.05 s ROSCO run of the NREL
5MW takes 0.115 s of CPU instead of 0.20 and 0.22 s of wall time instead of 0.245 (a 100 s run 0.1 s of CPU
less; docs/turbine-aero.md#speed). threadpoolctl sets the limit of every BLAS library the process has loaded
(numpy's and scipy's are two) and restores it afterwards.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import wraps


def one_blas_thread(command: Callable[..., int]) -> Callable[..., int]:
    """``command`` run with every loaded BLAS library held to one thread."""

    @wraps(command)
    def run(*args, **kwargs) -> int:
        from threadpoolctl import threadpool_limits
        with threadpool_limits(limits=1, user_api="blas"):
            return command(*args, **kwargs)
    return run
