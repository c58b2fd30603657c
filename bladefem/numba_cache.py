"""numba's on-disk cache of bladefem's kernels, made stale by a change in any kernel source.

numba keys a cached function by its own source file only: a kernel that calls a kernel of another file keeps its
cached machine code, with the old callee inlined, after that file changes (a partial update of an editable install,
a ``git pull``): the compiled path then silently runs old physics. :func:`install` puts, in front of numba's own
cache locators, the same locators (the package's ``__pycache__`` when writable, else numba's user cache folder, or
``NUMBA_CACHE_DIR``) for bladefem's files whose freshness stamp also holds a hash of every kernel source
(:data:`KERNEL_SOURCES`). It uses numba's private ``CacheImpl._locator_classes``; where that moved, numba's own
caching stays (the stale case included).
"""

from __future__ import annotations

import hashlib
from functools import cache
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
#: The files whose numba kernels call one another, relative to the package.
KERNEL_SOURCES = ("aero/*.py", "models/turbine/compiled*.py", "models/turbine/control.py",
                  "models/turbine/pitching.py")


@cache
def sources_hash() -> str:
    """SHA-256 of the kernel sources' names and contents."""
    digest = hashlib.sha256()
    for pattern in KERNEL_SOURCES:
        for path in sorted(PACKAGE.glob(pattern)):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def _whole(base):
    """``base`` locator for bladefem's files, stamped with the kernel sources' hash too."""

    class Locator(base):
        bladefem = True

        @classmethod
        def from_function(cls, py_func, py_file):
            if not Path(py_file).resolve().is_relative_to(PACKAGE):
                return None
            return super().from_function(py_func, py_file)

        def get_source_stamp(self):
            return super().get_source_stamp(), sources_hash()

    Locator.__name__ = Locator.__qualname__ = f"Bladefem{base.__name__}"
    return Locator


def install() -> None:
    """Put the locators in front of numba's (once per process); nothing without numba."""
    try:
        from numba.core import caching

        def named(name: str):                            # numba 0.68 dropped the leading underscores
            return getattr(caching, name, None) or getattr(caching, "_" + name)

        classes = named("CacheImpl")._locator_classes
        bases = tuple(named(name) for name in ("UserProvidedCacheLocator", "InTreeCacheLocator",
                                               "UserWideCacheLocator"))
    except (ImportError, AttributeError):                # numba missing, or its private API moved
        return
    if not any(getattr(locator, "bladefem", False) for locator in classes):
        classes[:0] = [_whole(base) for base in bases]


def cached_njit():
    """numba's ``njit`` with these locators installed (kernels cached, stale when any kernel source changes),
    without literal specializations (:func:`_unliteral`) and with numpy's error model unless a kernel asks
    otherwise (a float division by zero gives an IEEE inf or nan, which the runs' finiteness checks report, where
    the Python model raised ZeroDivisionError from inside a kernel; its test before every division kept LLVM from
    optimising the BEM and Kane kernels: the NREL 5MW's 100 s torque-law run 1.45 to 1.32 s of CPU), or None
    without numba: the one place the compiled modules take their compiler from."""
    try:
        from numba import njit
    except ImportError:                                    # pragma: no cover - numba is a dependency
        return None
    install()

    def compiler(*args, **options):
        options.setdefault("error_model", "numpy")
        if args and callable(args[0]):
            return _unliteral(njit(**options)(args[0]))
        decorate = njit(*args, **options)
        return lambda function: _unliteral(decorate(function))
    return compiler


def _unliteral(dispatcher):
    """``dispatcher`` compiled once per argument types when another kernel calls it with constants: numba types a
    constant argument (``rotate(..., 1, ...)``) as a literal and compiles, and links into every caller, one
    machine-code version per value (eight of one wind interpolation, three of a frame rotation); this types the
    arguments of such calls as their plain types (int64 for an int). Uses numba's ``get_call_template``; where
    that moved, the dispatcher is left as it is."""
    try:
        from numba.core import types
        template = dispatcher.get_call_template
    except (ImportError, AttributeError):                # pragma: no cover - numba's API moved
        return dispatcher

    def get_call_template(args, kws):
        return template(tuple(types.unliteral(a) for a in args), {k: types.unliteral(v) for k, v in kws.items()})

    dispatcher.get_call_template = get_call_template
    return dispatcher
