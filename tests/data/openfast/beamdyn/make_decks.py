"""Regenerate linearizations.json: OpenFAST v5.0.0 BeamDyn-blade linearizations (hub held, gravity off, no aero).

Needs an OpenFAST v5.0.0 build (OPENFAST=path/to/openfast) and the IEA repositories checked out (IEA15=, IEA22= their
roots). Usage: python make_decks.py TURBINE RPM straight|prebent [ORDER_ELEM]; each run writes runs/NAME.json.
The decks are written in OpenFAST v5.0.0's layout (the reading order of its FAST_Subs.f90, ElastoDyn_IO.f90 and
BeamDyn_IO.f90), from the turbines' own files.
"""
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np
QSI = True
ORDER = None

def fst(name, tmax, dt, lin_time, bd_file, ed_file):
    L = [("False", "Echo"), ('"FATAL"', "AbortLevel"), (tmax, "TMax"), (dt, "DT"), ("1", "ModCoupling"), ("1", "InterpOrder"),
         ("0", "NumCrctn"), ("1.0", "RhoInf"), ("1e-4", "ConvTol"), ("6", "MaxConvIter"), ("99999", "DT_UJac"), ("1e6", "UJacSclFact")]
    F = [("1", "NRotors"), ("2", "CompElast"), ("0", "CompInflow"), ("0", "CompAero"), ("0", "CompServo"), ("0", "CompSeaSt"),
         ("0", "CompHydro"), ("0", "CompSub"), ("0", "CompMooring"), ("0", "CompIce"), ("0", "CompSoil"), ("0", "MHK"), ("F", "MirrorRotor")]
    E = [("0", "Gravity"), ("1.225", "AirDens"), ("1025", "WtrDens"), ("1.464e-5", "KinVisc"), ("335", "SpdSound"),
         ("103500", "Patm"), ("1700", "Pvap"), ("0", "WtrDpth"), ("0", "MSL2SWL")]
    I = [(f'"{ed_file}"', "EDFile")] + [(f'"{bd_file}"', f"BDBldFile({i})") for i in (1, 2, 3)] + [
        ('"unused"', k) for k in ("InflowFile", "AeroFile", "ServoFile", "SeaStFile", "HydroFile", "SubFile", "MooringFile", "IceFile", "SoilFile")]
    O = [("False", "SumPrint"), ("1", "SttsTime"), ("99999", "ChkptTime"), ('"default"', "DT_Out"), ("0", "TStart"), ("1", "OutFileFmt"),
         ("True", "TabDelim"), ('"ES15.7E2"', "OutFmt")]
    Lin = [("True", "Linearize"), ("False", "CalcSteady"), ("3", "TrimCase"), ("0.001", "TrimTol"), ("0.01", "TrimGain"), ("0", "Twr_Kdmp"),
           ("0", "Bld_Kdmp"), ("1", "NLinTimes"), (lin_time, "LinTimes"), ("1", "LinInputs"), ("1", "LinOutputs"), ("False", "LinOutJac"), ("False", "LinOutMod")]
    V = [("0", "WrVTK"), ("2", "VTK_type"), ("False", "VTK_fields"), ("15", "VTK_fps")]
    out = ["------- OpenFAST v5.0.0 INPUT FILE -------", name]
    for head, rows in (("SIMULATION CONTROL", L), ("FEATURE SWITCHES AND FLAGS", F), ("ENVIRONMENTAL CONDITIONS", E),
                       ("INPUT FILES", I), ("OUTPUT", O), ("LINEARIZATION", Lin), ("VISUALIZATION", V)):
        out.append(f"---------------------- {head} ----------------------")
        out += [f"{v:<30} {k} - " for v, k in rows]
    return "\n".join(out) + "\n"

