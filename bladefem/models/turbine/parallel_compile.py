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
warm run never does. ``turbine --simulate`` starts it earlier still (:func:`prestart`, before the deck is read) when
the aerodynamic loads have nothing in the cache: it imports the kernels' modules and sets up numba's compiler
(:func:`warm_up`, about 0.4 s) while this process reads the deck and builds the model, then waits for its jobs.
The environment variable BLADEFEM_COMPILE_HELPER=0 never starts it, =1 always does. Both
processes write numba's cache: numba writes each file to a temporary name and renames it, and the two compile
different kernels except shared leaves (vector helpers, the beam node), which they compile for the same argument
types, so for the same index entry with equivalent machine code. If the helper fails (it cannot start, import this
same bladefem, or write the cache) this process compiles its kernels itself, as without it; a helper still running
when this process needs its kernels is waited for at most :data:`PATIENCE` s.
"""

from __future__ import annotations

import atexit
import os
import pickle
import subprocess
import sys
import time
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
#: seconds over which :func:`spare_core` measures the idle time of the cores
SAMPLE = 0.2
#: idle cores :func:`spare_core` asks for: one, less the sample's resolution (the counters tick 100 times a second:
#: 40 ticks of two cores in 0.2 s, a tick or two either way is 0.05-0.1 core)
IDLE = 0.9
#: the kernel's per-CPU time counters (Linux)
PROC_STAT = "/proc/stat"
#: starts of helper processes in this process (for tests)
STARTED: list[int] = []
#: the helper :func:`prestart` started, waiting for its jobs until :func:`compile_in_parallel` sends them
EARLY: list[subprocess.Popen] = []
#: the module of the integrators, which the helper compiles as the caller's ``extra``
INTEGRATORS = "bladefem.models.turbine.compiled_integrators"


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


def launch() -> subprocess.Popen | None:
    """A helper process (:func:`main`) waiting for its jobs on stdin, or None if it cannot start."""
    environment = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(PACKAGE.parent), *filter(None, [os.environ.get("PYTHONPATH")])])}
    try:
        helper = subprocess.Popen([sys.executable, "-m", __name__, str(PACKAGE)], stdin=subprocess.PIPE,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=environment)
    except OSError:
        return None
    STARTED.append(helper.pid)
    return helper


def start_helper(jobs) -> subprocess.Popen | None:
    """The helper process compiling ``jobs`` (the one :func:`prestart` started, else a new one), or None if it
    cannot start."""
    helper = EARLY.pop() if EARLY else launch()
    return None if helper is None else send(helper, jobs)


def send(helper: subprocess.Popen, jobs) -> subprocess.Popen | None:
    """``helper`` given ``jobs`` (its stdin closed after them), or None (and it stopped) if it cannot take them."""
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


def cold() -> bool:
    """Whether numba's disk cache holds nothing for the aerodynamic loads (a fresh install's first run, or kernel
    sources changed since: numba then reads the index as empty). Reads numba internals, as
    :func:`.compiled.will_compile`; if they moved, or numba is off, says False (the helper then starts later, at
    the first compiled call, as without this)."""
    if os.environ.get("BLADEFEM_NO_NUMBA"):
        return False
    try:
        from .compiled_loads import add_aero
        return not add_aero._cache._cache_file._load_index()
    except Exception:                                  # numba missing, or its private cache API changed
        return False


def prestart() -> None:
    """Start the helper now, before this process builds its model, where the first compiled call will compile
    (:func:`cold`) and a core looks free (:func:`spare_core`): it warms up (:func:`warm_up`) meanwhile. The call that
    compiles then sends it its jobs (:func:`start_helper`); a process that never does ends it at exit (and a helper
    whose caller is gone reads the end of its stdin and exits)."""
    if EARLY or not cold() or not spare_core():
        return
    helper = launch()
    if helper is not None:
        EARLY.append(helper)
        atexit.register(stop, helper)


def spare_core() -> bool:
    """Whether a helper process would find a core of its own: BLADEFEM_COMPILE_HELPER=1 (yes) or 0 (no), else at
    least two cores for this process and, of their time, one core's worth idle while this process waits
    :data:`SAMPLE` s (:func:`idle_cores`, at least :data:`IDLE`; where the system does not tell, the last minute's load average at least one
    below their number). The idle time now, not the load average: a run right after another one (a pip install, a
    previous run) sees a load average of one or more for a minute after that work has ended."""
    chosen = os.environ.get("BLADEFEM_COMPILE_HELPER", "")
    if chosen in ("0", "1"):
        return chosen == "1"
    cores = sorted(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else list(range(os.cpu_count() or 1))
    if len(cores) < 2:
        return False
    idle = idle_cores(cores)
    if idle is not None:
        return idle >= IDLE
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):                 # no load average on this system (Windows)
        load = 0.0
    return load <= len(cores) - 1


def cpu_times(cores: list[int]) -> tuple[float, float] | None:
    """(idle, total) jiffies of the CPUs ``cores`` from /proc/stat (Linux), or None where it cannot be read."""
    try:
        lines = Path(PROC_STAT).read_text().splitlines()
    except OSError:
        return None
    wanted, idle, total = {f"cpu{core}" for core in cores}, 0.0, 0.0
    for line in lines:
        fields = line.split()
        if fields and fields[0] in wanted:
            values = [float(v) for v in fields[1:]]
            idle += sum(values[3:5])                   # idle and iowait
            total += sum(values[:8])                   # user .. steal (guest time is counted in user)
            wanted.discard(fields[0])
    return None if wanted else (idle, total)


def idle_cores(cores: list[int]) -> float | None:
    """How many of the CPUs ``cores`` were idle, on average over :data:`SAMPLE` s, or None where the system does
    not tell (no /proc/stat, or it lacks one of them)."""
    before = cpu_times(cores)
    if before is None:
        return None
    time.sleep(SAMPLE)
    after = cpu_times(cores)
    if after is None or after[1] <= before[1]:
        return None
    return len(cores) * (after[0] - before[0]) / (after[1] - before[1])


def compile_in_parallel(entry: str, loaded: tuple, work: tuple, extra: tuple = ()) -> None:
    """:data:`HELPER` and the (module, function, argument types) of ``extra`` in a second process while this one
    compiles ``ENTRIES[entry]`` if :func:`spare_core`; returns when both are done (or the helper failed or ran past
    :data:`PATIENCE`: the caller's compilation then does what it left). Without a spare core, nothing (the caller
    compiles everything). A kernel that fails to compile here is left to the caller's compilation, which then
    reports the error as without this."""
    if not EARLY and not spare_core():
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


def warm_up() -> None:
    """Import the modules of the helper's kernels and compile one small function without caching it: numba's
    typing and target contexts are set up (about 0.2 s) before the jobs arrive."""
    import importlib

    from numba import njit
    for module in sorted({module for module, _, _ in HELPER} | {INTEGRATORS}):
        importlib.import_module(module)
    njit(lambda x: x + 1.0)(1.0)


def main() -> int:
    """The helper: if this interpreter imports the bladefem named in argv, warm up, then compile the pickled jobs on
    stdin (none: its caller needed none, or is gone)."""
    if Path(sys.argv[1]).resolve() != PACKAGE:
        return 1
    warm_up()
    jobs = sys.stdin.buffer.read()
    if jobs:
        compile_kernels(pickle.loads(jobs))
    return 0


if __name__ == "__main__":
    os._exit(main())                                   # numba's cache files are written and closed; freeing the
                                                       # compiled code at exit took 0.8 s that the caller waited
