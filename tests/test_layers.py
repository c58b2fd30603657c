"""The layers import downward only: file formats know nothing of models, builders nothing of the command line,
plots or written outputs (docs/formats.md, the README's layout)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "bladefem"
#: what each layer may import from bladefem (top-level package names)
ALLOWED = {
    "formats": {"errors", "files", "limits", "formats", "sections"},
    "builders": {"errors", "files", "limits", "formats", "sections", "elements", "assembly", "modal", "models", "aero",
                 "builders"},
    "sections": {"errors", "files", "limits", "sections"},
}


def bladefem_imports(path: Path) -> set[str]:
    """The bladefem top-level packages a module imports (absolute or relative, at any depth of the file)."""
    here = path.relative_to(PACKAGE.parent).with_suffix("").parts[:-1]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = here[: len(here) - node.level + 1]
                parts = [*base, *(node.module.split(".") if node.module else [])]
            else:
                parts = (node.module or "").split(".")
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.Import):
            parts, names = None, [alias.name for alias in node.names]
        else:
            continue
        if parts is None:
            found |= {name.split(".")[1] for name in names if name.startswith("bladefem.") and "." in name}
        elif parts and parts[0] == "bladefem":
            found |= {parts[1]} if len(parts) > 1 else set(names)
    return found


@pytest.mark.parametrize("layer", sorted(ALLOWED))
def test_a_layer_imports_only_the_layers_below(layer):
    wrong = {str(path.relative_to(PACKAGE)): sorted(bladefem_imports(path) - ALLOWED[layer])
             for path in sorted((PACKAGE / layer).rglob("*.py"))}
    assert not {name: packages for name, packages in wrong.items() if packages}


def test_the_import_reader_sees_relative_and_absolute_imports(tmp_path):
    assert bladefem_imports(PACKAGE / "formats" / "windio.py") >= {"errors", "formats"}
    assert "models" in bladefem_imports(PACKAGE / "builders" / "turbine_deck.py")
