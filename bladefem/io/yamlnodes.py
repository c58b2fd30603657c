"""Load YAML keeping the line number of every value, so errors can name the line."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

from ..errors import InputError

Key = tuple[Any, ...]


def _plain(node: yaml.Node, path: Key, lines: dict[Key, int]) -> Any:
    lines.setdefault(path, node.start_mark.line + 1)
    if isinstance(node, yaml.MappingNode):
        out = {}
        for key_node, value_node in node.value:
            key = key_node.value
            lines[path + (key,)] = key_node.start_mark.line + 1
            out[key] = _plain(value_node, path + (key,), lines)
        return out
    if isinstance(node, yaml.SequenceNode):
        return [_plain(item, path + (i,), lines) for i, item in enumerate(node.value)]
    return yaml.SafeLoader("").construct_object(node, deep=True)


def load_yaml(path: str | Path) -> tuple[Any, dict[Key, int]]:
    """Parse a YAML file; return the data and a map from key paths (tuples of keys/indices) to 1-based lines."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError("file not found", file=str(path)) from None
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"cannot read file ({error})", file=str(path)) from None
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        problem = getattr(error, "problem", None) or str(error).splitlines()[0]
        raise InputError(f"invalid YAML: {problem}", file=str(path),
                         line=None if mark is None else mark.line + 1) from None
    lines: dict[Key, int] = {}
    if node is None:
        raise InputError("file is empty", file=str(path))
    return _plain(node, (), lines), lines
