"""The same Kane equations as :meth:`TurbineModel.equations`, compiled with numba (optional) for time integration.

The kinematics are the two rules of ``kinematics.py`` written as loops over frames, span nodes and blades; the
generalized inertia and active forces are summed in the factored form ``Z^T (sum_p m_p G_p^T G_p) Z`` per node
group (``compiled_kernels``); adaptive Dormand-Prince integrators with dense output (``compiled_integrators``) and
the root-moment outputs (``compiled_outputs``) call them. :func:`compiled_equations` returns None when numba is not
installed; tests check that both paths give the same mass matrix and forcing to rounding.

numba compiles each kernel on its first use and caches it on disk (next to the sources, or in NUMBA_CACHE_DIR);
only the kernels a run needs are compiled, and a notice goes to stderr when a call compiles (not when it loads the
cached machine code).
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from contextlib import contextmanager, nullcontext
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

try:
    import numba
except ImportError:                                    # pragma: no cover - numba is optional
    numba = None

#: kernels called at least once in this process (compiled or loaded from the cache)
_READY: set[str] = set()


def first_call(kernel: str, what: str, dispatcher, args: tuple, stream=None,
               prepare: Callable[[], None] | None = None):
    """:func:`compile_notice` around the first call of ``kernel`` in this process when numba will compile it (no
    machine code for these argument types in this process or in numba's disk cache), after which ``prepare`` (if
    given) runs; nothing otherwise, and nothing on later calls (a check per call would cost more than a right-hand
    side)."""
    if kernel in _READY:
        return nullcontext()
    _READY.add(kernel)
    return compile_notice(what, stream, prepare) if will_compile(dispatcher, args) else nullcontext()


def will_compile(dispatcher, args: tuple) -> bool:
    """True when calling the numba ``dispatcher`` with ``args`` (or, all numba types, for these argument types)
    compiles: no overload for their types in this process and none in the on-disk cache (the index entry numba's
    ``Dispatcher.compile`` looks up: signature, CPU, bytecode hash, fresh source stamp). Reads numba internals; if
    they moved, says True (a notice too many)."""
    try:
        typed = all(isinstance(a, numba.types.Type) for a in args)
        signature = tuple(args) if typed else tuple(dispatcher.typeof_pyval(a) for a in args)
        if signature in dispatcher.overloads:
            return False
        cache = dispatcher._cache
        key = cache._index_key(signature, dispatcher.targetctx.codegen())
        return key not in cache._cache_file._load_index()
    except Exception:                                  # numba's private cache API changed
        return True


@contextmanager
def compile_notice(what: str, stream=None, prepare: Callable[[], None] | None = None):
    """Tell the user on stderr that a kernel is being compiled (then run ``prepare``), and how long it took
    (numba's warning about its first-class function types silenced meanwhile, :func:`.compiled_calls.unwarned`)."""
    stream = stream or sys.stderr
    start = time.perf_counter()
    print(f"bladefem: compiling the {what} with numba (first run only, cached afterwards)...", file=stream,
          flush=True)
    from .compiled_calls import unwarned
    try:
        with unwarned():
            if prepare is not None:
                prepare()
            yield
    finally:
        print(f"bladefem: compiled in {time.perf_counter() - start:.0f} s", file=stream, flush=True)


def model_data(model) -> tuple:
    """The model's arrays in the order the kernels unpack them."""
    from .compiled_invariants import blade_invariants
    tower, blade = model.tower_nodes, model.blade_nodes
    return (model.n,
            tower.across_flat.reshape(tower.k, tower.P, 3).copy(), tower.shortening_flat.reshape(4, 4, -1).copy(),
            _axial(tower), model.tower_masses.copy(),
            blade.across_flat.reshape(blade.k, blade.P, 3).copy(),
            blade.shortening_flat.reshape(blade.k, blade.k, -1).copy(), _axial(blade),
            model.blade_masses[0].copy(), model.blade_columns.astype(np.int64), model.blade_rotations.copy(),
            model.fore_aft_tilt.copy(), model.side_side_tilt.copy(), model.yaw.copy(), model.azimuth.copy(),
            model.generator_angle.copy(), model.tilt.copy(), model.rigid_offsets.copy(), model.rigid_masses.copy(),
            np.array(model.inertias, dtype=float), model.gravity.copy(), model.K.copy(), model.C.copy(),
            float(model.params.tower_base_height),
            blade_invariants(blade.across_flat.reshape(blade.k, blade.P, 3), blade.shortening_flat.reshape(
                blade.k, blade.k, -1), _axial(blade), model.blade_masses[0]))


def _axial(nodes) -> NDArray:
    """Undeflected axial positions of a node group (the offsets' axial component at zero deflection)."""
    return np.broadcast_to(np.asarray(nodes.axial, dtype=float), (nodes.P,)).copy()


def _dop853_tableau() -> tuple[NDArray, ...]:
    """Hairer's DOP853 coefficients as scipy ships them: A, C for the 16 stages (12 of the step, 3 more for the
    dense output after the derivative at the step's end), B, error weights E3, E5, interpolator D."""
    from scipy.integrate._ivp import dop853_coefficients as d
    return tuple(np.ascontiguousarray(a, dtype=float) for a in (d.A, d.B, d.C, d.E3, d.E5, d.D))


def _dp54_tableau() -> tuple[NDArray, ...]:
    """Dormand and Prince's 5(4) pair (J. R. Dormand, P. J. Prince, "A family of embedded Runge-Kutta formulae",
    J. Comput. Appl. Math. 6, 1980): A, B, C, the error weights E (5th minus 4th order, the 7th stage the
    derivative at the step's end), and Shampine's free 4th-order continuous extension P (L. F. Shampine, "Some
    practical Runge-Kutta formulas", Math. Comp. 46, 1986), as scipy's RK45 carries them (a test holds them
    equal). Written here rather than read from scipy.integrate, whose import takes 0.2 s of every run's start."""
    A = [[0, 0, 0, 0, 0],
         [1 / 5, 0, 0, 0, 0],
         [3 / 40, 9 / 40, 0, 0, 0],
         [44 / 45, -56 / 15, 32 / 9, 0, 0],
         [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0],
         [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]]
    B = [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]
    C = [0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1]
    E = [-71 / 57600, 0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40]
    P = [[1, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
         [0, 0, 0, 0],
         [0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
         [0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
         [0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
         [0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
         [0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]]
    return tuple(np.array(a, dtype=float) for a in (A, B, C, E, P))


@dataclass
class Integration:
    """States at the output times (T, size) and their load channels (T, len(compiled_outputs.COLUMNS)), the rows
    computed, right-hand sides used, and, if it stopped early, the status (1: not finite, 2: a coordinate beyond its
    limit, 3: step size underflow, 4: stopped by the watch, 5: interrupted), time, index of the offending state and
    what the watch returned; ``rate``: the state's time derivative at the end of a completed run."""

    states: NDArray
    loads: NDArray
    rows: int
    evaluations: int
    status: int = 0
    time: float = 0.0
    offending: int = -1
    reason: object = None
    rate: NDArray | None = None


#: the empty output row: the state rate without its load channels
_NO_ROW = np.zeros(0)


class CompiledEquations:
    """The compiled kernels bound to one model's data: ``equations(q, u) -> (M, f)`` (structure, aerodynamic loads,
    generator torque), ``derivative(t, x, q0, u0, index)`` for :class:`FreeSystem`, :meth:`integrate` and
    :meth:`outputs`. ``data`` and ``work`` are the structural kernel's (:func:`.compiled_kernels.equations`),
    ``aero`` and ``state`` the aerodynamic ones (:mod:`.compiled_loads`), ``law`` the generator's."""

    def __init__(self, data: tuple, hub_radius: float, aero: tuple, law: NDArray) -> None:
        from .compiled_aero_arrays import aero_state
        self.data, self.hub_radius, self.aero, self.law = data, hub_radius, aero, law
        n, blade_across, blades = data[0], data[5], data[10].shape[0]
        k = blade_across.shape[0]
        self.work = (np.zeros((blades, 6 + k, n)), np.zeros((blades, 3, 3)), np.zeros(3), np.zeros((3, n)),
                     np.zeros((4, 3)), np.zeros((blades, 6 + k, 6 + k)), np.zeros((blades, 6 + k)))
        self.state = aero_state(blades, aero[2].shape[0], k)
        self.loaded, self.all_work = (data, aero, law), (self.work, self.state)
        self._calls: dict[str, tuple] = {}             # kernel name -> (kernel, functions), :meth:`joined`

    def forget_solutions(self) -> None:
        """Clear the nodes' last BEM solutions (where the next solve starts, :func:`.compiled_loads.previous_root`:
        from scratch once cleared): a run starts from the node's inputs alone, whatever ran before on this
        model."""
        self.state[6][...] = 0.0

    def _parallel(self, entry: str, helper: tuple = ()) -> Callable[[], None]:
        """Before a cold first call of ``entry``: its kernels compiled on two processes where a core is free
        (:func:`.parallel_compile.compile_in_parallel`), ``helper``'s jobs too in the second one."""
        from .parallel_compile import compile_in_parallel
        return lambda: compile_in_parallel(entry, self.loaded, self.all_work, helper)

    def __call__(self, q: NDArray, u: NDArray, t: float = 0.0, wake: NDArray | None = None
                 ) -> tuple[NDArray, NDArray]:
        """(M, f) at (q, u) and time t, with the dynamic wake's states ``wake`` (B, Na, 4), else quasi-steady."""
        from .compiled_loads import equations
        flag = self.state[13]
        flag[0] = 0.0 if wake is None else 1.0
        if wake is not None:
            self.state[10][...] = wake
        args = (np.ascontiguousarray(q, dtype=float), np.ascontiguousarray(u, dtype=float), self.loaded,
                self.all_work, float(t))
        with first_call("equations", "turbine equations", equations, args, prepare=self._parallel("equations")):
            return equations(*args)

    def derivative(self, t: float, x: NDArray, q0: NDArray, u0: NDArray, index: NDArray) -> NDArray:
        """dx/dt of the free coordinates and the dynamic wake, x = (q_f, u_f, w): the integrators' state rate
        (:func:`.compiled_integrators.rate_function`, without output row), its kernels as first-class functions
        (a one-off call: numba converts them at each call, 0.35 ms; :meth:`rate` for a call at every step)."""
        from .compiled_integrators import rate_function
        args = (float(t), np.ascontiguousarray(x, dtype=float), q0, u0, index, self.loaded, self.all_work,
                float(self.hub_radius), _NO_ROW)
        return self.joined("derivative", "turbine equations", rate_function, args)

    def rate(self, t: float, x: NDArray, q0: NDArray, u0: NDArray, index: NDArray) -> NDArray:
        """:meth:`derivative` with its kernels linked in (:func:`.compiled_integrators.direct_rate`, compiled on
        its first call): for callers in Python at every right-hand side."""
        from .compiled_integrators import direct_rate
        args = (float(t), np.ascontiguousarray(x, dtype=float), q0, u0, index, self.loaded, self.all_work,
                float(self.hub_radius))
        with first_call("rate", "turbine equations", direct_rate, args):
            return direct_rate(*args)

    def joined(self, name: str, what: str, kernel, args: tuple, with_rate: bool = False,
               in_helper: bool = False):
        """``kernel``'s result for ``args`` after its function arguments (the state rate if ``with_rate``, and the
        kernels' tuple) given as first-class functions (:func:`.compiled_calls.join`), the kernel and its functions
        kept under ``name`` for the next calls. A cold first call compiles on two processes where a core is free,
        ``kernel`` itself in the helper if ``in_helper``."""
        from .compiled_calls import function_types, join, unwarned
        with unwarned():                               # numba makes function types at each call too
            if name in self._calls:
                called = self._calls[name]
                return called[0](*called[1:], *args)
            signature = function_types(kernel, self.loaded, self.all_work, args, with_rate)
            jobs = ((kernel.py_func.__module__, kernel.py_func.__name__, signature),) if (
                in_helper and signature is not None) else ()
            with first_call(name, what, kernel, signature or args, prepare=self._parallel("integrator", jobs)):
                self._calls[name], result = join(kernel, self.loaded, self.all_work, args, signature, with_rate)
                return result

    def integrate(self, times: NDArray, x0: NDArray, rtol: float, atol: float, q0: NDArray, u0: NDArray,
                  index: NDArray, order: int = 8, limit: NDArray | None = None,
                  watch: Callable[..., str | None] | None = None,
                  budget: int | None = None, first_step: float | None = None) -> Integration:
        """Adaptive Dormand-Prince 8(5,3) (``order=8``) or 5(4) (``order=5``) from ``times[0]`` to ``times[-1]``
        with dense output and the load channels at ``times``; stops at the first state beyond ``limit`` (per state,
        default none) or not finite. The compiled kernel returns after at most ``budget`` right-hand sides; between
        calls Ctrl-C is looked for (it only sets a flag while the kernel runs; the first call, which may compile,
        is left to the usual KeyboardInterrupt) and ``watch(t_before, t, times, states, loads, evaluations)`` with
        the output rows the call wrote may stop the run with a reason. ``first_step``: the first trial step, s
        (default 1e-3; a run restarted every controller interval starts with the interval)."""
        from .compiled_integrators import dop853_chunk, dp54_chunk
        from .compiled_outputs import COLUMNS
        from .watch import BUDGET, interruptible
        budget = BUDGET if budget is None else budget
        kernel, tableau = (dop853_chunk, _dop853_tableau()) if order == 8 else (dp54_chunk, _dp54_tableau())
        times = np.ascontiguousarray(times, dtype=float)
        x = np.ascontiguousarray(x0, dtype=float)
        limit = np.full(len(x), np.inf) if limit is None else np.ascontiguousarray(limit, dtype=float)
        out = np.full((len(times), len(x)), np.nan)
        out[0] = x
        loads = np.full((len(times), len(COLUMNS)), np.nan)
        index = np.ascontiguousarray(index, dtype=np.int64)
        q0, u0 = np.ascontiguousarray(q0, dtype=float), np.ascontiguousarray(u0, dtype=float)
        first = 1e-3 if first_step is None else first_step
        t, h, rows, evaluations = float(times[0]), min(first, max(times[-1] - times[0], 1e-12)), 1, 0
        f, end = np.zeros(len(x)), float(times[-1])

        def step(start: bool) -> tuple:
            args = (t, x, f, h, end, budget, start, times, out, loads, rows, float(rtol), float(atol), limit,
                    tableau, q0, u0, index, self.loaded, self.all_work, float(self.hub_radius))
            return self.joined(f"integrator {order}", "turbine simulation kernels", kernel, args, with_rate=True,
                               in_helper=True)

        t_before, rows_before = t, 0
        t, x, f, h, rows, count, status, bad = step(True)
        evaluations += count
        with interruptible() as interrupted:
            while True:
                if status:
                    return Integration(out, loads, rows, evaluations, int(status), float(t), int(bad))
                new = slice(rows_before, rows)
                reason = watch(t_before, t, times[new], out[new], loads[new], count) if watch else None
                if reason:
                    return Integration(out, loads, rows, evaluations, 4, float(t), reason=reason)
                if interrupted():
                    return Integration(out, loads, rows, evaluations, 5, float(t))
                if t >= end:
                    return Integration(out, loads, rows, evaluations, rate=f)
                t_before, rows_before = t, rows
                t, x, f, h, rows, count, status, bad = step(False)
                evaluations += count

    def outputs(self, times: NDArray, states: NDArray, q0: NDArray, u0: NDArray, index: NDArray,
                blade: int = 0) -> NDArray:
        """The load channels (T, len(compiled_outputs.COLUMNS)), SI, of ``blade``'s root and the rotor at every
        output row."""
        from .compiled_outputs import load_outputs
        args = (np.ascontiguousarray(times, dtype=float), np.ascontiguousarray(states, dtype=float),
                np.ascontiguousarray(q0, dtype=float), np.ascontiguousarray(u0, dtype=float),
                np.ascontiguousarray(index, dtype=np.int64), self.loaded, self.all_work, float(self.hub_radius),
                blade)
        return self.joined("outputs", "turbine outputs", load_outputs, args)

    def root_moments(self, times: NDArray, states: NDArray, q0: NDArray, u0: NDArray, index: NDArray,
                     blade: int = 0) -> NDArray:
        """Out-of-plane and in-plane root bending moments (T, 2), N m, of ``blade`` at every output row."""
        return self.outputs(times, states, q0, u0, index, blade)[:, :2]


def compiled_equations(model) -> CompiledEquations | None:
    """The compiled kernels on ``model``'s data; None without numba or with the environment variable
    BLADEFEM_NO_NUMBA set."""
    if numba is None or os.environ.get("BLADEFEM_NO_NUMBA"):
        return None
    from .compiled_aero_arrays import aero_data
    from .control import Generator
    law = (model.generator or Generator()).vector()
    return CompiledEquations(model_data(model), model.params.hub_radius, aero_data(model), law)
