"""Names of the turbine's modes from the participation of their coordinates.

A mode's participation in coordinate ``i`` is its share of the mode's energy, ``e_i = |z_i|^2 (K_ii + w^2 M_ii)``
normalised to sum 1 (strain plus kinetic energy of that coordinate alone; ``K`` the elastic and spring stiffness,
``M`` the mass matrix, both in the coordinates of the analysis). Shares are summed over the coordinates of one
family — a tower mode, the nacelle yaw, the drivetrain (generator azimuth and drivetrain twist), a blade mode in
collective or asymmetric (cosine + sine) multi-blade form, or one blade's mode — and the family with the largest
share names the mode, each family naming at most as many oscillating modes as it has coordinates
(:func:`name_modes`). An asymmetric blade mode is told apart by the nacelle motion it drives, as in Jonkman et
al. (2009), Table 9-1: at rest, a flap pattern along cos(psi) (vertical) tilts the rotor, "(pitch)", one along
sin(psi) yaws it, "(yaw)"; an edge pattern along cos(psi) pushes the hub sideways, "(yaw)", one along sin(psi)
up and down, "(pitch)". On a spinning rotor the pair is told apart by its whirl, from the phase between the cosine
and sine coordinates (forward: the pattern turns with the rotor). Drivetrain modes are counted ('1st', '2nd');
other repeated names get a count, '(2)'. A mode whose largest share belongs to a family that already names another
mode (its room used up) adds that family: '1st blade collective edge / drivetrain'. A non-oscillating mode of an
elastic coordinate (two real roots: an overdamped pair, e.g. a blade flap mode under strong aerodynamic damping) is
named '(overdamped, slow root)' and '(overdamped, fast root)', not counted as an oscillation; a lone real root
(a damper without a spring) '(decaying)'.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

ORDINALS = {"1": "1st", "2": "2nd", "3": "3rd"}
TOWER_KINDS = {"fa": "fore-aft", "ss": "side-side"}
BLADE_KINDS = {"flap": "flap", "edge": "edge"}


def family(coordinate: str) -> str:
    """The family a coordinate belongs to: 'tower_fa1', 'yaw', 'drivetrain', 'collective_flap1',
    'asymmetric_flap1', 'blade2_edge1'."""
    kind, _, mode = coordinate.partition("_")
    if kind in ("cosine", "sine"):
        return f"asymmetric_{mode}"
    if coordinate in ("generator_azimuth", "drivetrain"):
        return "drivetrain"
    return coordinate


def family_name(name: str, rigid: bool) -> str:
    """Readable name of a family: '1st tower fore-aft', 'nacelle yaw', '1st drivetrain torsion', '1st blade
    collective flap', '1st blade asymmetric flap', '1st flap of blade 2'; rigid-body modes 'rigid rotor rotation',
    'rigid nacelle yaw'."""
    kind, _, mode = name.partition("_")
    if rigid:
        return {"yaw": "rigid nacelle yaw", "drivetrain": "rigid rotor rotation"}.get(name, f"rigid {name}")
    if kind == "tower":
        return f"{ORDINALS[mode[-1]]} tower {TOWER_KINDS[mode[:2]]}"
    if kind in ("collective", "asymmetric"):
        return f"{ORDINALS[mode[-1]]} blade {kind} {BLADE_KINDS[mode[:4]]}"
    if kind.startswith("blade"):
        return f"{ORDINALS[mode[-1]]} {BLADE_KINDS[mode[:4]]} of blade {kind[5:]}"
    return {"yaw": "nacelle yaw", "drivetrain": "1st drivetrain torsion"}.get(name, name)


def participation(vector: NDArray, stiffness: NDArray, mass: NDArray, omega: float) -> NDArray:
    """Energy shares (sum 1) of a mode's coordinates ``vector`` (complex, (m,)) with the diagonals of the
    stiffness and mass matrices and the mode's natural frequency (rad/s)."""
    energy = np.abs(vector) ** 2 * (stiffness + omega**2 * mass)
    total = energy.sum()
    return energy / total if total > 0 else np.full(len(vector), 1.0 / len(vector))


def asymmetric_label(vector: NDArray, coordinates: list[str], mode: str, spinning: bool) -> str:
    """'(pitch)' / '(yaw)' at rest, '(forward whirl)' / '(backward whirl)' when spinning, for the asymmetric
    blade mode ``mode`` (e.g. 'flap1') with the complex coordinates ``vector``."""
    cosine = vector[coordinates.index(f"cosine_{mode}")]
    sine = vector[coordinates.index(f"sine_{mode}")]
    if not spinning:
        vertical = abs(cosine) >= abs(sine)
        return "(pitch)" if vertical == mode.startswith("flap") else "(yaw)"
    # q_k = ... + Re(c e^{iwt}) cos psi_k + Re(s e^{iwt}) sin psi_k: with s = -i c the pattern's crest sits at
    # psi = w t and turns with the rotor (forward); with s = +i c against it (backward)
    return "(forward whirl)" if (np.conj(cosine) * sine).imag < 0 else "(backward whirl)"


