"""An inspection report of a blade or a tower: provenance (software version, date, input files and their SHA-256),
model summary, frequency table, mode pictures, Campbell diagram (blade) or rotor-speed chart (tower) and ElastoDyn
mode-shape coefficients, written as Markdown and HTML with PNG images beside them.

The report is a list of blocks (heading, paragraph, table, image) rendered twice, so the two formats always say the
same thing. Images need matplotlib (diagrams) and pyvista (modes, optional: left out with a note without it).
Tower content: :mod:`bladefem.report_tower`.
"""

from __future__ import annotations

import datetime
import hashlib
import html
import math
import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .assembly import BladeMatrices
from .files import write_atomic
from .modal import (
    CampbellResult,
    ModalResult,
    blade_matrices,
    campbell_sweep,
    solve_modes,
)
from .plots.campbell import crossings, family_labels, save_campbell_plot
from .plots.labels import mode_labels
from .sections import Blade

__all__ = ["Block", "Heading", "Image", "Paragraph", "Report", "Table", "html_document", "markdown",
           "progress_bar", "provenance_blocks", "sweep", "write_report"]

Progress = Callable[[Iterable[Any]], Iterable[Any]]


# -- sweeps with a progress bar -----------------------------------------------------------------------------------

def progress_bar(description: str, quiet: bool = False) -> Progress:
    """A wrapper showing a progress bar (rich, on stderr) while iterating, or nothing when ``quiet`` or when stderr
    is not a terminal."""
    if quiet or not sys.stderr.isatty():
        return lambda items: items
    from rich.console import Console
    from rich.progress import track
    return lambda items: track(items, description=description, console=Console(stderr=True), transient=True)


def sweep(matrices: BladeMatrices, rpm: Sequence[float], n_modes: int, notes: tuple[str, ...] = (),
          progress: Progress | None = None) -> CampbellResult:
    """:func:`bladefem.modal.campbell_sweep` with an optional progress bar over the rotor speeds (rpm)."""
    return campbell_sweep(matrices, rpm, n_modes, notes, progress)


# -- blocks -------------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Heading:
    text: str
    level: int = 2


@dataclass(frozen=True)
class Paragraph:
    text: str


@dataclass(frozen=True)
class Table:
    header: tuple[str, ...]
    rows: list[tuple[str, ...]]
    align: str = ""          # one letter per column, 'l' or 'r' (default: first left, others right)


@dataclass(frozen=True)
class Image:
    file: str
    caption: str


Block = Heading | Paragraph | Table | Image


def markdown(blocks: Sequence[Block]) -> str:
    lines: list[str] = []
    for block in blocks:
        if isinstance(block, Heading):
            lines += ["#" * block.level + " " + block.text, ""]
        elif isinstance(block, Paragraph):
            lines += [block.text, ""]
        elif isinstance(block, Table):
            align = block.align or "l" + "r" * (len(block.header) - 1)
            lines.append("| " + " | ".join(block.header) + " |")
            lines.append("|" + "|".join("---:" if a == "r" else ":---" for a in align) + "|")
            lines += ["| " + " | ".join(row) + " |" for row in block.rows]
            lines.append("")
        else:
            lines += [f"![{block.caption}]({block.file})", "", f"*{block.caption}*", ""]
    return "\n".join(lines)


IMAGE_TYPES = {".png": "image/png", ".svg": "image/svg+xml", ".jpg": "image/jpeg", ".gif": "image/gif"}


def embedded(file: str, directory: Path | None) -> str:
    """A data URI with the picture's bytes (base64), or the relative path when there is no folder to read it from."""
    if directory is None:
        return file
    import base64
    data = base64.b64encode((directory / file).read_bytes()).decode("ascii")
    return f"data:{IMAGE_TYPES.get(Path(file).suffix.lower(), 'application/octet-stream')};base64,{data}"


STYLE = ("body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}"
         "table{border-collapse:collapse;margin:1em 0}td,th{padding:.2em .7em;border-bottom:1px solid #ccc}"
         "th{border-bottom:2px solid #444}td.r,th.r{text-align:right}figure{margin:1.5em 0}img{max-width:100%}"
         "figcaption{font-size:90%;color:#333}")


