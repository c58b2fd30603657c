"""Complete copies of the OpenFAST decks kept in tests/data (IEA-15MW, IEA-22MW, openfast_toolbox's NREL 5MW).

To keep the repository small only a few of some decks' airfoil polar files are stored (the IEA-15MW's and the
IEA-22MW's are all there: tests/data/iea15/README.md, tests/data/iea22/README.md). :func:`deck_copy` copies a
deck's folder tree into a temporary folder and gives every airfoil file that the AeroDyn files name but that is not
stored the contents of the stored polar nearest to it in the AFNames list. Every other file is the repository's own,
unchanged. Results that depend on filled-in polars are therefore not the reference turbine's; tests on such copies
check how the decks are read, refused and run, not aerodynamic values.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from bladefem.formats._labels import Labels

DATA = Path(__file__).resolve().parent / "data"


def airfoil_names(aerodyn: Path) -> list[Path]:
    """The NumAFfiles airfoil files of an AeroDyn primary file, resolved against its folder."""
    labels = Labels.read(aerodyn)
    count, number, names = labels.int("NumAFfiles"), labels.line("AFNames"), []
    while len(names) < count:
        words = labels.text.lines[number - 1].split()
        if words and not words[0].startswith("!"):
            names.append((aerodyn.parent / words[0].strip("\"'")).resolve())
        number += 1
    return names


def deck_copy(tree: str, tmp_path: Path) -> Path:
    """A copy of tests/data/``tree`` under ``tmp_path`` with every airfoil file its AeroDyn files name."""
    target = tmp_path / tree
    shutil.copytree(DATA / tree, target)
    for aerodyn in [*target.rglob("*AeroDyn15.dat"), *target.rglob("AeroDyn.dat")]:
        names = airfoil_names(aerodyn)
        stored = [i for i, name in enumerate(names) if name.is_file()]
        for i, name in enumerate(names):
            if not name.is_file():
                nearest = min(stored, key=lambda j: abs(j - i))
                name.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(names[nearest], name)
    return target
