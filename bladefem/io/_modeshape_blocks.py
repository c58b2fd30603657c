"""ElastoDyn's polynomial mode-shape blocks: five coefficients ``c_2 .. c_6`` of ``phi(x) = sum c_i x^i``.

ElastoDyn normalises each shape to 1 at the tip (``sum c_i = 1``) and refuses a block whose sum is off by more
than 0.001 (a single-precision check). Shipped files round large coefficients to six digits and miss by about that
much (the NREL 5MW tower's TwSSM2Sh adds up to 0.999), so the readers accept up to 0.01 and reject beyond.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ._fast_format import FastText, format_number

POWERS = (2, 3, 4, 5, 6)
#: Accepted deviation of a block's sum from 1 (ElastoDyn's own check is 0.001 in single precision).
SUM_TOLERANCE = 1e-2


def block_keys(prefix: str) -> tuple[str, ...]:
    """Key names of one block, e.g. ``BldFl1Sh(2)`` .. ``BldFl1Sh(6)``."""
    return tuple(f"{prefix}({power})" for power in POWERS)


def read_block(text: FastText, prefix: str) -> NDArray[np.float64]:
    """The five coefficients of block ``prefix``; :class:`InputError` if one is missing, not a number, or the block
    does not add up to 1."""
    keys = block_keys(prefix)
    coefficients = np.array([text.float(key) for key in keys])
    if abs(coefficients.sum() - 1.0) > SUM_TOLERANCE:
        raise text.error(f"mode-shape coefficients must add up to 1 (tip-normalised), they add up to "
                         f"{coefficients.sum():.6g}", text.line_of(keys[-1]), prefix)
    return coefficients


def block_values(prefix: str, coefficients: NDArray) -> dict[str, str]:
    """Key -> text of each coefficient, for an in-place update."""
    return {key: format_number(value) for key, value in zip(block_keys(prefix), coefficients)}


def block_lines(prefix: str, coefficients: NDArray, label: str) -> list[str]:
    """Fresh lines of one block for a file written from scratch."""
    lines = []
    for power, value in zip(POWERS, coefficients):
        description = f"{label}, coeff of x^{power}" if power == 2 else f"coeff of x^{power}"
        lines.append(f"{format_number(value):>24}   {prefix}({power}) - {description}\n")
    return lines
