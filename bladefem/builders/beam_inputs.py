"""Blades from the six-by-six beam formats on the command line: BeamDyn primary or blade files, HAWC2 ``.st`` files
(with ``--htc`` for the twist) and ``.htc`` files (the blade body's st file and c2_def). Parsing is
:mod:`bladefem.formats`, the mapping :mod:`bladefem.builders`; this module finds the companion files.
"""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from ..sections import Blade

#: Suffixes of sibling files searched for the BeamDyn primary file that names a blade file
PRIMARY_SUFFIXES = (".dat", ".inp", ".ipt", ".txt")


def beamdyn_primary_of(blade_path: Path) -> Path | None:
    """The BeamDyn primary file beside ``blade_path`` whose BldFile names it, or None."""
    from ..formats.beamdyn import read_beamdyn_primary
    for candidate in sorted(blade_path.parent.iterdir()):
        if candidate == blade_path or candidate.suffix.lower() not in PRIMARY_SUFFIXES or not candidate.is_file():
            continue
        try:
            head = candidate.read_text(errors="replace")[:20000]
        except OSError:
            continue
        if "kp_total" not in head or blade_path.name not in head:
            continue
        try:
            primary = read_beamdyn_primary(candidate)
        except InputError:
            continue
        if primary.blade_path().resolve() == blade_path.resolve():
            return candidate
    return None


def beamdyn_blade(kind: str, path: Path, hub_radius: float, precone: float, sections: str = "full",
                  axis: str = "curved") -> Blade:
    from ..builders.beamdyn import blade_from_beamdyn
    from ..formats.beamdyn import read_beamdyn_blade, read_beamdyn_primary
    primary_path = path if kind == "beamdyn-primary" else beamdyn_primary_of(path)
    if primary_path is None:
        raise InputError("a BeamDyn blade file needs its primary file (key points: length, twist); none beside it "
                         "names it in BldFile: give the primary file as INPUT", file=str(path), field="BldFile")
    primary = read_beamdyn_primary(primary_path)
    blade_file = primary.blade_path()
    if not blade_file.is_file():
        raise InputError(f"blade file '{primary.blade_file}' not found", file=str(primary_path),
                         line=primary.key_lines.get("BldFile"), field="BldFile")
    return blade_from_beamdyn(primary, read_beamdyn_blade(blade_file), hub_radius=hub_radius, precone=precone,
                              sections=sections, axis=axis)


def _blade_body(bodies, path: Path):
    names = [name for name in bodies.bodies if name.lower().startswith("blade")]
    if not names:
        raise InputError(f"no main_body named blade* with a c2_def (bodies: {', '.join(bodies.bodies) or 'none'})",
                         file=str(path), field="main_body")
    return bodies.bodies[names[0]]


def hawc2_blade(kind: str, path: Path, htc: str | Path | None, hub_radius: float, precone: float,
                sections: str = "full", axis: str = "curved") -> Blade:
    from ..builders.hawc2 import blade_from_hawc2
    from ..formats.hawc2_htc import read_hawc2_bodies
    from ..formats.hawc2_st import read_hawc2_st
    body = None
    if kind == "hawc2-htc":
        if htc is not None:
            raise InputError("--htc does not apply to an .htc INPUT", file=str(path), field="--htc")
        body = _blade_body(read_hawc2_bodies(path), path)
        if not body.st_file:
            raise InputError(f"body '{body.name}' has no timoschenko_input filename", file=str(path), line=body.line,
                             field="filename")
        # HAWC2 resolves file names from the folder it runs in: the htc's folder or the one above it
        tries = [path.parent / body.st_file, path.parent.parent / body.st_file, path.parent / Path(body.st_file).name]
        found = [p for p in tries if p.is_file()]
        if not found:
            raise InputError(f"st file '{body.st_file}' not found beside the htc, one folder up, or by its name "
                             "beside the htc", file=str(path),
                             line=body.line, field="filename")
        st_path = found[0]
        subset = read_hawc2_st(st_path).subset(*body.st_set)
    else:
        st_path = path
        if htc is not None:
            body = _blade_body(read_hawc2_bodies(htc), Path(htc))
        st = read_hawc2_st(path)
        subset = st.subset(*(body.st_set if body is not None else (1, 1)))
    return blade_from_hawc2(subset, body, st_path=str(st_path), hub_radius=hub_radius, precone=precone,
                            sections=sections, axis=axis)
