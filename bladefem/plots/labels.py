"""Names of modes and mode families in figures and tables: '1st flap', '2nd fore-aft', ..."""

from __future__ import annotations

from collections.abc import Iterable


def ordinal(n: int) -> str:
    """1st, 2nd, 3rd, 4th, ... 11th, 12th, 13th, 21st."""
    suffix = "th" if 10 <= n % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return f"{n}{suffix}"


def kind_labels(kinds: Iterable[str]) -> list[str]:
    """'1st flap', '1st edge', '2nd flap', ... counting each kind in the given order."""
    counts: dict[str, int] = {}
    labels = []
    for kind in kinds:
        counts[kind] = counts.get(kind, 0) + 1
        labels.append(f"{ordinal(counts[kind])} {kind}")
    return labels


def mode_labels(modes: Iterable) -> list[str]:
    """Labels of modes (objects with a ``kind``) in frequency order."""
    return kind_labels(mode.kind for mode in modes)
