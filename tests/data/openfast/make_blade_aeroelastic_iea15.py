"""Write, run and extract OpenFAST linearizations of the IEA-15MW BeamDyn blade turning in still air with
quasi-steady aerodynamics (blade_aeroelastic_linearization_iea15.json): the NREL 5MW case of
make_blade_aeroelastic.py for the IEA-15MW.

Not run by the tests (OpenFAST is not needed to use the JSON file). Each case: the IEA-15MW deck of tests/data/iea15
brought to OpenFAST v5.0.0's layouts by ``iea15_rosco/write_decks.py`` (its docstring lists the changes), then:
BeamDyn blades (tests/data/iea15/beamdyn: the six-by-six sections, no structural damping, order_elem ORDER, the
reference axis straightened: key points' kp_xr and kp_yr 0) written by ``beamdyn/make_decks.py``, the hub held
(every ElastoDyn DOF off), RotSpeed the case's rotor speed, pitch 0, no precone (the deck's -4 deg set to 0), Gravity
0, no ServoDyn; AeroDyn without induction (Wake_Mod 0: the relative velocity is the rotation alone, as in still air),
legacy projection (BEM_Mod 1), no unsteady aerodynamics (UA_Mod 0), no tower influence, the blade file's
aerodynamic-centre offsets and cant (BlCrvAC, BlSwpAC, BlCrvAng) 0 with the straightened axis; still air
(CompInflow 0). Linearized once at LIN_TIME = 0 s (CalcSteady False): the blade as BeamDyn's QuasiStaticInit leaves
it under its centrifugal load, before the aerodynamic loads act; blade 1's modes as for the 5MW.

Why straightened: a prebent blade bends back under its centrifugal load (about 1 m at the tip at rated speed), and
BeamDyn linearizes about that deflected state, which couples the edgewise motion with twist (the coned 5MW blade of
make_blade_aeroelastic.py shows how much); a straight blade without precone has no such steady bending, so both
tools linearize about the same (undeflected) blade. ``--prebent`` keeps the files' curved axis and aerodynamic-centre
offsets (``prebent_points``).

Why at 0 s: the aerodynamic loads switch on at 0 s and start a motion; at ``--lin-time 0.02`` (the 5MW's time) the
blade is linearized part way into it, its tip twisted by the airfoils' pitching moment (``tip_twist_rad``: -3.3 deg
at 13.5 rpm), which moves the edge modes' damping (``lin_time_0.02_points``). Still air at pitch 0 has no steady
state near the undeflected blade (the sections at minus their twist carry a large negative lift): the undeflected
blade is the operating point both tools can share.

    python tests/data/openfast/make_blade_aeroelastic_iea15.py OPENFAST_EXECUTABLE RUNS_FOLDER [RPM ...]
        [--order N] [--lin-time T] [--prebent] [--structural] [--no-pitching-moment] [--constant-cm CM]
        [--scale-cm F] [--no-mass-offsets] [--reduce]

``--constant-cm CM``: every airfoil's pitching-moment coefficient set to CM at every angle of attack
(:func:`constant_pitching_moment`; ``constant_cm_points``): the moment then changes with the relative speed alone,
not with the angle of attack.

``--scale-cm F``: every airfoil's Cm multiplied by F (``scaled_cm_points``, with ``cm_factor``): with F = 1 and -1
the damping's parts odd and even in the pitching moment.

``--no-mass-offsets``: the sections' mass centres on the reference axis in the blade file
(:func:`without_mass_offsets`; keys ``no_mass_offsets_*``).

Every point written carries ``rotating_frame_modes`` (:func:`rotating_frame_modes`).

``--reduce``: extract the JSON from the runs already in RUNS_FOLDER (OpenFAST not run).
"""

from __future__ import annotations

import json
import math
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
IEA = ROOT / "tests" / "data" / "iea15"
BEAMDYN = IEA / "beamdyn"
RPMS = (7.56, 11.0, 13.5, 16.0, 18.5)
ORDER = 10
DT, LIN_TIME = "0.001", "0"
FST = "blade.fst"
#: the AeroDyn blade table's columns set to 0 on the straightened blade
OFFSETS = ("BlCrvAC", "BlSwpAC", "BlCrvAng")


def straightened_aerodyn_blade(text: str) -> str:
    """An AeroDyn blade file's text with the columns :data:`OFFSETS` of its node table set to 0."""
    lines = text.splitlines()
    count = int(next(line.split()[0] for line in lines if line.split()[1:2] == ["NumBlNds"]))
    header = next(k for k, line in enumerate(lines) if line.split()[:1] == ["BlSpn"])
    columns = [lines[header].split().index(name) for name in OFFSETS]
    for k in range(header + 2, header + 2 + count):
        words = lines[k].split()
        for c in columns:
            words[c] = "0.0"
        lines[k] = "  ".join(words)
    return "\n".join(lines) + "\n"


