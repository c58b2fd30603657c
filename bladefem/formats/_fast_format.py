"""Line parser shared by the FAST-style ("value  Key  - description") input files of ElastoDyn and BModes.

A FAST input file is a sequence of lines; most hold one value followed by its key name and a comment:
``     63   TipRad      - The distance from the rotor apex to the blade tip (meters)``. Tables are blocks of rows
of numbers. This module finds keys wherever they are (the files are read by key, not by position, so reordered or
commented files still read) and reports every problem as an :class:`InputError` naming the file, the 1-based line
and the field.

The raw text is kept (:class:`FastText`) so that writers can change a value in place and leave every other byte of
the file as it was.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field

from ..errors import InputError
from ..files import read_input
from ..limits import MAX_MAGNITUDE
from ._label_table import spellings

#: A value (quoted string or a token without blanks) followed by a key name such as ``TipRad`` or ``PreCone(1)``.
#: BModes writes ``rot_rpm:`` (a colon after the key) and sometimes ``"file" : key``; both are accepted.
KEY_LINE = re.compile(r"""^(?P<lead>\s*)(?P<value>"[^"]*"|'[^']*'|[^\s"',]+)(?P<gap>\s+(?::\s*)?)"""
                      r"""(?P<key>[A-Za-z_][A-Za-z0-9_]*(?:\(\d+\))?):?(?=\s|$)""")
#: A line with several values before a key name (``1 2   TwrPotent``): not a ``value key`` line, but a mistake in
#: one when the key is asked for (a key named in a heading or a comment is preceded by words, not values)
_VALUE = r"""(?:[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?|true|false|t|f|default|"[^"]*")"""
CROWDED_LINE = re.compile(rf"""^\s*(?:{_VALUE}\s+){{2,}}(?P<key>[A-Za-z_][A-Za-z0-9_]*(?:\(\d+\))?)(?=\s|$)""",
                          re.IGNORECASE)
TRUE_WORDS = ("true", "t", ".true.")
FALSE_WORDS = ("false", "f", ".false.")


@dataclass(frozen=True)
class KeyValue:
    """One ``value key`` line: the value's text, its 1-based line number, and its character span in the line."""

    text: str
    line: int
    start: int
    end: int
    key_start: int = 0


