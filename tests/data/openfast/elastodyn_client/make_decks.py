"""The real client of `bladefem elastodyn --write`: OpenFAST v5.0.0 with ElastoDyn blades, parked, linearized.

For a turbine (iea15, iea22) and a coefficient file (the blade file the repository ships, or one rewritten by bladefem),
write an OpenFAST v5.0.0 deck with ElastoDyn only: the hub held (every DOF off except FlapDOF1, FlapDOF2, EdgeDOF),
gravity off, no aerodynamics, parked or at a rotor speed; linearize at t = 0.02 s and print the blade frequencies (each appears three
times, once per blade). Usage:
    OPENFAST=... IEA15=... IEA22=... python make_decks.py TURBINE NAME BLADE_FILE [RPM]
writes runs/TURBINE_NAME_RPMrpm.json. The deck writers are those of ../beamdyn/make_decks.py. Not part of bladefem.
"""
import json
import pathlib
import shutil
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "beamdyn"))
import make_decks as bd  # noqa: E402

BLADE_DOFS = ("FlapDOF1", "FlapDOF2", "EdgeDOF")


def elastodyn_blades(source: str, rpm: float, blade_file: str, tower_file: str) -> str:
    text = bd.elastodyn(source, rpm, blade_file, tower_file)
    lines = []
    for line in text.splitlines():
        parts = line.split()
        if len(parts) > 1 and parts[1] in BLADE_DOFS:
            line = f"{'True':<30} {parts[1]} - "
        lines.append(line)
    return "\n".join(lines) + "\n"


def main(turbine: str, name: str, blade_file: str, rpm: str = "0") -> None:
    _, _, ed_main, tower = bd.TURBINES[turbine]
    work = pathlib.Path("runs") / f"{turbine}_{name}_{rpm}rpm"
    if work.exists():
        shutil.rmtree(work)
    work.mkdir(parents=True)
    shutil.copy(blade_file, work / "ed_blade.dat")
    shutil.copy(tower, work / "tower.dat")
    (work / "ed.dat").write_text(elastodyn_blades(pathlib.Path(ed_main).read_text(), float(rpm), "ed_blade.dat", "tower.dat"))
    fst = bd.fst(f"{turbine} {name}", "0.03", "0.001", "0.02", "unused", "ed.dat").replace(
        "2                              CompElast", "1                              CompElast")
    (work / "main.fst").write_text(fst)
    done = subprocess.run([bd.OPENFAST, "main.fst"], cwd=work, capture_output=True, text=True)
    (work / "log.txt").write_text(done.stdout + done.stderr)
    lins = sorted(work.glob("*.lin"))
    if not lins:
        raise SystemExit(f"{turbine} {name}: OpenFAST failed\n{(done.stdout + done.stderr)[-1500:]}")
    f, z = bd.frequencies(bd.read_A(lins[0]))
    print(turbine, name, rpm, [round(float(x), 5) for x in f[::3]])
    json.dump({"turbine": turbine, "coefficients": name, "rpm": float(rpm), "frequencies_hz": f.tolist(),
               "damping_ratio": z.tolist()}, open(f"runs/{turbine}_{name}_{rpm}rpm.json", "w"), indent=1)


if __name__ == "__main__":
    main(*sys.argv[1:5])