def elastodyn(source: str, rpm: float, blade_file: str, tower_file: str) -> str:
    """ElastoDyn v5 primary from a v3 one: every DOF off, the rotor at rpm, the v4/v5 entries added (zero)."""
    values = {}
    for line in source.splitlines():
        parts = line.split()
        if len(parts) >= 2 and not line.startswith("-"):
            values[parts[1]] = parts[0]
    def v(k, default="0"):
        return values.get(k, default)
    order = [("SIMULATION CONTROL", [("False", "Echo"), ("3", "Method"), ('"default"', "DT")]),
             ("DEGREES OF FREEDOM", [("False", k) for k in ("FlapDOF1", "FlapDOF2", "EdgeDOF", "PitchDOF", "TeetDOF", "DrTrDOF", "GenDOF", "YawDOF",
                                                          "TwFADOF1", "TwFADOF2", "TwSSDOF1", "TwSSDOF2", "PtfmSgDOF", "PtfmSwDOF", "PtfmHvDOF", "PtfmRDOF", "PtfmPDOF", "PtfmYDOF")]),
             ("INITIAL CONDITIONS", [("0", "OoPDefl"), ("0", "IPDefl"), ("0", "BlPitch(1)"), ("0", "BlPitch(2)"), ("0", "BlPitch(3)"), ("0", "TeetDefl"),
                                     ("0", "Azimuth"), (f"{rpm}", "RotSpeed")] + [("0", k) for k in ("NacYaw", "TTDspFA", "TTDspSS", "PtfmSurge", "PtfmSway", "PtfmHeave", "PtfmRoll", "PtfmPitch", "PtfmYaw")]),
             ("TURBINE CONFIGURATION", [(v("NumBl"), "NumBl"), (v("TipRad"), "TipRad"), (v("HubRad"), "HubRad")] +
              [(v(f"PreCone({i})"), f"PreCone({i})") for i in (1, 2, 3)] +
              [(v(k), k) for k in ("HubCM", "UndSling", "Delta3", "AzimB1Up", "OverHang", "ShftGagL", "ShftTilt", "NacCMxn", "NacCMyn", "NacCMzn",
                                   "NcIMUxn", "NcIMUyn", "NcIMUzn", "Twr2Shft", "TowerHt", "TowerBsHt", "PtfmCMxt", "PtfmCMyt", "PtfmCMzt")] +
              [("0", "PtfmRefxt"), ("0", "PtfmRefyt"), (v("PtfmRefzt"), "PtfmRefzt")]),
             ("MASS AND INERTIA", [("0", f"TipMass({i})") for i in (1, 2, 3)] + [("0", f"PBrIner({i})") for i in (1, 2, 3)] + [("0", f"BlPIner({i})") for i in (1, 2, 3)] +
              [(v(k), k) for k in ("HubMass", "HubIner")] + [("0", "HubIner_Teeter")] + [(v(k), k) for k in ("GenIner", "NacMass", "NacYIner", "YawBrMass")] +
              [("0", k) for k in ("PtfmMass", "PtfmRIner", "PtfmPIner")] + [(v("PtfmYIner"), "PtfmYIner")] + [("0", k) for k in ("PtfmXYIner", "PtfmYZIner", "PtfmXZIner")]),
             ("BLADE", [("50", "BldNodes")] + [(f'"{blade_file}"', f"BldFile({i})") for i in (1, 2, 3)]),
             ("ROTOR-TEETER", [("0", k) for k in ("TeetMod", "TeetDmpP", "TeetDmp", "TeetCDmp", "TeetSStP", "TeetHStP", "TeetSSSp", "TeetHSSp")]),
             ("YAW-FRICTION", [("0", k) for k in ("YawFrctMod", "M_CSmax", "M_FCSmax", "M_MCSmax", "M_CD", "M_FCD", "M_MCD", "sig_v", "sig_v2", "OmgCut")]),
             ("DRIVETRAIN", [("100", "GBoxEff"), (v("GBRatio"), "GBRatio"), (v("DTTorSpr"), "DTTorSpr"), (v("DTTorDmp"), "DTTorDmp")]),
             ("FURLING", [("False", "Furling"), ('"unused"', "FurlFile")]),
             ("TOWER", [("20", "TwrNodes"), (f'"{tower_file}"', "TwrFile")]),
             ("OUTPUT", [("False", "SumPrint"), ("1", "OutFile"), ("True", "TabDelim"), ('"ES10.3E2"', "OutFmt"), ("0", "TStart"), ("1", "DecFact"),
                         ("0", "NTwGages"), ("0", "TwrGagNd"), ("0", "NBlGages"), ("0", "BldGagNd")])]
    out = ["------- ELASTODYN v5.0 INPUT FILE -------", "BeamDyn reference: every ElastoDyn DOF off"]
    for head, rows in order:
        out.append(f"---------------------- {head} ----------------------")
        out += [f"{val:<30} {key} - " for val, key in rows]
    out += ["                   OutList  - ", '"RotSpeed"', "END"]
    return "\n".join(out) + "\n"

def beamdyn_primary(source: str, blade_file: str, straight: bool) -> str:
    lines = source.splitlines()
    out, skip = [], False
    for line in lines:
        if "PITCH ACTUATOR" in line:
            skip = True
            continue
        if skip and line.startswith("---"):
            skip = False
        if skip:
            continue
        if "BldFile" in line and "MATERIAL" not in line:
            line = f'"{blade_file}"    BldFile - '
        if ("OUTLIST" in line.upper() and line.lstrip().startswith("-")) or (line.split()[:1] == ["OutList"]):
            out += [line, "END"]
            break
        if ORDER and line.split()[1:2] == ["order_elem"]:
            line = f"{ORDER}   order_elem - "
        if "QuasiStaticInit" in line:
            line = ("True" if QSI else "False") + "          QuasiStaticInit - "
        out.append(line)
    text = "\n".join(out) + "\n"
    if straight:         # the reference axis straightened: no prebend or sweep (x, y of the key points 0)
        def fix(m):
            z, t = m.group(3), m.group(4)
            return f"\t 0.0 \t 0.0 \t {z} \t {t} "
        text = re.sub(r"(?m)^\s*([-\d.eE+]+)\s+([-\d.eE+]+)\s+([-\d.eE+]+)\s+([-\d.eE+]+)\s*$", fix, text)
    return text

