"""The controller library and its setup for a deck whose ServoDyn runs a Bladed-style DLL (PCMode, VSContrl 5).

Which library (the first that exists):

1. ``--discon-library PATH``: any library with the Bladed ``DISCON`` entry point;
2. the deck's ``DLL_FileName``, relative to the ServoDyn file (as OpenFAST reads it);
3. when ``DLL_FileName`` names ROSCO's library (``libdiscon*``), the one an installed ROSCO package ships
   (``rosco/lib/libdiscon.so``, found with :func:`importlib.util.find_spec`, which does not import the package:
   ROSCO's wheel installs with ``pip install --no-deps rosco``, without its heavy runtime dependencies).

``DLL_InFile`` (ROSCO's DISCON.IN) is read relative to the ServoDyn file and sent to the library as an absolute
path; ``DLL_DT`` "default" is the deck's DT.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from ..errors import InputError
from ..models.turbine.discon import ControllerSetup

#: file name of ROSCO's library on this platform
ROSCO_LIBRARY = {"win32": "libdiscon.dll", "darwin": "libdiscon.dylib"}.get(sys.platform, "libdiscon.so")
#: how to get it
ROSCO_INSTALL = "pip install --no-deps rosco==2.10.6"


def rosco_library() -> Path | None:
    """The library of an installed ROSCO package, without importing it; None if there is none."""
    try:
        spec = importlib.util.find_spec("rosco")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    for folder in spec.submodule_search_locations:
        candidate = Path(folder) / "lib" / ROSCO_LIBRARY
        if candidate.is_file():
            return candidate
    return None


def controller_library(servo, override: str | None) -> Path:
    """The library to run (see the module's docstring); an :class:`InputError` naming the ServoDyn line or the
    option when there is none."""
    if override is not None:
        path = Path(override)
        if not path.is_file():
            raise InputError(f"controller library not found: {override}", field="--discon-library")
        return path.resolve()
    line = servo.dll.lines["DLL_FileName"]
    written = servo.controller.strip().strip('"')
    path = Path(servo.path).parent / written
    if written and path.is_file():
        return path.resolve()
    if Path(written).name.lower().startswith("libdiscon") or written.upper() == "DISCON_LIB_PATH":
        found = rosco_library()
        if found is not None:
            return found
        raise InputError(f"ROSCO's controller library '{written}' is neither there nor installed: install it "
                         f"({ROSCO_INSTALL}) or give --discon-library PATH", file=servo.path, line=line,
                         field="DLL_FileName")
    raise InputError(f"controller library not found: {path} (give --discon-library PATH)", file=servo.path,
                     line=line, field="DLL_FileName")


def controller_setup(deck, override: str | None, time_step: float | None = None) -> ControllerSetup:
    """The :class:`ControllerSetup` of a :class:`~.turbine_deck.TurbineDeck` whose ServoDyn has a DLL;
    ``time_step`` (s, ``--controller-dt``) replaces ServoDyn's DLL_DT."""
    servo = deck.servodyn
    dll = servo.dll
    infile = Path(servo.path).parent / dll.infile.strip().strip('"')
    if not infile.is_file():
        raise InputError(f"the controller's input file is not there: {infile}", file=servo.path,
                         line=dll.lines["DLL_InFile"], field="DLL_InFile")
    return ControllerSetup(
        library=str(controller_library(servo, override)), infile=str(infile.resolve()),
        time_step=time_step or dll.time_step or deck.time_step, blades=deck.params.n_blades, individual=dll.individual,
        servodyn=servo.path, pitch_limits=dll.pitch_limits, rate_limits=dll.rate_limits,
        air_density=deck.aero.rotor.air_density if deck.aero is not None else 1.225, hub_height=deck.hub_height,
        time_step_from="--controller-dt" if time_step else "ServoDyn's DLL_DT" if dll.time_step else
        "DLL_DT 'default': the deck's DT")
