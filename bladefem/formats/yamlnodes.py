"""Load YAML keeping the line number of every value, so errors can name the line.

Plain scalars are resolved by the YAML 1.2 core schema (what windIO's own tools use): ``1e9``, ``1.0e7``, ``.5``
and ``-3.`` are floats, ``true``/``false`` booleans, ``null``/``~`` null; ``yes``, ``on`` or ``1_000`` stay text.
Hostile files end in an :class:`InputError` naming the line: nesting deeper than :data:`MAX_DEPTH`, aliases that
expand to more than :data:`MAX_VALUES` values (alias bombs), a recursive alias, a duplicate key, a key that is not
a scalar, a number beyond double precision, more than one document, a tag other than the standard scalar ones.
The data is built from the parser's events without recursion.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from ..errors import InputError
from ..files import decode_utf8, read_input

Key = tuple[Any, ...]

#: Deepest nesting of mappings and lists accepted (windIO turbine files nest about 10 deep)
MAX_DEPTH = 64
#: Most values (scalars, mappings, lists, counting each use of an alias in full) in one file
MAX_VALUES = 2_000_000
#: Longest integer accepted, digits (a double holds 309)
MAX_DIGITS = 310

PARSER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
NULL = re.compile(r"~|null|Null|NULL|")
TRUE, FALSE = ("true", "True", "TRUE"), ("false", "False", "FALSE")
INTEGER = re.compile(r"[-+]?[0-9]+")
OCTAL, HEXADECIMAL = re.compile(r"0o[0-7]+"), re.compile(r"0x[0-9a-fA-F]+")
FLOAT = re.compile(r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?")
INFINITY = re.compile(r"[-+]?\.(inf|Inf|INF)")
NAN = re.compile(r"\.(nan|NaN|NAN)")
TAG = "tag:yaml.org,2002:"


@dataclass
class _Open:
    """A mapping or list being built: its value, key path, pending key (mappings) and anchor."""

    value: dict | list
    path: Key
    anchor: str | None
    start: int
    key: Any = None
    has_key: bool = False
    key_lines: dict = field(default_factory=dict)


class _Builder:
    def __init__(self, path: str) -> None:
        self.path = path
        self.lines: dict[Key, int] = {}
        self.anchors: dict[str, tuple[Any, int]] = {}
        self.stack: list[_Open] = []
        self.values = 0
        self.root: Any = None
        self.documents = 0

    def error(self, message: str, line: int) -> InputError:
        return InputError(message, file=self.path, line=line)

    def count(self, values: int, line: int) -> None:
        self.values += values
        if self.values > MAX_VALUES:
            raise self.error(f"more than {MAX_VALUES:,} values (counting every use of an alias in full): refusing "
                             "the file", line)

    def place(self, value: Any, line: int, is_key_candidate: bool) -> Key | None:
        """Put a finished value into the open container (or make it the root); its key path."""
        if not self.stack:
            self.root = value
            self.lines.setdefault((), line)
            return ()
        top = self.stack[-1]
        if isinstance(top.value, list):
            path = top.path + (len(top.value),)
            top.value.append(value)
            self.lines[path] = line
            return path
        if not top.has_key:
            if not is_key_candidate:
                raise self.error("a mapping key must be a plain value, not a list or mapping", line)
            if value in top.key_lines:
                raise self.error(f"duplicate key '{value}' (first at line {top.key_lines[value]})", line)
            top.key, top.has_key = value, True
            top.key_lines[value] = line
            self.lines[top.path + (value,)] = line
            return None
        path = top.path + (top.key,)
        top.value[top.key] = value
        top.has_key = False
        return path

    def open(self, event: yaml.Event, value: dict | list) -> None:
        line = event.start_mark.line + 1
        if event.tag not in (None, "!", TAG + ("map" if isinstance(value, dict) else "seq")):
            raise self.error(f"unsupported tag {event.tag} (only standard tags are read)", line)
        if len(self.stack) >= MAX_DEPTH:
            raise self.error(f"nested deeper than {MAX_DEPTH} levels", line)
        if self.stack and isinstance(self.stack[-1].value, dict) and not self.stack[-1].has_key:
            raise self.error("a mapping key must be a plain value, not a list or mapping", line)
        path = self.path_of_next()
        self.count(1, line)
        self.stack.append(_Open(value, path, event.anchor, self.values, key_lines={}))
        self.lines.setdefault(path, line)

    def path_of_next(self) -> Key:
        if not self.stack:
            return ()
        top = self.stack[-1]
        return top.path + ((len(top.value),) if isinstance(top.value, list) else (top.key,))

    def close(self, event: yaml.Event) -> None:
        done = self.stack.pop()
        size = self.values - done.start + 1
        self.place(done.value, self.lines.get(done.path, event.start_mark.line + 1), False)
        if done.anchor is not None:
            self.anchors[done.anchor] = (done.value, size)

    def scalar(self, event: yaml.ScalarEvent) -> None:
        line = event.start_mark.line + 1
        value = self.resolve(event, line)
        self.count(1, line)
        self.place(value, line, True)
        if event.anchor is not None:
            self.anchors[event.anchor] = (value, 1)

    def alias(self, event: yaml.AliasEvent) -> None:
        line = event.start_mark.line + 1
        if event.anchor not in self.anchors:
            raise self.error(f"alias *{event.anchor} refers to no complete anchor (undefined or recursive)", line)
        value, size = self.anchors[event.anchor]
        self.count(size, line)
        self.place(value, line, not isinstance(value, (dict, list)))

    def resolve(self, event: yaml.ScalarEvent, line: int) -> Any:
        text, tag = event.value, event.tag
        if tag == "!" or (tag is None and event.style):
            return text                                  # quoted, block or non-specific '!'
        if tag is None:
            return self.plain(text, line)
        kinds = {TAG + "str": str, TAG + "int": int, TAG + "float": float, TAG + "bool": bool, TAG + "null": None}
        if tag not in kinds:
            raise self.error(f"unsupported tag {tag} (only standard scalar tags are read)", line)
        if kinds[tag] is str:
            return text
        value = self.plain(text, line)
        wanted = kinds[tag]
        if wanted is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if (wanted is None and value is not None) or (wanted is not None and type(value) is not wanted):
            raise self.error(f"'{text}' is not a valid {tag[len(TAG):]}", line)
        return value

    def plain(self, text: str, line: int) -> Any:
        """A plain scalar by the YAML 1.2 core schema."""
        if NULL.fullmatch(text):
            return None
        if text in TRUE or text in FALSE:
            return text in TRUE
        if INTEGER.fullmatch(text) or OCTAL.fullmatch(text) or HEXADECIMAL.fullmatch(text):
            if len(text) > MAX_DIGITS:
                raise self.error(f"number with {len(text)} digits is beyond double precision", line)
            value = int(text, 8 if text.startswith("0o") else 16 if text.startswith("0x") else 10)
            if abs(value) > 1.7976931348623157e308:
                raise self.error(f"number {text[:12]}... is beyond double precision (1.8e308)", line)
            return value
        if FLOAT.fullmatch(text):
            value = float(text)
            if math.isinf(value):
                raise self.error(f"number {text} is beyond double precision (1.8e308)", line)
            return value
        if INFINITY.fullmatch(text):
            return -math.inf if text.startswith("-") else math.inf
        if NAN.fullmatch(text):
            return math.nan
        return text


def parse_yaml(text: str, path: str = "<input>") -> tuple[Any, dict[Key, int]]:
    """Parse YAML text; return the data and a map from key paths (tuples of keys/indices) to 1-based lines."""
    builder = _Builder(path)
    try:
        for event in yaml.parse(text, Loader=PARSER):
            if isinstance(event, yaml.ScalarEvent):
                builder.scalar(event)
            elif isinstance(event, yaml.MappingStartEvent):
                builder.open(event, {})
            elif isinstance(event, yaml.SequenceStartEvent):
                builder.open(event, [])
            elif isinstance(event, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
                builder.close(event)
            elif isinstance(event, yaml.AliasEvent):
                builder.alias(event)
            elif isinstance(event, yaml.DocumentStartEvent):
                builder.documents += 1
                if builder.documents > 1:
                    raise builder.error("a second YAML document ('---'): one document per file",
                                        event.start_mark.line + 1)
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        problem = getattr(error, "problem", None) or str(error).splitlines()[0]
        where = f" (column {mark.column + 1})" if mark is not None else ""
        line = None if mark is None else mark.line + 1
        if isinstance(error, yaml.reader.ReaderError):      # a character YAML refuses: its position, no mark
            code = error.character if isinstance(error.character, int) else ord(error.character[:1] or "\0")
            problem = f"character U+{code:04X} is not allowed in YAML (a control character or not text)"
            line = text[:error.position].count("\n") + 1
        raise InputError(f"invalid YAML: {problem}{where}", file=path, line=line) from None
    return builder.root, builder.lines


def load_yaml(path: str | Path) -> tuple[Any, dict[Key, int]]:
    """Parse a YAML file; return the data and a map from key paths (tuples of keys/indices) to 1-based lines."""
    text = decode_utf8(read_input(path), path)
    data, lines = parse_yaml(text, str(path))
    if data is None and not lines:
        raise InputError("no content (only comments or blank lines)", file=str(path), line=1)
    return data, lines
