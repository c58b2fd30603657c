"""Errors raised for user mistakes (bad input files, bad option values)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["InputError"]


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
        where = self.file or "<input>"
        if self.line is not None:
            where += f":{self.line}"
        field = f" field '{self.field}':" if self.field else ""
        return f"{where}:{field} {self.message}"
