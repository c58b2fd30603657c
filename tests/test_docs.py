"""User documents cite the papers by what they are and use no project-internal words: no 'seed paper 002', no
'000_...' file names, no issue numbers, no names of the people who wrote a module, no pointer to a reference
folder outside the repository; every relative link points to a file that exists."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")), *sorted((ROOT / "cases").rglob("README.md")),
             ROOT / "bladefem" / "data" / "README.md"]
EXAMPLES = sorted((ROOT / "examples").glob("*.py"))
INTERNAL = [
    (r"\bseed(?![-_]comparison)\b", "'seed' for a paper"),
    (r"\b00\d_", "a paper's internal file name"),
    (r"\bissues? \d+\b|\(issue\b", "an issue number"),
    (r"\bengineer'?s?\b", "who wrote a module"),
    (r"shared/reference|reference folder|\breference/nrel5mw", "a folder outside the repository"),
]


def user_text(path: Path) -> str:
    """A document's text, or an example's docstring (what its reader sees first; the documents it writes are
    checked as documents)."""
    if path.suffix != ".py":
        return path.read_text()
    return ast.get_docstring(ast.parse(path.read_text())) or ""


@pytest.mark.parametrize("path", DOCUMENTS + EXAMPLES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_project_internal_words(path):
    text = re.sub(r"\bseed: \d+|\bSEED\b", "", user_text(path))      # a random generator's seed is fine
    for pattern, what in INTERNAL:
        found = re.search(pattern, text, flags=re.IGNORECASE)
        assert not found, f"{path.name}: {what}: ...{text[max(0, found.start() - 40):found.end() + 40]}..."


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_exist(path):
    for target in re.findall(r"\]\(([^)#\s]+)(?:#[^)]*)?\)", path.read_text()):
        if "://" not in target:
            assert (path.parent / target).exists(), f"{path.name}: {target}"


def test_the_papers_are_cited_by_what_they_are():
    readme = (ROOT / "README.md").read_text()
    references = " ".join(readme[readme.index("## References"):].split())
    assert "Hamilton's principle" in references and "Kane's method" in references
    assert "NREL/TP-500-38060" in references
