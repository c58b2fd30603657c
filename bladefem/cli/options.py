"""Option values checked as argparse parses them: each bounded to what the models can answer (:mod:`bladefem.limits`,
the limit named in the message), so a bad value is a one-line usage error (exit 2) before any computation. Only
the standard library and bladefem's light modules (errors, limits, files) are imported: parsing stays fast."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from typing import Any

from ..errors import InputError, LimitError
from ..files import check_writable
from ..limits import MAX_SPEEDS, check_elements, check_n_modes, check_rpm, check_speeds

#: Most ElastoDyn analysis nodes (BldNodes, TwrNodes; OpenFAST's own files use 17 to 50)
MAX_NODES = 1000


def _argument(check: Callable[[Any], Any]) -> Callable[[str], Any]:
    """An argparse ``type`` from a check that raises LimitError."""
    def parse(text: str) -> Any:
        try:
            return check(text)
        except LimitError as error:
            raise argparse.ArgumentTypeError(error.message) from None
    return parse


def _whole(text: str) -> int | str:
    try:
        return int(text)
    except ValueError:
        return text


rpm = _argument(check_rpm)
n_modes = _argument(lambda text: check_n_modes(_whole(text)))
elements = _argument(lambda text: check_elements(_whole(text)))


def _number(text: str, low: float = -math.inf, low_open: bool = False) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got '{text}'") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got '{text}'")
    if value < low or (low_open and value == low):
        raise argparse.ArgumentTypeError(f"must be {'positive' if low_open else 'non-negative'}, got '{text}'")
    return value


def finite(text: str) -> float:
    """A finite number."""
    return _number(text)


def non_negative(text: str) -> float:
    """A finite number >= 0."""
    return _number(text, 0.0)


def positive(text: str) -> float:
    """A finite number > 0."""
    return _number(text, 0.0, low_open=True)


def rpm_sweep(text: str) -> tuple[float, ...]:
    """START:STOP:COUNT (rpm) -> evenly spaced rotor speeds, rpm, at most :data:`MAX_SPEEDS` of them."""
    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        start, stop, count = check_rpm(parts[0]), check_rpm(parts[1]), int(parts[2])
    except ValueError as error:
        detail = error.message if isinstance(error, LimitError) else "expected START:STOP:COUNT in rpm (e.g. 0:15:16)"
        raise argparse.ArgumentTypeError(f"{detail}, got '{text}'") from None
    if not (1 <= count <= MAX_SPEEDS and start <= stop):
        raise argparse.ArgumentTypeError(f"need START <= STOP and 1 <= COUNT <= {MAX_SPEEDS}, got '{text}'")
    if count == 1:
        return (start,)
    return tuple(start + (stop - start) * k / (count - 1) for k in range(count))


def check_sweep(speeds: Any, modes: int, mesh: int | None, option: str = "--rpm") -> None:
    """An InputError naming ``option`` when a sweep's mode shapes would not fit in memory (estimated up front)."""
    try:
        check_speeds(speeds, modes, mesh, option)
    except LimitError as error:
        raise InputError(error.message, field=option) from None


def check_folder(path: str, field: str = "--output") -> None:
    """Fail now when an output folder (the option ``field``) is a file or cannot be created or written into."""
    from pathlib import Path

    folder = Path(path)
    if folder.exists() and not folder.is_dir():
        raise InputError("is a file, not a folder (give a folder for the outputs)", file=path, field=field)
    check_writable(folder / "probe")


def check_output(path: str | None, field: str | None = None) -> None:
    """Fail now, not after the computation, when an output file (of the option ``field``) cannot be written
    (an input of the command, read-only, a folder...)."""
    if path:
        check_writable(path, field=field)


#: Options that only blades take, and only towers (argparse dest -> option)
BLADE_ONLY = {"tip_radius": "--tip-radius", "hub_radius": "--hub-radius", "precone_deg": "--precone-deg",
              "pitch_deg": "--pitch-deg", "root": "--root", "gravity": "--gravity",
              "gravity_azimuth_deg": "--azimuth-deg"}
TOWER_ONLY = {"tower_height": "--tower-height", "no_gravity": "--no-gravity", "point_top_mass": "--point-top-mass",
              "elastodyn_coefficients": "--elastodyn-coefficients", "margin_percent": "--margin-percent"}