def overdamped_name(name: str, root: int, roots: int) -> str:
    """Name of the ``root``-th (by increasing rate) of ``roots`` real roots of the family ``name``."""
    if roots < 2:
        return f"{name} (decaying)"            # one real root: e.g. a damper without a spring
    which = {1: "slow root", 2: "fast root"}.get(root, f"root {root}") if roots == 2 else f"root {root}"
    return f"{name} (overdamped, {which})"


def name_modes(vectors: list[NDArray], shares: list[NDArray], coordinates: list[str], rigid: list[bool],
               spinning: bool, oscillating: list[bool] | None = None) -> list[str]:
    """A name for each mode (in the given order) from its participation (see the module's description).

    A family holds as many oscillating modes as it has coordinates: the (mode, family) pairs are taken in
    decreasing share, a pair only while the mode is unnamed and its family has room. So the drivetrain twist names
    one mode, the one it dominates most (0.62 Hz with the generator locked), and the other mode it shares (the
    blades' collective edge against the hub) goes to its next family. Modes that do not oscillate (real
    eigenvalues: rigid-body motions, an undamped-spring coordinate's damper decay) are named by their dominant
    family and use up its room, one coordinate per two of them; the drivetrain's is the 'rotor speed' (a free rotor
    settling under the generator's torque law and the aerodynamic torque)."""
    oscillating = [True] * len(vectors) if oscillating is None else oscillating
    families = [family(c) for c in coordinates]
    unique = list(dict.fromkeys(families))
    room = {u: families.count(u) for u in unique}
    totals = [np.array([share[[f == u for f in families]].sum() for u in unique]) for share in shares]
    chosen: list[str | None] = [None] * len(vectors)
    still = [0] * len(unique)
    for i, total in enumerate(totals):
        if not oscillating[i]:
            chosen[i] = unique[int(np.argmax(total))]
            still[unique.index(chosen[i])] += 1
    for u, count in zip(unique, still):
        room[u] -= (count + 1) // 2
    pairs = sorted(((total[j], i, unique[j]) for i, total in enumerate(totals) if oscillating[i]
                    for j in range(len(unique))), key=lambda pair: -pair[0])
    for _, i, u in pairs:
        if chosen[i] is None and room[u] > 0:
            chosen[i], room[u] = u, room[u] - 1
    names: list[str] = []
    used: dict[str, int] = {}
    overdamped = [family_name(chosen[i] or unique[int(np.argmax(total))], False)
                  for i, total in enumerate(totals) if not oscillating[i] and not rigid[i]]
    roots: dict[str, int] = {}
    for i, (vector, total) in enumerate(zip(vectors, totals)):
        dominant = chosen[i] or unique[int(np.argmax(total))]
        name = family_name(dominant, rigid[i])
        if rigid[i]:
            names.append(name)
            continue
        if dominant == "drivetrain" and not oscillating[i]:
            names.append("rotor speed")        # the free rotor's speed settling under the generator torque law
            continue
        if not oscillating[i]:
            # two real roots of one coordinate: an overdamped pair, not an oscillation; named once each
            roots[name] = roots.get(name, 0) + 1
            names.append(overdamped_name(name, roots[name], overdamped.count(name)))
            continue
        if dominant.startswith("asymmetric_"):
            label = asymmetric_label(vector, coordinates, dominant.split("_", 1)[1], spinning)
            other = {"(pitch)": "(yaw)", "(yaw)": "(pitch)", "(forward whirl)": "(backward whirl)",
                     "(backward whirl)": "(forward whirl)"}[label]
            if f"{name} {label}" in used and f"{name} {other}" not in used:
                # the family's two oscillations are one of each: a degenerate pair (rotor on a rigid hub), or
                # a pair damped so strongly (aerodynamic flap damping near critical) that its whirl is ill-defined
                label = other
            name += " " + label
        top = unique[int(np.argmax(total))]
        if top != dominant and total[unique.index(top)] > 0.5:
            # the family that dominates this mode already names another one: say that it dominates here too
            name += " / " + ("drivetrain" if top == "drivetrain" else family_name(top, False))
        used[name] = used.get(name, 0) + 1
        if dominant == "drivetrain":
            names.append(f"{ORDINALS.get(str(used[name]), str(used[name]) + 'th')} drivetrain torsion")
        else:
            names.append(name if used[name] == 1 else f"{name} ({used[name]})")
    return names
