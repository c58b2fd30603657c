"""The tower part of the inspection report: model summary, frequency table, mode pictures with the top mass, the
rotor-speed chart (1P and blade-passing bands, soft-stiff classification) and ElastoDyn tower coefficients."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from .models.tower_campbell import tower_campbell
from .plots.labels import mode_labels
from .plots.tower_campbell import save_tower_campbell_plot
from .report import Block, Heading, Image, Paragraph, Table, g, picture_blocks
from .sections.tower import Tower

__all__ = ["tower_blocks"]


def tower_summary_blocks(tower: Tower) -> list[Block]:
    top = tower.top_mass
    supports = tower.supports
    held = [name for name, present in (("tension wires", bool(supports.wires)),
                                       ("foundation", supports.foundation is not None),
                                       ("floating platform", supports.platform is not None),
                                       ("soil springs", supports.soil is not None)) if present]
    rows = [("flexible height", g(tower.height), "m"), ("base height", g(tower.base_height), "m"),
            ("distributed mass", g(tower.sections.mass_moments()[0], 6), "kg"),
            ("top mass", g(top.mass if top is not None else 0.0, 6), "kg"),
            ("gravity", g(tower.gravity), "m/s^2"), ("base", ", ".join(held) or "clamped", ""),
            ("section stations", str(tower.sections.stations), "")]
    if top is not None and top.mass > 0:
        rows.insert(4, ("top-mass centre (up, side-side, fore-aft)", ", ".join(g(c, 4) for c in top.offset), "m"))
    blocks: list[Block] = [
        Heading("Model"),
        Paragraph(f"Input: {tower.sections.source or 'built in code'}. Model: Euler-Bernoulli beam finite elements "
                  "in fore-aft and side-side bending with the top mass as a rigid body, gravity (axial load and "
                  "the top mass's pendulum effect) and the supports listed."),
        Table(("quantity", "value", "unit"), rows, "lrl")]
    if tower.notes:
        blocks.append(Paragraph("Notes: " + "; ".join(tower.notes) + "."))
    return blocks


def tower_frequency_blocks(result) -> list[Block]:
    rows = []
    for number, (mode, label) in enumerate(zip(result.modes, mode_labels(result.modes)), 1):
        e = mode.energy_fractions
        rows.append((str(number), f"{mode.frequency_hz:.4f}", label, f"{e['fore-aft']:.2f}",
                     f"{e['side-side']:.2f}", f"{e['torsion']:.2f}", f"{mode.residual:.1e}"))
    return [Heading("Natural frequencies"),
            Table(("mode", "frequency (Hz)", "kind", "fore-aft share", "side-side share", "torsion share",
                   "residual"), rows, "rrlrrrr"),
            Paragraph("Shares are the fractions of kinetic energy in each motion; the residual is the normwise "
                      "backward error of the eigenpair.")]


def coefficient_blocks(tower: Tower, elements: int | None) -> list[Block]:
    from .models.tower_fit import tower_coefficients

    try:
        fitted = tower_coefficients(tower, elements=elements)
    except LookupError as error:
        return [Heading("ElastoDyn tower mode-shape coefficients"), Paragraph(f"Not available: {error}.")]
    rows = [(fit.label, *(f"{c:.6g}" for c in fit.fit.coefficients), f"{fit.fit.rms_error:.1e}",
             f"{fit.fe_frequency_hz:.4f}", f"{fit.elastodyn_frequency_hz:.4f}") for fit in fitted.fits.values()]
    blocks: list[Block] = [
        Heading("ElastoDyn tower mode-shape coefficients"),
        Paragraph(f"Polynomials sum c_i x^i (i = 2..6, sum c_i = 1) fitted to the finite-element shapes (rigid base "
                  f"motion removed); 'ElastoDyn' is the frequency ElastoDyn derives from the polynomial with "
                  f"{fitted.nodes} nodes and the top mass as a point mass."),
        Table(("mode", "x^2", "x^3", "x^4", "x^5", "x^6", "RMS error", "FE (Hz)", "ElastoDyn (Hz)"), rows,
              "lrrrrrrrr")]
    if fitted.warnings:
        blocks.append(Paragraph("Warnings: " + "; ".join(fitted.warnings) + "."))
    return blocks


def tower_blocks(tower: Tower, directory: Path, sweep_rpm: Sequence[float], n_modes: int, elements: int | None,
                 pictures: bool, operating_rpm: tuple[float, float] | None,
                 blades: int) -> tuple[list[Block], list[Path]]:
    """The report's blocks for a tower and the images written into ``directory``."""
    chart = tower_campbell(tower, sweep_rpm, n_modes, elements, operating_rpm, blades)
    images = [directory / "campbell.png"]
    save_tower_campbell_plot(chart, images[0])
    blocks: list[Block] = [Heading(f"{tower.name}: modal report", 1), *tower_summary_blocks(tower),
                           *tower_frequency_blocks(chart.modes)]
    blocks += picture_blocks(tower, chart.modes, directory, n_modes, pictures, images)
    low, high = chart.operating_rpm
    blocks += [Heading("Tower frequencies and the rotor's excitation bands"),
               Image("campbell.png", f"Tower modes against rotor speed with the 1P and {blades}P bands over the "
                                     f"operating range {low:g}-{high:g} rpm (lighter: the {chart.margin:.0%} "
                                     "margin)."),
               Paragraph(f"Design: {chart.statement()}."), *coefficient_blocks(tower, elements)]
    return blocks, images