def check_applicable(args: argparse.Namespace, tower: bool) -> None:
    """Refuse options that do not apply to INPUT (a tower or a blade) instead of ignoring them. ``--tip-mass`` is a
    tower's top mass only for a bare ElastoDyn tower file and a windIO tower (other towers give their own)."""
    given = [option for name, option in (BLADE_ONLY if tower else TOWER_ONLY).items()
             if getattr(args, name, None) not in (None, False)]
    if not tower and getattr(args, "rotor_azimuth_deg", 0.0):
        given.append("--rotor-azimuth-deg")
    if tower and getattr(args, "tip_mass", None) is not None:
        from ..builders.detect import detect_format
        kind = detect_format(args.input)
        if not (kind == "windio" or (kind == "elastodyn-tower" and not getattr(args, "elastodyn_main", None))):
            given.append("--tip-mass")
    what = "tower" if tower else "blade"
    for option in given:
        raise InputError(f"{option} does not apply to a {what} (INPUT describes a {what})", file=args.input,
                         field=option)


def check_limits(args: argparse.Namespace) -> None:
    """InputErrors naming the option for values parsed without a bounded type (``--rpm``, ``--n-modes``,
    ``--elements``, ``--nodes``)."""
    checks = {"rpm": check_rpm, "n_modes": check_n_modes, "elements": check_elements,
              "nodes": lambda value, name: None if 1 <= value <= MAX_NODES else _limit(
                  f"must lie between 1 and {MAX_NODES} nodes, got {value}", name)}
    for name, check in checks.items():
        value = getattr(args, name, None)
        if value is not None:
            try:
                check(value, name)
            except LimitError as error:
                raise InputError(error.message, field="--" + name.replace("_", "-")) from None


def _limit(message: str, name: str) -> None:
    raise LimitError(message, field=name)


def emit(text: str, output: str | None) -> None:
    """``text`` to the file ``output`` (written whole, named on stderr), or to stdout without one."""
    import sys

    if output:
        from pathlib import Path

        from ..files import write_atomic
        write_atomic(output, text)
        print(f"# written to {Path(output)}", file=sys.stderr)
    else:
        sys.stdout.write(text)


def check_turbine_bounds(args: argparse.Namespace) -> None:
    """Refuse option values past what is physical (:mod:`bladefem.limits` says why each bound is where it is)."""
    from ..limits import (
        MAX_RPM,
        MAX_RTOL,
        MAX_SHEAR_EXPONENT,
        MAX_WIND_SPEED,
        MAX_YAW_DAMPING,
        MAX_YAW_STIFFNESS,
        MIN_RTOL,
    )
    if args.pitch_deg is not None and abs(args.pitch_deg) > 180:
        raise InputError(f"must lie between -180 and 180 deg, got {args.pitch_deg:g}", field="--pitch-deg")
    if args.rpm is not None and args.rpm > MAX_RPM:
        raise InputError(f"rotor speed must lie between 0 and {MAX_RPM:g} rpm (MAX_RPM), got {args.rpm:g}",
                         field="--rpm")
    if args.rtol is not None and not MIN_RTOL <= args.rtol <= MAX_RTOL:
        raise InputError(f"must lie between {MIN_RTOL:g} and {MAX_RTOL:g} (MIN_RTOL, MAX_RTOL), got {args.rtol:g}",
                         field="--rtol")
    if args.wind_speed is not None and max(args.wind_speed) > MAX_WIND_SPEED:
        raise InputError(f"at most {MAX_WIND_SPEED:g} m/s (MAX_WIND_SPEED), got {max(args.wind_speed):g}",
                         field="--wind-speed")
    if args.shear_exp is not None and abs(args.shear_exp) > MAX_SHEAR_EXPONENT:
        raise InputError(f"must lie between -{MAX_SHEAR_EXPONENT:g} and {MAX_SHEAR_EXPONENT:g}, got "
                         f"{args.shear_exp:g}", field="--shear-exp")
    for name, largest in (("yaw_stiffness", MAX_YAW_STIFFNESS), ("yaw_damping", MAX_YAW_DAMPING)):
        if getattr(args, name) is not None and getattr(args, name) > largest:
            raise InputError(f"must be at most {largest:g} (past it the yaw is locked: --dof yaw=off), got "
                             f"{getattr(args, name):g}", field="--" + name.replace("_", "-"))


def dof_option(dofs: tuple[str, ...], names: list[str] | None, base: Any) -> Any:
    """The free DOFs that ``--dof`` NAME=on|off entries make of ``base`` (a mistake named as the option)."""
    from ..models.turbine.system import select_dofs

    try:
        return select_dofs(dofs, names or [], base=base)
    except InputError as error:
        raise InputError(error.message, field="--dof") from None