def constant_pitching_moment(folder: Path, cm: float) -> None:
    """Every airfoil table under ``folder`` (``*Polar*.dat``) with its Cm column (the fourth) set to ``cm``: the
    ``NumAlf`` rows after the line labelled so, comment lines skipped."""
    edited_pitching_moment(folder, lambda value: cm)


def scaled_pitching_moment(folder: Path, factor: float) -> None:
    """Every airfoil table under ``folder`` with its Cm column multiplied by ``factor`` (-1: the moment's sign
    turned, so that the damping's parts odd and even in the moment can be told apart)."""
    edited_pitching_moment(folder, lambda value: factor * value)


def edited_pitching_moment(folder: Path, edit) -> None:
    """Every airfoil table under ``folder`` (``*Polar*.dat``) with its Cm column (the fourth) replaced by
    ``edit(Cm)``: the ``NumAlf`` rows after the line labelled so, comment lines skipped."""
    for path in sorted(folder.rglob("*Polar*.dat")):
        lines = path.read_text().splitlines()
        for k, line in enumerate(lines):
            if line.split()[1:2] != ["NumAlf"]:
                continue
            rows, row = int(line.split()[0]), k + 1
            while rows:
                words = lines[row].split()
                if words and not words[0].startswith("!"):
                    lines[row] = "  ".join([*words[:3], f"{edit(float(words[3])):.6e}", *words[4:]])
                    rows -= 1
                row += 1
        path.write_text("\n".join(lines) + "\n")


def without_mass_offsets(text: str) -> str:
    """A BeamDyn blade file's text with each station's six-by-six mass matrix's translation-rotation blocks set to
    0: the sections' mass centres on the reference axis (the rotary inertias and the stiffness kept). BeamDyn's
    rows follow each station's ``eta`` line: six of stiffness, a blank line, six of mass."""
    lines = text.splitlines()
    k = next(k for k, line in enumerate(lines) if "DISTRIBUTED PROPERTIES" in line) + 1
    while k < len(lines):
        if len(lines[k].split()) != 1:
            k += 1
            continue
        for i in range(6):
            words = lines[k + 8 + i].split()
            lines[k + 8 + i] = "  ".join("0.0" if (i < 3) != (j < 3) else words[j] for j in range(6))
        k += 14
    return "\n".join(lines) + "\n"


def bladefem_blade(folder: Path, mass_offsets: bool = True) -> Path:
    """The BeamDyn primary file of the blade as these cases run it, in ``folder`` (the stored files; without
    ``mass_offsets`` the blade file edited by :func:`without_mass_offsets`)."""
    folder.mkdir(parents=True, exist_ok=True)
    for path in BEAMDYN.glob("IEA-15-240-RWT_BeamDyn*.dat"):
        text = path.read_text()
        if not mass_offsets and path.name.endswith("_blade.dat"):
            text = without_mass_offsets(text)
        (folder / path.name).write_text(text)
    return folder / "IEA-15-240-RWT_BeamDyn.dat"


def bladefem_aerodyn(folder: Path) -> Path:
    """The deck's AeroDyn files copied into ``folder`` as these cases run them, in the stored (legacy) layout that
    bladefem reads: quasi-steady polars (AFAeroMod 1), no tower influence, the blade file straightened
    (:func:`straightened_aerodyn_blade`); returns the primary file."""
    sys.path.insert(0, str(HERE))
    from make_standstill import labelled

    for name in ("IEA-15-240-RWT-Monopile", "IEA-15-240-RWT"):
        shutil.copytree(IEA / name, folder / name)
    primary = folder / "IEA-15-240-RWT-Monopile" / "IEA-15-240-RWT-Monopile_AeroDyn15.dat"
    text = primary.read_text()
    for label, value in (("AFAeroMod", "1"), ("TwrPotent", "0"), ("TwrShadow", "0"), ("TwrAero", "False")):
        text = labelled(text, label, value)
    primary.write_text(text)
    blade = folder / "IEA-15-240-RWT" / "IEA-15-240-RWT_AeroDyn15_blade.dat"
    blade.write_text(straightened_aerodyn_blade(blade.read_text()))
    return primary


