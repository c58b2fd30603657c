"""ElastoDyn's polynomial mode-shape blocks: five coefficients ``c_2 .. c_6`` of ``phi(x) = sum c_i x^i``.

ElastoDyn normalises each shape to 1 at the tip (``sum c_i = 1``) and refuses a block whose sum is off by more
than 0.001 (a single-precision check). Shipped files round large coefficients to six digits and miss by about that
much (the NREL 5MW tower's TwSSM2Sh adds up to 0.999), so the readers accept up to 0.01 and reject beyond.
"""

from __future__ import annotations

from decimal import ROUND_HALF_EVEN, Decimal

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


#: Decimal places of coefficients written into an existing file.
DECIMALS = 10


def decimal_texts(coefficients: NDArray, decimals: int = DECIMALS) -> list[str]:
    """Coefficients as fixed-point text with ``decimals`` places whose decimal sum is exactly 1: c_2 .. c_5 are
    rounded and c_6 = 1 - (c_2 + ... + c_5) is computed in decimal arithmetic."""
    quantum = Decimal(1).scaleb(-decimals)
    head = [Decimal(repr(float(c))).quantize(quantum, rounding=ROUND_HALF_EVEN) for c in coefficients[:-1]]
    return [f"{value:.{decimals}f}" for value in head + [Decimal(1) - sum(head)]]


def block_values(prefix: str, coefficients: NDArray) -> dict[str, str]:
    """Key -> text of each coefficient for an in-place update (fixed point, decimal sum exactly 1)."""
    return dict(zip(block_keys(prefix), decimal_texts(coefficients)))


def block_lines(prefix: str, coefficients: NDArray, label: str, texts: list[str] | None = None) -> list[str]:
    """Fresh lines of one block for a file written from scratch (exact shortest floats unless ``texts`` given)."""
    texts = texts or [format_number(value) for value in coefficients]
    lines = []
    for power, text in zip(POWERS, texts):
        description = f"{label}, coeff of x^{power}" if power == 2 else f"coeff of x^{power}"
        lines.append(f"{text:>24}   {prefix}({power}) - {description}\n")
    return lines
