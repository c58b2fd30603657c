"""Watchdogs for tests: a hang fails the test instead of stalling the suite, by process CPU time (:func:`cpu_limit`)
or by wall time (:func:`wall_limit`, for a block that waits idle: a FIFO opened for reading, a client waiting on a
hung worker)."""

from __future__ import annotations

import contextlib
import signal


class Hang(BaseException):
    """Raised by :func:`cpu_limit` and :func:`wall_limit`; a BaseException so that no ``except Exception`` (or
    ``except OSError``) in the code under test swallows it."""


@contextlib.contextmanager
def _alarm(signum: int, timer: int, seconds: float, message: str):
    """Raise :class:`Hang` with ``message`` when ``timer`` (an interval timer sending ``signum``) runs out."""
    def expire(signum, frame):
        raise Hang(message)

    previous = signal.signal(signum, expire)
    signal.setitimer(timer, seconds)
    try:
        yield
    finally:
        signal.setitimer(timer, 0)
        signal.signal(signum, previous)


def cpu_limit(seconds: float, reason: str = ""):
    """Raise :class:`Hang` when the block takes more than ``seconds`` of process CPU time."""
    return _alarm(signal.SIGPROF, signal.ITIMER_PROF, seconds,
                  f"more than {seconds} s of CPU{': ' + reason if reason else ''}")


def wall_limit(seconds: float, reason: str = ""):
    """Raise :class:`Hang` when the block takes more than ``seconds`` of wall time."""
    return _alarm(signal.SIGALRM, signal.ITIMER_REAL, seconds,
                  f"more than {seconds} s of wall time{': ' + reason if reason else ''}")
