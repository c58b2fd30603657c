"""Errors raised for user mistakes (bad input files, bad option values)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["InputError", "LimitError", "SolveError", "shown"]


def shown(value: object, limit: int = 40, quoted: bool = True) -> str:
    """``repr(value)`` (``str`` when not ``quoted``) cut to ``limit`` characters, for echoing what a file holds in a
    one-line message."""
    text = repr(value) if quoted else str(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


@dataclass
class InputError(Exception):
    """A user mistake in an input file or option, located by file, line and field.

    The CLI prints ``str(error)`` as one line and exits with code 2.
    """

    message: str
    file: str | None = None
    line: int | None = None
    field: str | None = None

    def __str__(self) -> str:
        if self.file is None:                          # an option or argument: name it
            return f"field '{self.field}': {self.message}" if self.field else self.message
        where = self.file
        if self.line is not None:
            where += f":{self.line}"
        field = f" field '{self.field}':" if self.field else ""
        return f"{where}:{field} {self.message}"


class SolveError(Exception):
    """A computation whose answer is not a result (e.g. an eigenpair whose residual is not small, usually from
    section properties too extreme for double precision). The CLI prints it as one line and exits with code 1."""


class LimitError(InputError, ValueError):
    """An argument outside what the models can answer (see :mod:`bladefem.limits`): a ``ValueError`` for the Python
    API, a one-line error with exit code 2 on the command line."""