@dataclass
class FastText:
    """The lines of an input file (line endings kept) and an index of its ``value key`` lines."""

    path: str
    lines: list[str]
    keys: dict[str, KeyValue] = field(default_factory=dict)
    #: how the file's bytes decode ("utf-8", or "latin-1" for legacy files); write it back the same way
    encoding: str = "utf-8"
    _lower: dict[str, str] = field(default_factory=dict, repr=False, compare=False)
    #: key name (lower case) -> line of a line with several values before that key (see :data:`CROWDED_LINE`)
    crowded: dict[str, int] = field(default_factory=dict)

    @classmethod
    def read(cls, path: str | os.PathLike) -> FastText:
        """Read a file as text; a missing or unreadable file is an :class:`InputError`."""
        path = str(path)
        raw = read_input(path)
        encoding = text_encoding(raw)
        text = raw.decode(encoding)
        if "\x00" in text:
            raise InputError("not a text file (contains NUL bytes)", file=path,
                             line=text[:text.index("\x00")].count("\n") + 1)
        if not text.strip():
            raise InputError("file holds only blank lines", file=path, line=1)
        parsed = cls.parse(path, text)
        parsed.encoding = encoding
        return parsed

    @classmethod
    def parse(cls, path: str, text: str) -> FastText:
        lines = text.splitlines(keepends=True)
        keys: dict[str, KeyValue] = {}
        crowded: dict[str, int] = {}
        for number, line in enumerate(lines, start=1):
            match = KEY_LINE.match(line)
            if match is None and (extra := CROWDED_LINE.match(line)):
                crowded.setdefault(extra["key"].lower(), number)
            if match is None or match["key"] in keys:
                continue
            value = match["value"]
            if value[0] in "\"'":
                value = value[1:-1]
            keys[match["key"]] = KeyValue(value, number, match.start("value"), match.end("value"),
                                          match.start("key"))
        return cls(path, lines, keys, crowded=crowded)

    def refuse_crowded(self, key: str) -> None:
        """An InputError when ``key`` (under any of its spellings), absent as a ``value key`` line, has a line with
        several values before it."""
        for name in spellings(key):
            line = self.crowded.get(name.lower())
            if line is not None:
                values = self.lines[line - 1].split()
                count = next(i for i, word in enumerate(values) if word.lower() == name.lower())
                raise self.error(f"expected one value before {name}, found {count} ({' '.join(values[:count])})",
                                 line, name)

    # -- errors -------------------------------------------------------------------------------------------------
    def error(self, message: str, line: int | None = None, field: str | None = None) -> InputError:
        """An :class:`InputError` in this file; without a line, the end of the file (where a missing entry was
        looked for last)."""
        return InputError(message, file=self.path, line=line if line is not None else max(len(self.lines), 1),
                          field=field)

    def spelled(self, key: str) -> str | None:
        """The label under which the file writes ``key`` (any spelling of :func:`~bladefem.formats._label_table.spellings`,
        any case), or None."""
        if key in self.keys:
            return key
        folded = self._folded()
        for name in spellings(key):
            if name.lower() in folded:
                return folded[name.lower()]
        return None

    def _folded(self) -> dict[str, str]:
        if len(self._lower) != len(self.keys):
            self._lower.clear()
            for written, entry in sorted(self.keys.items(), key=lambda item: item[1].line):
                self._lower.setdefault(written.lower(), written)
        return self._lower

    def find(self, key: str) -> KeyValue:
        written = self.spelled(key)
        if written is None:
            self.refuse_crowded(key)
            names = spellings(key)
            also = f" (also looked for {', '.join(names[1:])})" if names[1:] else ""
            raise self.error("missing key" + also, line=len(self.lines) or None, field=key)
        return self.keys[written]

    def has(self, key: str) -> bool:
        if self.spelled(key) is None:
            self.refuse_crowded(key)
            return False
        return True

    # -- typed values -------------------------------------------------------------------------------------------
    def float(self, key: str, *, positive: bool = False, non_negative: bool = False) -> float:
        entry = self.find(key)
        value = to_float(entry.text, self.error, entry.line, key)
        if positive and value <= 0:
            raise self.error(f"must be positive, got {entry.text}", entry.line, key)
        if non_negative and value < 0:
            raise self.error(f"must not be negative, got {entry.text}", entry.line, key)
        return value

    def int(self, key: str, *, minimum: int | None = None) -> int:
        entry = self.find(key)
        value = to_int(entry.text, self.error, entry.line, key)
        if minimum is not None and value < minimum:
            raise self.error(f"must be at least {minimum}, got {value}", entry.line, key)
        return value

    def bool(self, key: str) -> bool:
        entry = self.find(key)
        word = entry.text.strip().lower()
        if word in TRUE_WORDS:
            return True
        if word in FALSE_WORDS:
            return False
        raise self.error(f"expected True or False, got '{entry.text}'", entry.line, key)

    def string(self, key: str) -> str:
        return self.find(key).text

    def line_of(self, key: str) -> int:
        return self.find(key).line

    # -- tables -------------------------------------------------------------------------------------------------
    def header_line(self, first_column: str, after: int = 0) -> int:
        """1-based number of the first line after line ``after`` whose first word is ``first_column``."""
        for number in range(after + 1, len(self.lines) + 1):
            words = self.lines[number - 1].split()
            if words and words[0].lower() == first_column.lower():
                return number
        raise self.error(f"table header starting with '{first_column}' not found", len(self.lines) or None,
                         first_column)

    def table(self, first_line: int, rows: int, columns: tuple[str, ...], exact: bool = False) -> list[list[float]]:
        """Read ``rows`` rows of numbers starting at 1-based line ``first_line``, one value per column name (and,
        with ``exact``, nothing more on the line)."""
        table = []
        for number in range(first_line, first_line + rows):
            if number > len(self.lines):
                raise self.error(f"table ends early: expected {rows} rows, found {number - first_line}", number - 1,
                                 columns[0])
            table.append(self.row(number, columns, exact))
        return table

    def row(self, number: int, columns: tuple[str, ...], exact: bool = False) -> list[float]:
        words = self.lines[number - 1].split()
        if exact and len(words) > len(columns):
            raise self.error(f"expected {len(columns)} values ({' '.join(columns)}), found {len(words)}", number,
                             columns[-1])
        values = []
        for i, name in enumerate(columns):
            if i >= len(words):
                raise self.error(f"expected {len(columns)} columns, found {len(words)}", number, name)
            values.append(to_float(words[i], self.error, number, name))
        return values

    # -- in-place editing ---------------------------------------------------------------------------------------
    def replaced(self, values: dict[str, str]) -> str:
        """The file's text with the value of each given key replaced; every other line is kept byte for byte.
        The new value is right-aligned where the old one ended, or, when longer, as far as the key column allows
        (keeping the key where it was and at least one blank before it)."""
        lines = list(self.lines)
        for key, new in values.items():
            entry = self.find(key)
            line = lines[entry.line - 1]
            if len(new) < entry.end:
                lines[entry.line - 1] = new.rjust(entry.end) + line[entry.end:]
            elif len(new) < entry.key_start:
                lines[entry.line - 1] = new.rjust(entry.key_start - 1) + " " + line[entry.key_start:]
            else:
                lines[entry.line - 1] = new + " " + line[entry.key_start:]
        return "".join(lines)


