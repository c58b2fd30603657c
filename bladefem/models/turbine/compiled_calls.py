"""The integrators joined to the kernels they call through numba's first-class functions, so that each kernel's
machine code is generated once.

numba links the library of every kernel a kernel calls into its own and optimizes and generates machine code again
for the whole tree (of a cold run's compilation, 8.4 s went to the integrator regenerating the equations, the
aerodynamic loads and the output row it calls through the state rate). A kernel given another one as an argument of
type ``numba.types.FunctionType(signature)`` calls it through its address instead: nothing is linked. So the
integrators (:func:`.compiled_integrators.dp54_chunk`, :func:`.compiled_integrators.dop853_chunk`) take the state
rate (:func:`.compiled_integrators.rate_function`) as such an argument, and the state rate the structural equations
(:func:`.compiled_kernels.equations`), the aerodynamic loads (:func:`.compiled_loads.add_aero`) and the output row
(:func:`.compiled_outputs.output_row`) as a tuple of them; each is compiled (or loaded from numba's disk cache) on
its own, the aerodynamic loads possibly in a helper process (:mod:`.parallel_compile`).

A dispatcher given a dispatcher argument compiles a version for it (and links it); the integrators are therefore
called through dispatchers made for the one signature with the function types (:func:`integrator`), which numba
meets by converting the dispatchers passed to the function types.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from functools import cache

import numpy as np


@contextmanager
def unwarned() -> Iterator[None]:
    """numba's warning that its first-class function types are experimental (numba 0.68; raised as the types are
    made and as kernels taking them compile) silenced: it is not the user's to act on."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="First-class function type feature is experimental")
        yield


def kernel_types(loaded: tuple, work: tuple):
    """numba type of the tuple (structural equations, aerodynamic loads, output row) the state rate takes, for
    ``loaded`` and ``work`` of :class:`.compiled.CompiledEquations` (argument types of
    :func:`.parallel_compile.kernel_signatures`)."""
    from numba import typeof, types
    from .parallel_compile import kernel_signatures
    kinds = kernel_signatures(loaded, work)
    matrix, vector = typeof(np.zeros((1, 1))), typeof(np.zeros(1))
    return types.Tuple((types.FunctionType(types.Tuple((matrix, vector))(*kinds["structure"])),
                        types.FunctionType(types.none(*kinds["aero"])),
                        types.FunctionType(types.none(*kinds["row"]))))


def rate_types(loaded: tuple, work: tuple) -> tuple:
    """Argument types of :func:`.compiled_integrators.rate_function`."""
    from numba import typeof, types
    vector, index = typeof(np.zeros(1)), typeof(np.zeros(1, dtype=np.int64))
    return (kernel_types(loaded, work), types.float64, vector, vector, vector, index, typeof(loaded), typeof(work),
            types.float64, vector)


def functions(with_rate: bool = True) -> tuple:
    """The dispatchers a joined kernel is given: (the state rate, (structural equations, aerodynamic loads, output
    row)); without ``with_rate`` the kernels' tuple alone (the output rows, the derivative)."""
    from .compiled_integrators import rate_function
    from .compiled_kernels import equations
    from .compiled_loads import add_aero
    from .compiled_outputs import output_row
    called = (equations, add_aero, output_row)
    return (rate_function, called) if with_rate else (called,)


def kernels(loaded: tuple, work: tuple, with_rate: bool = True) -> tuple:
    """:func:`functions`, each compiled (or loaded from the disk cache) for its argument types first: numba converts
    a dispatcher without that version to a function type by compiling it for the full signature, return type
    included, another entry of the disk cache than the one :mod:`.parallel_compile`'s helper writes."""
    from .parallel_compile import kernel_signatures
    given = functions(with_rate)
    kinds = kernel_signatures(loaded, work)
    for dispatcher, kind in zip(given[-1], ("structure", "aero", "row")):
        dispatcher.compile(kinds[kind])
    if with_rate:
        given[0].compile(rate_types(loaded, work))
    return given


def integrator_types(kernel, loaded: tuple, work: tuple, args: tuple, with_rate: bool = True) -> tuple:
    """Argument types of the integrator ``kernel`` for its arguments ``args`` after the function ones (the state
    rate and the kernels' tuple; the tuple alone without ``with_rate``)."""
    from numba import typeof, types
    rate = types.FunctionType(typeof(np.zeros(1))(*rate_types(loaded, work)))
    return (*((rate,) if with_rate else ()), kernel_types(loaded, work), *(kernel.typeof_pyval(a) for a in args))


@cache
def integrator(kernel, signature: tuple):
    """``kernel`` (a numba dispatcher) compiled for ``signature`` only, and cached: called with the dispatchers of
    :func:`kernels`, it converts them to its function types rather than compiling a version for them."""
    from ...numba_cache import cached_njit
    return cached_njit()([signature], cache=True)(kernel.py_func)


def linked(kernel, with_rate: bool = True) -> tuple:
    """``kernel`` with :func:`functions` given as dispatchers: numba compiles a version of it for them and links them
    in, as before first-class functions (a slower cold compilation, the same results). The fallback of :func:`join`
    where this numba cannot make or call the function types (marked experimental)."""
    return kernel, *functions(with_rate)


def function_types(kernel, loaded: tuple, work: tuple, args: tuple, with_rate: bool = True) -> tuple | None:
    """:func:`integrator_types`, or None where this numba cannot make the function types."""
    from numba.core.errors import NumbaError
    try:
        return integrator_types(kernel, loaded, work, args, with_rate)
    except (NumbaError, TypeError):
        return None


def join(kernel, loaded: tuple, work: tuple, args: tuple, signature: tuple | None, with_rate: bool = True
         ) -> tuple[tuple, tuple]:
    """(the kernel and the functions it is called with, its first call's result) for ``kernel`` called with
    ``args`` after the function arguments (the state rate if ``with_rate``, and the kernels' tuple): through
    first-class functions for ``signature`` (:func:`function_types`); where numba refuses them (None, or a numba
    error or a type mismatch while they are compiled or first called, before the kernel has run) with the kernels
    linked in (:func:`linked`)."""
    from numba.core.errors import NumbaError
    if signature is not None:
        try:
            joined = (integrator(kernel, signature), *kernels(loaded, work, with_rate))
            return joined, joined[0](*joined[1:], *args)
        except (NumbaError, TypeError):
            pass
    joined = linked(kernel, with_rate)
    return joined, joined[0](*joined[1:], *args)