def html_document(title: str, blocks: Sequence[Block], directory: Path | None = None) -> str:
    """The report as one HTML page; its pictures (files in ``directory``) are embedded as data URIs, so the page
    alone carries them."""
    e = html.escape
    body: list[str] = []
    for block in blocks:
        if isinstance(block, Heading):
            body.append(f"<h{block.level}>{e(block.text)}</h{block.level}>")
        elif isinstance(block, Paragraph):
            body.append(f"<p>{e(block.text)}</p>")
        elif isinstance(block, Table):
            align = block.align or "l" + "r" * (len(block.header) - 1)
            head = "".join(f'<th class="{a}">{e(h)}</th>' for h, a in zip(block.header, align))
            rows = "".join("<tr>" + "".join(f'<td class="{a}">{e(c)}</td>' for c, a in zip(row, align)) + "</tr>"
                           for row in block.rows)
            body.append(f"<table><tr>{head}</tr>{rows}</table>")
        else:
            body.append(f'<figure><img src="{e(embedded(block.file, directory))}" alt="{e(block.caption)}">'
                        f"<figcaption>{e(block.caption)}</figcaption></figure>")
    return (f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>{e(title)}</title>'
            f"<style>{STYLE}</style></head><body>\n" + "\n".join(body) + "\n</body></html>\n")


# -- content ------------------------------------------------------------------------------------------------------

def g(value: float, digits: int = 5) -> str:
    return f"{value:.{digits}g}"


def mass_rows(blade: Blade) -> list[tuple[str, ...]]:
    """Mass and first and second mass moments of the distributed blade about the root and about the rotor apex
    (along the pitch axis; exact integrals of the piecewise-linear mass), plus the tip mass on its own."""
    rows = []
    for where, offset in (("blade root", 0.0), ("rotor apex", blade.hub_radius)):
        _, first, second = blade.sections.mass_moments(offset)
        rows += [(f"first mass moment about the {where}", g(first, 6), "kg m"),
                 (f"second mass moment about the {where}", g(second, 6), "kg m^2")]
    mass = blade.sections.mass_moments()[0]
    rows.insert(0, ("distributed mass", g(mass, 6), "kg"))
    if blade.tip_mass is not None and blade.tip_mass.mass > 0:
        rows.append(("tip mass (not in the moments above)", g(blade.tip_mass.mass, 6), "kg"))
    return rows


def case_provenance(source: str) -> str | None:
    """The ``source`` entry of a bladefem case file (where its section data came from), if it has one."""
    path = Path(source)
    if path.suffix.lower() not in (".yaml", ".yml") or not path.is_file():
        return None
    import yaml
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError):
        return None
    return str(data["source"]) if isinstance(data, dict) and data.get("source") else None


def file_hash(path: str | Path) -> str:
    """SHA-256 of a file's bytes, hex."""
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for chunk in iter(lambda: stream.read(1 << 16), b""):
            digest.update(chunk)
    return digest.hexdigest()


def provenance_blocks(inputs: Sequence[str | Path], now: datetime.datetime | None = None) -> list[Block]:
    """Who wrote the report and from what: bladefem's version, the date (UTC) and every input file with its
    SHA-256, so that a report can be traced to the exact files it was computed from."""
    from . import __version__

    moment = (now or datetime.datetime.now(datetime.timezone.utc)).strftime("%Y-%m-%d %H:%M:%S UTC")
    rows = [(str(path), file_hash(path)) for path in inputs if Path(path).is_file()]
    blocks: list[Block] = [Paragraph(f"Written by bladefem {__version__} on {moment}.")]
    if rows:
        blocks.append(Table(("input file", "SHA-256"), rows, "ll"))
    else:
        blocks.append(Paragraph("Input: built in code (no input file)."))
    return blocks


def report_inputs(sections_source: str, inputs: Sequence[str | Path] | None) -> list[str | Path]:
    """The files to list: those given, else the section table's source if it is a file."""
    if inputs:
        return list(inputs)
    return [sections_source] if sections_source and Path(sections_source).is_file() else []


def summary_blocks(blade: Blade, matrices: BladeMatrices) -> list[Block]:
    sections = blade.sections
    geometry = [("flexible length", g(blade.length), "m"), ("hub radius", g(blade.hub_radius), "m"),
                ("tip radius", g(blade.tip_radius), "m"), ("precone", g(math.degrees(blade.precone)), "deg"),
                ("pitch", g(math.degrees(blade.pitch)), "deg"), ("root", blade.root, ""),
                ("section stations", str(sections.stations), "")]
    origin = case_provenance(sections.source)
    provenance = (f"Input: {sections.source or 'built in code'}"
                  + (f" (section data from {origin})" if origin else "")
                  + ". Model: Euler-Bernoulli beam finite elements (Hermite cubic bending, coupled flap and edge "
                  f"through twist and pitch), {matrices.free.size} free degrees of freedom; frequencies without "
                  "Coriolis coupling, linearised about the undeflected blade.")
    blocks: list[Block] = [Heading("Model"), Paragraph(provenance),
                           Table(("quantity", "value", "unit"), geometry + mass_rows(blade), "lrl")]
    if blade.notes:
        blocks.append(Paragraph("Notes: " + "; ".join(blade.notes) + "."))
    return blocks