def write_case(folder: Path, rpm: float, aero: bool = True, prebent: bool = False, order: int = ORDER,
               pitching_moment: bool = True, lin_time: str = LIN_TIME, mass_offsets: bool = True) -> Path:
    """The case's files in OpenFAST v5.0.0's layout (module docstring); without ``aero`` the blade alone, without
    ``pitching_moment`` the airfoils' pitching moment left out (UseBlCm False), without ``mass_offsets`` the
    sections' mass centres moved onto the reference axis (:func:`without_mass_offsets`)."""
    for path in (HERE, HERE / "beamdyn", HERE / "iea15_rosco"):
        sys.path.insert(0, str(path))
    import make_decks
    import write_decks as rosco
    from make_standstill import labelled

    rosco.write_case(folder, 0.0, "unused")          # the deck in v5 layouts (its AeroDyn, airfoils, tower)
    mono, shared = folder / rosco.MONO, folder / rosco.SHARED
    make_decks.ORDER = order
    blade_text = (BEAMDYN / "IEA-15-240-RWT_BeamDyn_blade.dat").read_text()
    (mono / "bd_blade.dat").write_text(make_decks.beamdyn_blade(
        blade_text if mass_offsets else without_mass_offsets(blade_text)))
    (mono / "bd.dat").write_text(make_decks.beamdyn_primary((BEAMDYN / "IEA-15-240-RWT_BeamDyn.dat").read_text(),
                                                            "bd_blade.dat", not prebent))
    tmax = f"{float(lin_time) + float(DT):g}"
    main = make_decks.fst(f"IEA-15MW BeamDyn blade at {rpm:g} rpm in still air", tmax, DT, lin_time, "bd.dat",
                          "ed.dat")
    main = main.replace('"unused"                       AeroFile', f'"{rosco.AD}" AeroFile')
    for label, value in (("CompElast", "2"), ("CompInflow", "0"), ("CompAero", "2" if aero else "0"),
                         ("LinInputs", "0"), ("LinOutputs", "0")):
        main = labelled(main, label, value)
    (mono / FST).write_text(main)
    ed = make_decks.elastodyn((IEA / rosco.MONO / rosco.ED).read_text(), rpm, "unused",
                              f"{rosco.MONO}_ElastoDyn_tower.dat")
    for label in ("PreCone(1)", "PreCone(2)", "PreCone(3)"):
        ed = labelled(ed, label, "0")
    (mono / "ed.dat").write_text(ed)
    ad = mono / rosco.AD
    text = ad.read_text()
    for label, value in (("Wake_Mod", "0"), ("BEM_Mod", "1"), ("UA_Mod", "0"), ("TwrPotent", "0"),
                         ("TwrShadow", "0"), ("TwrAero", "False"), ("UseBlCm", str(pitching_moment))):
        text = labelled(text, label, value)
    ad.write_text(text)
    if not prebent:
        blade = shared / f"{rosco.SHARED}_AeroDyn15_blade.dat"
        blade.write_text(straightened_aerodyn_blade(blade.read_text()))
    return mono / FST


def tip_twist(lin: Path) -> float:
    """Blade 1's elastic twist at its tip at the operating point of the ``.lin`` file, rad: BeamDyn's last node's
    rotation about the span axis (Z), from its Wiener-Milenkovic parameter c as 4 atan(c / 4)."""
    rows = [line.split() for line in lin.read_text().splitlines()
            if "BD_1 finite element node" in line and "rotational displacement in Z, rad" in line
            and "derivative" not in line]
    return 4 * math.atan(float(rows[-1][1]) / 4)


