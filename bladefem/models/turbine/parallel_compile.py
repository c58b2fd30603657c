"""A cold run's kernels compiled on two cores. numba compiles in one thread; the integrators call the kernels below
them as first-class functions (:mod:`.compiled_calls`): each is compiled into a library of its own that no caller
links in, and none needs another compiled first (only its signature). While this process compiles the structural
equations (:func:`.compiled_kernels.equations`), the output row and the state rate, a second Python process compiles
the aerodynamic loads (:func:`.compiled_loads.add_aero`, with the BEM below it) and the integrator into numba's disk
cache (``dispatcher.compile(signature)`` with ``cache=True``); when this process then calls the integrator, numba
loads them from there instead of compiling them.

Measured compile CPU of one cold ``--simulate`` (all in one process at load average 1, callees included): for the
helper the aerodynamic loads 10.4 s and the integrator 2.4 s (:data:`HELPER` and the caller's ``extra``; 13.4 s with
the helper's start, on two free cores), for this process the structural equations 3.8 s, the output row 4.6 s and
the state rate 2.7 s (:data:`ENTRIES`; 11.4 s). Before the first-class functions the integrator, which linked them
all, compiled after both (8.4 s: numba optimizes and generates machine code again for the whole tree linked into a
library).

Only a cold call (:func:`.compiled.first_call` found no machine code in the cache) starts the helper, and only when
a second core looks free (:func:`spare_core`: a helper on a busy machine only adds its start, about 1 s of CPU); a
warm run never does. The environment variable BLADEFEM_COMPILE_HELPER=0 never starts it, =1 always does. Both
processes write numba's cache: numba writes each file to a temporary name and renames it, and the two compile
different kernels except shared leaves (vector helpers, the beam node), which they compile for the same argument
types, so for the same index entry with equivalent machine code. If the helper fails (it cannot start, import this
same bladefem, or write the cache) this process compiles its kernels itself, as without it; a helper still running
when this process needs its kernels is waited for at most :data:`PATIENCE` s.
"""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np

#: the kernels the helper process compiles: (module, function, kind of :func:`signatures`)
HELPER = (("bladefem.models.turbine.compiled_loads", "add_aero", "aero"),)
#: the kernels this process compiles meanwhile, per entry point that calls the loaded equations
ENTRIES = {
    "integrator": (("bladefem.models.turbine.compiled_kernels", "equations", "structure"),
                   ("bladefem.models.turbine.compiled_outputs", "output_row", "row"),
                   ("bladefem.models.turbine.compiled_integrators", "rate_function", "rate")),
    "outputs": (("bladefem.models.turbine.compiled_kernels", "equations", "structure"),
                ("bladefem.models.turbine.compiled_outputs", "output_row", "row")),
    "derivative": (("bladefem.models.turbine.compiled_kernels", "equations", "structure"),
                   ("bladefem.models.turbine.compiled_state", "state_rate", "state")),
    "equations": (("bladefem.models.turbine.compiled_kernels", "equations", "structure"),),
}
#: seconds this process waits for a helper still compiling once its own share is done
PATIENCE = 300.0
#: the bladefem package this process runs (the helper must import the same one)
PACKAGE = Path(__file__).resolve().parents[2]
#: starts of helper processes in this process (for tests)
STARTED: list[int] = []


def signatures(loaded: tuple, work: tuple) -> dict:
    """:func:`kernel_signatures` and the state rate's (``"rate"``, :func:`.compiled_calls.rate_types`)."""
    from .compiled_calls import rate_types
    return {**kernel_signatures(loaded, work), "rate": rate_types(loaded, work)}