def beamdyn_blade(source: str) -> str:
    """v5 blade file: damping off, the modal-damping block added after the mu table."""
    lines = source.splitlines()
    out = []
    has_modal = "n_modes" in source
    for k, line in enumerate(lines):
        parts = line.split()
        if len(parts) > 1 and parts[1] == "damp_type":
            line = " 0   damp_type        - Damping type: 0: none"
        out.append(line)
        if not has_modal and k > 0 and "mu1" not in line and lines[k - 1].strip().startswith("(-)"):
            out += ["---------------------- MODAL DAMPING -----------------------", "1  n_modes - ", "0.0  zeta - "]
    return "\n".join(out) + "\n"

def read_A(path):
    text = pathlib.Path(path).read_text().splitlines()
    n = None
    for line in text:
        m = re.search(r"Number of continuous states:\s+(\d+)", line)
        if m: n = int(m.group(1))
    start = next(i for i, l in enumerate(text) if l.strip().startswith("A:"))
    rows = [list(map(float, text[start + 1 + k].split())) for k in range(n)]
    return np.array(rows)

def frequencies(A, count=12):
    lam = np.linalg.eigvals(A)
    f = np.abs(lam) / (2 * np.pi)
    zeta = -lam.real / np.abs(lam)
    keep = lam.imag > 1e-9
    order = np.argsort(f[keep])
    return f[keep][order], zeta[keep][order]

def run(case, primary, blade, ed_source, tower_file, rpm, straight, tmax="0.03", dt="0.001", lin_time="0.02"):
    work = pathlib.Path("runs") / case
    if work.exists(): shutil.rmtree(work)
    work.mkdir(parents=True)
    (work / "bd_blade.dat").write_text(beamdyn_blade(pathlib.Path(blade).read_text()))
    (work / "bd.dat").write_text(beamdyn_primary(pathlib.Path(primary).read_text(), "bd_blade.dat", straight))
    shutil.copy(tower_file, work / "tower.dat")
    (work / "ed.dat").write_text(elastodyn(pathlib.Path(ed_source).read_text(), rpm, "unused", "tower.dat"))
    (work / "main.fst").write_text(fst(case, tmax, dt, lin_time, "bd.dat", "ed.dat"))
    done = subprocess.run([OPENFAST, "main.fst"], cwd=work, capture_output=True, text=True)
    (work / "log.txt").write_text(done.stdout + done.stderr)
    lins = sorted(work.glob("*.lin"))
    if not lins:
        print(case, "FAILED", (done.stdout + done.stderr)[-1500:])
        return None
    f, z = frequencies(read_A(lins[0]))
    return f, z


OPENFAST = os.environ.get("OPENFAST", "openfast")
R = os.environ.get("IEA15", ".") + "/OpenFAST/"
R22 = os.environ.get("IEA22", ".") + "/OpenFAST/"
ROOT = pathlib.Path(__file__).resolve().parents[4]
TURBINES = {
 "iea15": (R + "IEA-15-240-RWT/IEA-15-240-RWT_BeamDyn.dat", R + "IEA-15-240-RWT/IEA-15-240-RWT_BeamDyn_blade.dat",
           R + "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat", R + "IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn_tower.dat"),
 "iea22": (R22 + "IEA-22-280-RWT/IEA-22-280-RWT_BeamDyn.dat", R22 + "IEA-22-280-RWT/IEA-22-280-RWT_BeamDyn_Blade.dat",
           R22 + "IEA-22-280-RWT-Monopile/IEA-22-280-RWT_ElastoDyn.dat", R22 + "IEA-22-280-RWT-Monopile/IEA-22-280-RWT_ElastoDyn_tower.dat"),
 "nrel5mw": (str(ROOT) + "/tests/data/nrel5mw_beamdyn/bd_primary_nrel_5mw.inp", str(ROOT) + "/tests/data/nrel5mw_beamdyn/nrel_5mw_blade.inp",
           str(ROOT) + "/cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ElastoDyn.dat", str(ROOT) + "/cases/nrel5mw/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat"),
}
if __name__ == "__main__":
    turbine, rpm, shape = sys.argv[1], float(sys.argv[2]), sys.argv[3]

    ORDER = int(sys.argv[4]) if len(sys.argv) > 4 else None
    name = f"{turbine}_{rpm:g}rpm_{shape}" + (f"_order{ORDER}" if ORDER else "")
    f, z = run(name, *TURBINES[turbine], rpm, shape == "straight")
    print(name, np.round(f[:21:3], 4))
    json.dump({"turbine": turbine, "rpm": rpm, "reference_axis": shape, "frequencies_hz": f[:36].tolist(), "damping_ratio": z[:36].tolist()},
              open(f"runs/{name}.json", "w"), indent=1)