def rotating_frame_modes(lin: Path, rpm: float, count: int = 12) -> list[dict]:
    """Blade 1's oscillating modes (as :func:`make_blade_aeroelastic.blade1_modes`) after the transform of
    OpenFAST/openfast#3400 (fixing OpenFAST/openfast#3394): BeamDyn's state Jacobians are a snapshot in the
    inertial frame but flagged rotating; ``A_r = S A S^-1 + blkdiag(-[w]x)``, ``S = [[I, 0], [-[w]x, I]]`` on each
    (q, dq/dt) triplet, with the hub's angular velocity ``w = (Omega, 0, 0)`` in the states' axes (the shaft along
    X, blade 1 up, no precone)."""
    import numpy as np
    from make_blade_aeroelastic import blade1_modes
    from make_standstill import read_lin

    names, A = read_lin(lin)
    own = np.ix_(*2 * [np.array(["BD_1 " in name for name in names])])
    half = len(A[own]) // 2
    omega = rpm * math.pi / 30.0
    spin = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -omega], [0.0, omega, 0.0]])
    S = np.eye(2 * half)
    for i in range(0, half, 3):
        S[half + i:half + i + 3, i:i + 3] = -spin
    A[own] = S @ A[own] @ np.linalg.inv(S) + np.kron(np.eye(2 * half // 3), -spin)
    return [mode for mode in blade1_modes(names, A) if "natural_frequency_hz" in mode][:count]


def main() -> None:
    from make_blade_aeroelastic import linearized

    openfast, runs = sys.argv[1], Path(sys.argv[2])
    flags = sys.argv[3:]
    valued = ("--order", "--lin-time", "--constant-cm", "--scale-cm")
    order = int(flags[flags.index("--order") + 1]) if "--order" in flags else ORDER
    lin_time = flags[flags.index("--lin-time") + 1] if "--lin-time" in flags else LIN_TIME
    reduce = "--reduce" in flags
    cm = float(flags[flags.index("--constant-cm") + 1]) if "--constant-cm" in flags else None
    factor = float(flags[flags.index("--scale-cm") + 1]) if "--scale-cm" in flags else None
    aero, prebent, moment = "--structural" not in flags, "--prebent" in flags, "--no-pitching-moment" not in flags
    offsets = "--no-mass-offsets" not in flags
    numbers = [f for k, f in enumerate(flags) if not f.startswith("--") and (k == 0 or flags[k - 1] not in valued)]
    rpms = tuple(float(r) for r in numbers) or RPMS
    points = []
    for rpm in rpms:
        folder = runs / (f"rpm{rpm:g}_order{order}_t{lin_time}{'' if aero else '_structural'}"
                         f"{'_prebent' if prebent else ''}{'' if moment else '_nocm'}"
                         f"{'' if cm is None else f'_cm{cm:g}'}"
                         f"{'' if factor is None else f'_cmx{factor:g}'}{'' if offsets else '_no_mass_offsets'}")
        if reduce:
            fst = folder / "IEA-15-240-RWT-Monopile" / FST
        else:
            if folder.exists():
                shutil.rmtree(folder)
            fst = write_case(folder, rpm, aero, prebent, order, moment, lin_time, offsets)
            if cm is not None:
                constant_pitching_moment(folder, cm)
            if factor is not None:
                scaled_pitching_moment(folder, factor)
        point = linearized(None if reduce else openfast, fst, rpm, count=12)
        lin = next(fst.parent.glob("*.lin"))
        points.append({**point, "order_elem": order, "tip_twist_rad": tip_twist(lin),
                       "rotating_frame_modes": rotating_frame_modes(lin, rpm),
                       **({} if cm is None else {"constant_cm": cm}),
                       **({} if factor is None else {"cm_factor": factor})})
    path = HERE / "blade_aeroelastic_linearization_iea15.json"
    old = json.loads(path.read_text()) if path.exists() else {}
    key = ("prebent_points" if prebent else "no_pitching_moment_points" if not moment else
           "constant_cm_points" if cm is not None else "scaled_cm_points" if factor is not None else
           "points" if aero else "structural_points")
    if not offsets:
        key = f"no_mass_offsets_{key}"
    if order != ORDER:
        key = f"order{order}_{key}"
    if float(lin_time) != float(LIN_TIME):
        key = f"lin_time_{lin_time}_{key}"
    kept = [p for p in old.get(key, []) if p["rpm"] not in rpms or p.get("cm_factor") != factor]
    out = {"case": "blade_aeroelastic_linearization_iea15",
           "description": "IEA-15MW BeamDyn blade (the deck's six-by-six sections, reference axis straightened, "
                          f"order_elem {ORDER}, no structural damping) on a held hub turning at each rpm in still "
                          "air, pitch 0, no precone, no gravity, AeroDyn without induction (Wake_Mod 0), BEM_Mod 1, "
                          "UA off (quasi-steady), no tower, aerodynamic-centre offsets and cant 0; linearized at "
                          f"{LIN_TIME} s (the undeflected blade); blade 1's modes; tip_twist_rad: the tip's elastic "
                          "twist at the operating point. structural_points: the same without aerodynamics "
                          "(CompAero 0); no_pitching_moment_points: without the airfoils' pitching moment (UseBlCm "
                          "False); constant_cm_points: every airfoil's Cm set to constant_cm at every angle of attack; "
                          "prebent_points: the files' curved axis and aerodynamic-centre offsets; orderN_*: "
                          "order_elem N (convergence); lin_time_T_*: linearized at T s, part way into the motion "
                          "the aerodynamic loads start; scaled_cm_points: every airfoil's Cm times cm_factor; "
                          "no_mass_offsets_*: the sections' mass centres moved onto the reference axis (the mass "
                          "matrices' translation-rotation blocks 0); rotating_frame_modes: the modes after "
                          "OpenFAST/openfast#3400's rotating-frame transform of BeamDyn's state matrix (points written "
                          "since it was added).",
           "provenance": {"openfast": {"version": "v5.0.0", "commit": "2895884d2",
                                       "build": "the build of /work/build/openfast-src (Release, double precision)"},
                          "blade": "tests/data/iea15/beamdyn",
                          "aerodyn": "tests/data/iea15/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_AeroDyn15.dat",
                          "script": "tests/data/openfast/make_blade_aeroelastic_iea15.py"},
           **{k: v for k, v in old.items() if k.endswith("points")},
           key: sorted(kept + points, key=lambda p: (p["rpm"], p.get("cm_factor", 0.0)))}
    path.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    sys.path.insert(0, str(HERE))
    main()