def text_encoding(data: bytes | str | os.PathLike) -> str:
    """"utf-8" when the bytes (or the file's bytes) decode as UTF-8, else "latin-1" (legacy FAST and BModes files
    carry Latin-1 degree signs and micro signs in their comments)."""
    if not isinstance(data, bytes):
        data = read_input(data)
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return "latin-1"
    return "utf-8"


def to_float(text: str, error, line: int | None, key: str) -> float:
    """A finite float from Fortran-style text (``1.0D+3`` and ``1.0d3`` accepted), at most
    :data:`~bladefem.limits.MAX_MAGNITUDE` in size."""
    try:
        value = float(text.replace("D", "E").replace("d", "e"))
    except ValueError:
        raise error(f"expected a number, got '{text}'", line, key) from None
    if not math.isfinite(value):
        raise error(f"value is not a finite number ({text})", line, key)
    if abs(value) > MAX_MAGNITUDE:
        raise error(f"{text} is beyond any value a blade, tower or turbine input takes (|value| up to "
                    f"{MAX_MAGNITUDE:g})", line, key)
    return value


def to_int(text: str, error, line: int | None, key: str) -> int:
    """An integer (``3``, or ``3.0``), at most :data:`~bladefem.limits.MAX_MAGNITUDE` in size."""
    try:
        value = int(text)
    except ValueError:
        pass
    else:
        if abs(value) > MAX_MAGNITUDE:
            raise error(f"must be at most {MAX_MAGNITUDE:g} in magnitude, got {text[:20]}"
                        f"{'...' if len(text) > 20 else ''}", line, key)
        return value
    value = to_float(text, error, line, key)
    if value != int(value):
        raise error(f"expected an integer, got '{text}'", line, key)
    return int(value)


def format_number(value: float) -> str:
    """Shortest text that reads back as exactly the same float."""
    return repr(float(value))


def exact_inverse(value: float, to_file, from_file) -> float:
    """A number ``y`` within a few ulps of ``to_file(value)`` with ``from_file(y) == value`` exactly, so that a file
    written from SI values (e.g. radians written as degrees) reads back bit for bit."""
    guess = to_file(value)
    up = down = guess
    candidates = [guess]
    for _ in range(16):
        up, down = math.nextafter(up, math.inf), math.nextafter(down, -math.inf)
        candidates += [up, down]
    for candidate in candidates:
        if from_file(candidate) == value:
            return candidate
    return guess


def degrees_exact(radians: float) -> float:
    """Degrees that :func:`math.radians` maps back to exactly ``radians``."""
    return exact_inverse(float(radians), math.degrees, math.radians)


def rpm_to_rad_per_s(rpm: float) -> float:
    return rpm * math.pi / 30.0


def rpm_exact(rad_per_s: float) -> float:
    """rpm that :func:`rpm_to_rad_per_s` maps back to exactly ``rad_per_s``."""
    return exact_inverse(float(rad_per_s), lambda w: w * 30.0 / math.pi, rpm_to_rad_per_s)


