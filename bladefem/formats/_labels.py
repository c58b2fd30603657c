"""Label lookup for OpenFAST module input files (.fst, AeroDyn, InflowWind, ServoDyn).

OpenFAST matches labels without regard to case (``PLExp`` / ``PLexp``), its versions and tools spell some of them
differently (``BldFile(1)`` / ``BldFile1``, :mod:`bladefem.formats._label_table`) and recent versions renamed several of
them (``WakeMod`` -> ``Wake_Mod``); :class:`Labels` finds a value under any of its names, treats the word ``default``
as "use the default", and reports problems as :class:`InputError` naming the file, line and label.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import InputError
from ..files import input_problem
from ._fast_format import FALSE_WORDS, TRUE_WORDS, FastText, KeyValue, to_float, to_int


class Labels:
    """Case-insensitive access to the ``value label`` lines of one file."""

    def __init__(self, text: FastText) -> None:
        self.text = text

    @classmethod
    def read(cls, path: str | os.PathLike) -> Labels:
        return cls(FastText.read(path))

    @property
    def path(self) -> str:
        return self.text.path

    def error(self, message: str, line: int | None = None, label: str | None = None) -> InputError:
        return self.text.error(message, line, label)

    def which(self, *names: str) -> str | None:
        """The first of ``names`` present in the file (as spelled there, under any of its spellings in
        :mod:`bladefem.formats._label_table`), or None."""
        for name in names:
            written = self.text.spelled(name)
            if written is not None:
                return written
        for name in names:
            self.text.refuse_crowded(name)
        return None

    def has(self, *names: str) -> bool:
        return self.which(*names) is not None

    def entry(self, *names: str) -> tuple[str, KeyValue]:
        written = self.which(*names)
        if written is not None:
            return written, self.text.keys[written]
        raise self.error("missing label" + (f" (also looked for {', '.join(names[1:])})" if names[1:] else ""),
                         len(self.text.lines) or None, names[0])

    def line(self, *names: str) -> int:
        return self.entry(*names)[1].line

    def string(self, *names: str) -> str:
        return self.entry(*names)[1].text.strip()

    def is_default(self, *names: str) -> bool:
        return self.string(*names).lower() == "default"

    def float(self, *names: str, default: float | None = None, positive: bool = False,
              non_negative: bool = False) -> float:
        """A number; the word ``default`` gives ``default`` (an error when there is none)."""
        key, entry = self.entry(*names)
        if entry.text.strip().lower() == "default":
            if default is None:
                raise self.error("no default: give a number", entry.line, key)
            return default
        value = to_float(entry.text, self.error, entry.line, key)
        if positive and value <= 0:
            raise self.error(f"must be positive, got {entry.text}", entry.line, key)
        if non_negative and value < 0:
            raise self.error(f"must not be negative, got {entry.text}", entry.line, key)
        return value

    def int(self, *names: str, default: int | None = None, choices: tuple[int, ...] | None = None) -> int:
        key, entry = self.entry(*names)
        if entry.text.strip().lower() == "default" and default is not None:
            return default
        value = to_int(entry.text, self.error, entry.line, key)
        if choices is not None and value not in choices:
            raise self.error(f"must be one of {', '.join(map(str, choices))}, got {value}", entry.line, key)
        return value

    def bool(self, *names: str) -> bool:
        key, entry = self.entry(*names)
        word = entry.text.strip().lower()
        if word in TRUE_WORDS:
            return True
        if word in FALSE_WORDS:
            return False
        raise self.error(f"expected True or False, got '{entry.text}'", entry.line, key)

    def file(self, *names: str) -> Path:
        """A file name resolved against this file's folder."""
        key, entry = self.entry(*names)
        name = entry.text.strip()
        if not name:
            raise self.error("empty file name", entry.line, key)
        return Path(os.path.normpath(Path(self.text.path).parent / name))

    def existing_file(self, *names: str) -> Path:
        """:meth:`file`, which must exist."""
        path = self.file(*names)
        problem = input_problem(path)
        if problem is not None:
            key, entry = self.entry(*names)
            raise self.error(f"{problem}: {path}", entry.line, key)
        return path