def frequency_blocks(result: ModalResult) -> list[Block]:
    rows = []
    for number, (mode, label) in enumerate(zip(result.modes, mode_labels(result.modes)), 1):
        e = mode.energy_fractions
        rows.append((str(number), f"{mode.frequency_hz:.4f}", label, f"{e['flap']:.2f}", f"{e['edge']:.2f}",
                     f"{e['torsion']:.2f}", f"{mode.residual:.1e}"))
    return [Heading(f"Natural frequencies at {result.rotor_speed_rpm:g} rpm"),
            Table(("mode", "frequency (Hz)", "kind", "flap share", "edge share", "torsion share", "residual"),
                  rows, "rrlrrrr"),
            Paragraph("Shares are the fractions of kinetic energy in each field; the residual is "
                      "||K x - omega^2 M x|| / ||K x||.")]


#: crossings closer than this to the operating speed (relative) are remarked on
NEAR_OPERATING = 0.1


def crossing_blocks(result: CampbellResult, operating_rpm: float | None) -> list[Block]:
    """The table of crossings with the nP lines, and a remark on those within :data:`NEAR_OPERATING` of the
    operating speed (rpm)."""
    labels = family_labels(result)
    rows = [(labels[c.family], f"{c.harmonic}P", f"{c.rpm:.2f}", f"{c.frequency_hz:.4f}",
             "" if operating_rpm is None else f"{c.rpm - operating_rpm:+.2f}") for c in crossings(result)]
    if not rows:
        return [Paragraph("No family crosses the 1P, 3P, 6P or 9P lines in the swept range.")]
    blocks: list[Block] = [Table(("family", "excitation", "rotor speed (rpm)", "frequency (Hz)",
                                  "from operating (rpm)"), rows, "llrrr")]
    if operating_rpm:
        near = [c for c in crossings(result) if abs(c.rpm - operating_rpm) <= NEAR_OPERATING * operating_rpm]
        blocks.append(Paragraph(
            "Near the operating speed: " + "; ".join(
                f"the {labels[c.family]} meets {c.harmonic}P at {c.rpm:.2f} rpm, {abs(c.rpm - operating_rpm):.2f} "
                f"rpm {'below' if c.rpm < operating_rpm else 'above'} the operating {operating_rpm:g} rpm"
                for c in near) + "." if near else
            f"No crossing lies within {NEAR_OPERATING:.0%} of the operating speed {operating_rpm:g} rpm."))
    return blocks


def elastodyn_blocks(blade: Blade, rpm: float, elements: int | None) -> list[Block]:
    """ElastoDyn polynomial coefficients of the blade modes (flap 1, flap 2, edge 1) fitted to the FE shapes."""
    try:
        from .modal.elastodyn_fit import blade_coefficients
    except ImportError:                      # the fit module is optional: the report stays complete without it
        return []
    try:
        fitted = blade_coefficients(blade, rpm, elements=elements)
    except LookupError as error:             # e.g. fewer than two flap modes among those computed
        return [Heading("ElastoDyn mode-shape coefficients"), Paragraph(f"Not available: {error}.")]
    rows = []
    for fit in fitted.fits.values():
        rows.append((fit.label, *(f"{c:.6g}" for c in fit.fit.coefficients), f"{fit.fit.rms_error:.1e}",
                     f"{fit.fe_frequency_hz:.4f}", f"{fit.elastodyn_frequency_hz:.4f}"))
    blocks: list[Block] = [
        Heading("ElastoDyn mode-shape coefficients"),
        Paragraph(f"Polynomials sum c_i x^i (i = 2..6, sum c_i = 1) fitted to the finite-element shapes at {rpm:g} "
                  f"rpm; 'ElastoDyn' is the frequency ElastoDyn derives from the polynomial with {fitted.nodes} "
                  f"nodes. {mass_statement(blade)}"),
        Table(("mode", "x^2", "x^3", "x^4", "x^5", "x^6", "RMS error", "FE (Hz)", "ElastoDyn (Hz)"), rows,
              "lrrrrrrrr")]
    if fitted.warnings:
        blocks.append(Paragraph("Warnings: " + "; ".join(fitted.warnings) + "."))
    return blocks


