"""Write, run and extract OpenFAST linearizations of the NREL 5MW BeamDyn blade turning in still air with quasi-steady
aerodynamics (blade_aeroelastic_linearization.json).

Not run by the tests (OpenFAST is not needed to use the JSON file). Each case: BeamDyn blades (OpenFAST's NREL 5MW
example, tests/data/nrel5mw_beamdyn, straight reference axis, no structural damping, order_elem ORDER), the hub held
(every ElastoDyn DOF off), RotSpeed the case's rotor speed, pitch 0, no precone, Gravity 0, no ServoDyn; AeroDyn
from cases/nrel5mw without induction (Wake_Mod 0: the relative velocity is the rotation alone, as in still air),
legacy projection (BEM_Mod 1), no unsteady aerodynamics (UA_Mod 0: quasi-steady polars, frozen-wake by
construction), no tower influence; still air (CompInflow 0). Linearized once at LIN_TIME s (CalcSteady False). The
three blades do not couple (no rotor, tower or yaw DOF): blade 1's modes are the eigenvalues whose eigenvectors
live on its BeamDyn states.

    python tests/data/openfast/make_blade_aeroelastic.py OPENFAST_EXECUTABLE RUNS_FOLDER [RPM ...] [--structural]
        [--coned] [--lin-time T]

``--lin-time 0`` linearizes at 0 s instead, the undeflected blade before the aerodynamic loads act
(``lin_time_0_points``): at LIN_TIME the blade has started to twist under the airfoils' pitching moment.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
DECK = ROOT / "cases" / "nrel5mw"
BEAMDYN = ROOT / "tests" / "data" / "nrel5mw_beamdyn"
FST = "blade.fst"
AERODYN = "NRELOffshrBsline5MW_Onshore_AeroDyn.dat"
RPMS = (12.1, 20.0, 24.0)
ORDER = 14
TMAX, DT, LIN_TIME = "0.03", "0.001", "0.02"


def write_case(folder: Path, rpm: float, aero: bool = True, coned: bool = False, lin_time: str = LIN_TIME) -> Path:
    """The case's files in OpenFAST v5.0.0's layout (the writers of beamdyn/make_decks.py and make_standstill.py);
    without ``aero`` the blade alone (CompAero 0), the structure's own damping as BeamDyn linearizes it; ``coned``
    keeps the deck's precone (-2.5 deg)."""
    sys.path.insert(0, str(HERE / "beamdyn"))
    sys.path.insert(0, str(HERE))
    import make_decks
    from make_standstill import labelled, write_case as parked

    parked(folder, 0.0)                                   # the deck's AeroDyn file in the v5 layout
    make_decks.ORDER = ORDER
    (folder / "bd_blade.dat").write_text(make_decks.beamdyn_blade((BEAMDYN / "nrel_5mw_blade.inp").read_text()))
    (folder / "bd.dat").write_text(make_decks.beamdyn_primary((BEAMDYN / "bd_primary_nrel_5mw.inp").read_text(),
                                                              "bd_blade.dat", True))
    tmax = TMAX if lin_time == LIN_TIME else f"{float(lin_time) + float(DT):g}"
    main = make_decks.fst(f"NREL 5MW BeamDyn blade at {rpm:g} rpm in still air", tmax, DT, lin_time, "bd.dat",
                          "ed.dat")
    main = main.replace('"unused"                       AeroFile', f'"{AERODYN}" AeroFile')
    for label, value in (("CompElast", "2"), ("CompInflow", "0"), ("CompAero", "2" if aero else "0"),
                         ("LinInputs", "0"), ("LinOutputs", "0")):
        main = labelled(main, label, value)
    (folder / FST).write_text(main)
    ed = make_decks.elastodyn((DECK / "NRELOffshrBsline5MW_Onshore_ElastoDyn.dat").read_text(), rpm,
                              "NRELOffshrBsline5MW_Blade.dat", "NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")
    for label in ("PreCone(1)", "PreCone(2)", "PreCone(3)"):      # the deck's -2.5 deg: a coned blade bends
        ed = ed if coned else labelled(ed, label, "0")                # under its centrifugal load
    (folder / "ed.dat").write_text(ed)
    return folder / FST


