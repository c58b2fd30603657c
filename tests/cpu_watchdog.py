"""A CPU-time watchdog for tests: a hang fails the test instead of stalling the suite."""

from __future__ import annotations

import contextlib
import signal


class Hang(BaseException):
    """Raised by :func:`cpu_limit`; a BaseException so that no ``except Exception`` (or ``except OSError``) in the
    code under test swallows it."""


@contextlib.contextmanager
def cpu_limit(seconds: float, reason: str = ""):
    """Raise :class:`Hang` when the block takes more than ``seconds`` of process CPU time."""
    def expire(signum, frame):
        raise Hang(f"more than {seconds} s of CPU{': ' + reason if reason else ''}")

    previous = signal.signal(signal.SIGPROF, expire)
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)