def mass_statement(blade: Blade) -> str:
    """Which distributed mass the fit used: an ElastoDyn blade file's AdjBlMs (and stiffness factors) are applied
    when read, a case file's mass stands as given; the two give different coefficients."""
    adjusted = next((note for note in blade.notes if "AdjBlMs" in note), None)
    if adjusted:
        return f"The sections are the ElastoDyn blade file's with its factors applied ({adjusted})."
    return ("The sections are used as given (mass factor 1): `bladefem elastodyn` on an ElastoDyn file scales the "
            "mass by its AdjBlMs, so its coefficients and frequencies differ from these.")


def can_render() -> bool:
    try:
        import pyvista  # noqa: F401
    except ImportError:
        return False
    return True


@dataclass(frozen=True)
class Report:
    """Paths written by :func:`write_report`."""

    markdown: Path
    html: Path
    images: tuple[Path, ...] = field(default=())


def write_report(structure: Any, directory: str | Path, rpm: float, sweep_rpm: Sequence[float], n_modes: int = 6,
                 elements: int | None = None, pictures: bool = True, quiet: bool = True,
                 inputs: Sequence[str | Path] | None = None, operating_rpm: tuple[float, float] | None = None,
                 blades: int = 3) -> Report:
    """Compute and write ``report.md`` and ``report.html`` (with ``campbell.png`` and ``modes.png``) for a blade at
    the operating speed ``rpm`` (rpm) with a Campbell sweep over ``sweep_rpm`` (rpm), or for a tower (a
    :class:`~bladefem.sections.tower.Tower`) with its rotor-speed chart over ``sweep_rpm`` and the operating range
    ``operating_rpm`` (rpm; default the swept range) of a rotor of ``blades`` blades. ``inputs``: the input files
    listed with their SHA-256 (default: the section table's source file)."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    if not isinstance(structure, Blade):
        from .report_tower import tower_blocks
        blocks, images = tower_blocks(structure, directory, sweep_rpm, n_modes, elements, pictures, operating_rpm,
                                      blades)
        blocks[1:1] = provenance_blocks(report_inputs(structure.sections.source, inputs))
        return _write(directory, f"{structure.name}: modal report", blocks, images)
    blade = structure
    matrices = blade_matrices(blade, elements, n_modes, max(rpm, *sweep_rpm))
    result = solve_modes(matrices, rpm, n_modes, blade.notes + matrices.notes)
    campbell = sweep(matrices, sweep_rpm, n_modes, blade.notes + matrices.notes, progress_bar("Campbell sweep", quiet))
    operating = rpm if rpm > 0 else None
    images = [directory / "campbell.png"]
    save_campbell_plot(campbell, images[0], title=blade.name, operating_rpm=operating)
    blocks: list[Block] = [Heading(f"{blade.name}: modal report", 1),
                           *provenance_blocks(report_inputs(blade.sections.source, inputs)),
                           *summary_blocks(blade, matrices), *frequency_blocks(result)]
    blocks += picture_blocks(blade, result, directory, n_modes, pictures, images,
                             f" at {rpm:g} rpm")
    blocks += [Heading("Campbell diagram"),
               Image("campbell.png", f"Mode families tracked by MAC over {sweep_rpm[0]:g}-{sweep_rpm[-1]:g} rpm "
                                     "with the 1P, 3P, 6P and 9P excitation lines; circles mark crossings."),
               *crossing_blocks(campbell, operating), *elastodyn_blocks(blade, rpm, elements)]
    return _write(directory, f"{blade.name}: modal report", blocks, images)


def picture_blocks(structure: Any, result: ModalResult, directory: Path, n_modes: int, pictures: bool,
                   images: list[Path], where: str = "") -> list[Block]:
    """The strip of mode pictures (``modes.png``), or a note when pyvista is missing."""
    if not pictures:
        return []
    if not can_render():
        return [Paragraph("Mode pictures need pyvista (pip install 'bladefem[render]').")]
    from .plots.modes3d import FRACTION, caption, drawing, save_mode_strip
    images.append(directory / "modes.png")
    save_mode_strip(structure, result, images[-1], n_modes)
    return [Image("modes.png", f"First {min(n_modes, len(result.modes))} modes{where}: deformed (coloured by "
                               f"displacement magnitude) over undeformed (grey); largest displacement drawn at "
                               f"{FRACTION:.0%} of the length; {caption(drawing(structure))}.")]


def _write(directory: Path, title: str, blocks: list[Block], images: list[Path]) -> Report:
    paths = Report(directory / "report.md", directory / "report.html", tuple(images))
    write_atomic(paths.markdown, markdown(blocks))
    write_atomic(paths.html, html_document(title, blocks, directory))
    return paths