def kernel_signatures(loaded: tuple, work: tuple) -> dict:
    """numba argument types of the kernels above as the loaded equations and the rate function call them, for
    ``loaded`` (structure, aero, law) and ``work`` (structural work, aero state) of
    :class:`.compiled.CompiledEquations`: vectors and matrices made inside the kernels are C-contiguous float64,
    the free-coordinate index int64, the blade an int64 (constant arguments are typed plainly,
    :func:`bladefem.numba_cache.cached_njit`)."""
    from numba import typeof, types
    vector, matrix, index = typeof(np.zeros(1)), typeof(np.zeros((1, 1))), typeof(np.zeros(1, dtype=np.int64))
    structure, aero = typeof(loaded[0]), typeof(loaded[1])
    structural, state = typeof(work[0]), typeof(work[1])
    return {"aero": (vector, vector, vector, structure, aero, structural, state, types.float64),
            "structure": (vector, vector, structure, structural),
            "state": (vector, matrix, vector, index),
            "row": (vector, vector, matrix, vector, index, typeof(loaded), typeof(work), types.float64, types.int64,
                    vector)}


def compile_kernels(jobs) -> None:
    """Compile each (module, function, argument types) of ``jobs``: numba loads it from its disk cache if it is
    there, else compiles and caches it."""
    import importlib
    for module, name, argument_types in jobs:
        getattr(importlib.import_module(module), name).compile(tuple(argument_types))


def ready(module: str, name: str, argument_types: tuple) -> bool:
    """Whether this process already holds the kernel for these argument types (compiled or loaded by an earlier
    entry point: a second helper would only load it again)."""
    import importlib
    return tuple(argument_types) in getattr(importlib.import_module(module), name).signatures


def start_helper(jobs) -> subprocess.Popen | None:
    """The helper process compiling ``jobs``, or None if it cannot start."""
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(PACKAGE.parent), *filter(None, [os.environ.get("PYTHONPATH")])])}
    try:
        helper = subprocess.Popen([sys.executable, "-m", __name__, str(PACKAGE)], stdin=subprocess.PIPE,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=environment)
    except OSError:
        return None
    STARTED.append(helper.pid)
    try:
        helper.stdin.write(pickle.dumps(jobs))
        helper.stdin.close()
    except OSError:
        stop(helper)
        return None
    return helper


def stop(helper: subprocess.Popen) -> None:
    """End ``helper`` if it still runs."""
    if helper.poll() is None:
        helper.kill()
    helper.wait()


def spare_core() -> bool:
    """Whether a helper process would find a core of its own: BLADEFEM_COMPILE_HELPER=1 (yes) or 0 (no), else at
    least two cores for this process and the last minute's load average at least one below their number."""
    chosen = os.environ.get("BLADEFEM_COMPILE_HELPER", "")
    if chosen in ("0", "1"):
        return chosen == "1"
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):                 # no load average on this system (Windows)
        load = 0.0
    return cores >= 2 and load <= cores - 1


def compile_in_parallel(entry: str, loaded: tuple, work: tuple, extra: tuple = ()) -> None:
    """:data:`HELPER` and the (module, function, argument types) of ``extra`` in a second process while this one
    compiles ``ENTRIES[entry]`` if :func:`spare_core`; returns when both are done (or the helper failed or ran past
    :data:`PATIENCE`: the caller's compilation then does what it left). Without a spare core, nothing (the caller
    compiles everything). A kernel that fails to compile here is left to the caller's compilation, which then
    reports the error as without this."""
    if not spare_core():
        return
    try:
        kinds = signatures(loaded, work)
    except Exception:                                 # compiled ahead only to save time: the call compiles it all
        return
    wanted = [(module, name, kinds[kind]) for module, name, kind in HELPER] + list(extra)
    jobs = [job for job in wanted if not ready(*job)]
    helper = start_helper(jobs) if jobs else None
    try:
        compile_kernels([(module, name, kinds[kind]) for module, name, kind in ENTRIES[entry]])
        if helper is not None:
            helper.wait(timeout=PATIENCE)
    except Exception:                                 # a helper past PATIENCE, a kernel that fails here: the call
        pass                                          # compiles what is left (and reports its error)
    finally:
        if helper is not None:
            stop(helper)


def main() -> int:
    """The helper: compile the pickled jobs on stdin if this interpreter imports the bladefem named in argv."""
    if Path(sys.argv[1]).resolve() != PACKAGE:
        return 1
    compile_kernels(pickle.load(sys.stdin.buffer))
    return 0


if __name__ == "__main__":
    sys.exit(main())