def blade1_modes(names: list[str], A: np.ndarray) -> list[dict]:
    """Blade 1's modes: the eigenvalues (upper half-plane) of A's block on blade 1's BeamDyn states (its
    displacements and velocities). The blades do not couple, so A has no entries between them (checked); a block
    avoids splitting the three blades' equal eigenvalues by their eigenvectors."""
    own = np.array(["BD_1 " in name for name in names])
    if np.abs(A[np.ix_(own, ~own)]).max() > 0 or np.abs(A[np.ix_(~own, own)]).max() > 0:
        raise SystemExit("blade 1's states couple with the others")
    values = np.linalg.eigvals(A[np.ix_(own, own)])
    real = np.abs(values.imag) <= 1e-9 * np.abs(values)
    modes = [{"natural_frequency_hz": float(abs(v) / (2 * np.pi)), "damped_frequency_hz": float(v.imag / (2 * np.pi)),
              "damping_ratio": float(-v.real / abs(v))} for v in values[(values.imag > 0) & ~real]]
    modes += [{"real_root_per_s": float(v.real)} for v in values[real]]     # overdamped (or divergent) motion
    return sorted(modes, key=lambda mode: mode.get("natural_frequency_hz", 0.0))


def linearized(openfast: str | None, fst: Path, rpm: float, count: int = 10) -> dict:
    """Run OpenFAST on ``fst`` (its log beside it as log.txt; ``openfast`` None: read the run already there) and
    give the point: blade 1's ``count`` lowest oscillating modes and its six largest real roots (per s)."""
    from make_standstill import read_lin

    if openfast is not None:
        done = subprocess.run([openfast, fst.name], cwd=fst.parent, capture_output=True, text=True)
        (fst.parent / "log.txt").write_text(done.stdout + done.stderr)
        if done.returncode:
            raise SystemExit(f"{fst}: exit {done.returncode}\n{(done.stdout + done.stderr)[-2000:]}")
    names, A = read_lin(next(fst.parent.glob("*.lin")))
    modes = blade1_modes(names, A)
    oscillating = [m for m in modes if "natural_frequency_hz" in m][:count]
    print(rpm, [(round(m["natural_frequency_hz"], 4), round(100 * m["damping_ratio"], 3)) for m in oscillating[:8]],
          flush=True)
    return {"rpm": rpm, "modes": oscillating,
            "real_roots_per_s": sorted(m["real_root_per_s"] for m in modes if "real_root_per_s" in m)[-6:]}


def main() -> None:
    openfast, runs = sys.argv[1], Path(sys.argv[2])
    aero, coned = "--structural" not in sys.argv[3:], "--coned" in sys.argv[3:]
    flags = sys.argv[3:]
    lin_time = flags[flags.index("--lin-time") + 1] if "--lin-time" in flags else LIN_TIME
    rpms = tuple(float(r) for k, r in enumerate(flags)
                 if not r.startswith("--") and (k == 0 or flags[k - 1] != "--lin-time")) or RPMS
    points = []
    for rpm in rpms:
        folder = runs / f"rpm{rpm:g}{'' if aero else '_structural'}{'_coned' if coned else ''}_t{lin_time}"
        if folder.exists():
            shutil.rmtree(folder)
        points.append(linearized(openfast, write_case(folder, rpm, aero, coned, lin_time), rpm))
    path = HERE / "blade_aeroelastic_linearization.json"
    old = json.loads(path.read_text()) if path.exists() else {}
    key = "coned_points" if coned else "points" if aero else "structural_points"
    key = key if lin_time == LIN_TIME else f"lin_time_{lin_time}_{key}"
    kept = [p for p in old.get(key, []) if p["rpm"] not in rpms]
    out = {"case": "blade_aeroelastic_linearization",
           "description": "NREL 5MW BeamDyn blade (OpenFAST's example sections, straight axis, order_elem "
                          f"{ORDER}, no structural damping) on a held hub turning at each rpm in still air, pitch 0, "
                          "no gravity, AeroDyn without induction (Wake_Mod 0), BEM_Mod 1, UA off (quasi-steady), no "
                          f"tower; linearized at {LIN_TIME} s; blade 1's modes. structural_points: the same "
                          "without aerodynamics (CompAero 0); coned_points: with the deck's precone (-2.5 deg); "
                          "lin_time_0_points: linearized at 0 s, before the aerodynamic loads act.",
           "provenance": {"openfast": {"version": "v5.0.0", "commit": "2895884d2",
                                       "build": "the build of /work/build/openfast-src (Release, double precision)"},
                          "blade": "tests/data/nrel5mw_beamdyn", "aerodyn": "cases/nrel5mw/" + AERODYN,
                          "script": "tests/data/openfast/make_blade_aeroelastic.py"},
           **{k: v for k, v in old.items() if k.endswith("points")},
           key: sorted(kept + points, key=lambda p: p["rpm"])}
    path.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    sys.path.insert(0, str(HERE))
    main()
