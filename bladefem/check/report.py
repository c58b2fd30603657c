"""Outputs of ``bladefem check``: a table for the terminal, JUnit XML for CI systems, and JSON for scripts."""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from typing import Any

from .evaluate import Outcome


def _number(value: float) -> str:
    return f"{value:.4g}" if math.isfinite(value) else str(value)


def table(outcomes: Sequence[Outcome]) -> str:
    """One line per outcome: requirement, check, measured value, limit, margin, PASS/FAIL, and the detail."""
    rows = [("requirement", "check", "measured", "limit", "margin", "result")]
    rows += [(o.requirement, o.check, f"{_number(o.measured)} {o.unit}", o.limit, f"{_number(o.margin)} {o.unit}",
              "PASS" if o.passed else "FAIL") for o in outcomes]
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip() for row in rows]
    lines.insert(1, "  ".join("-" * width for width in widths))
    failed = sum(not o.passed for o in outcomes)
    details = [f"  {o.requirement} / {o.check}: {o.detail}" for o in outcomes if o.detail]
    summary = f"{len(outcomes) - failed} passed, {failed} failed"
    return "\n".join(lines + ["", "details:", *details, "", summary])


def junit_xml(outcomes: Sequence[Outcome], suite: str = "bladefem check") -> bytes:
    """JUnit XML: one testsuite, one testcase per outcome (classname = requirement), a ``failure`` element with the
    numbers for each failed one."""
    failures = sum(not o.passed for o in outcomes)
    root = ET.Element("testsuites", name=suite, tests=str(len(outcomes)), failures=str(failures), errors="0")
    node = ET.SubElement(root, "testsuite", name=suite, tests=str(len(outcomes)), failures=str(failures),
                         errors="0", skipped="0")
    for o in outcomes:
        case = ET.SubElement(node, "testcase", classname=o.requirement, name=o.check, time="0")
        message = (f"measured {_number(o.measured)} {o.unit}, limit {o.limit}, margin {_number(o.margin)} "
                   f"{o.unit}: {o.detail}")
        if not o.passed:
            ET.SubElement(case, "failure", message=message, type="RequirementNotMet").text = message
        else:
            ET.SubElement(case, "system-out").text = message
    ET.indent(root)
    return ET.tostring(root, encoding="utf-8", xml_declaration=True) + b"\n"


def to_json(outcomes: Sequence[Outcome]) -> dict[str, Any]:
    """``{"passed": bool, "outcomes": [{"requirement", "check", "passed", "measured", "unit", "limit", "margin",
    "detail"}]}``; non-finite numbers become null."""
    def finite(value: float) -> float | None:
        return value if math.isfinite(value) else None
    return {"passed": all(o.passed for o in outcomes),
            "outcomes": [{"requirement": o.requirement, "check": o.check, "passed": o.passed,
                          "measured": finite(o.measured), "unit": o.unit, "limit": o.limit,
                          "margin": finite(o.margin), "detail": o.detail} for o in outcomes]}


def dumps(outcomes: Sequence[Outcome]) -> str:
    return json.dumps(to_json(outcomes), indent=2) + "\n"
