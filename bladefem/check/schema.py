"""The published JSON Schema of a ``bladefem check`` spec (printed by ``bladefem check --schema``)."""

from __future__ import annotations

import json
from typing import Any

from ..limits import MAX_RPM

SCHEMA_ID = "https://bladefem.org/schemas/check-spec-1.json"

_POSITIVE = {"type": "number", "exclusiveMinimum": 0}
#: a rotor speed, rpm: 0 to :data:`bladefem.limits.MAX_RPM`
_RPM = {"type": "number", "minimum": 0, "maximum": MAX_RPM}
_RPM_RANGE = {"type": "array", "items": _RPM, "minItems": 2, "maxItems": 2,
              "description": "operating rotor-speed range [min, max], rpm"}
_MODE_NAME = {"type": "string", "pattern": r"^[a-z-]+ [1-9][0-9]*$",
              "description": "a mode family by kind and number in frequency order, e.g. 'flap 1', 'edge 2', "
                             "'fore-aft 1', 'side-side 1', 'torsion 1'"}

MODEL = {
    "type": "object",
    "additionalProperties": False,
    "required": ["input"],
    "properties": {
        "input": {"type": "string", "description": "any input bladefem reads, relative to the spec file"},
        "operating_rpm": _RPM_RANGE,
        "rpm_points": {"type": "integer", "minimum": 2, "maximum": 200,
                       "description": "rotor speeds of the Campbell sweep over the operating range (default 16)"},
        "blades": {"type": "integer", "minimum": 1, "maximum": 10, "description": "number of blades (default 3)"},
        "n_modes": {"type": "integer", "minimum": 1, "maximum": 30,
                    "description": "modes solved and tracked (default 8)"},
        "elements": {"type": "integer", "minimum": 1, "maximum": 5000,
                     "description": "fixed element count (default: refined until converged)"},
        "tip_radius_m": _POSITIVE,
        "hub_radius_m": {"type": "number", "minimum": 0},
        "precone_deg": {"type": "number", "minimum": -45, "maximum": 45},
        "pitch_deg": {"type": "number", "minimum": -180, "maximum": 180},
        "tip_mass_kg": {"type": "number", "minimum": 0},
        "elastodyn_main": {"type": "string", "description": "ElastoDyn main file for an ElastoDyn blade file"},
        "sections": {"enum": ["full", "condensed", "reduced"],
                     "description": "six-by-six blades: the whole sections in the FE with the transverse shear "
                                    "(default), with the shear condensed, or the diagonal beam"},
        "axis": {"enum": ["curved", "straight"],
                 "description": "six-by-six blades: the file's curved reference axis (default) or straightened onto "
                                "the pitch axis (--straight-axis)"},
        "aerodyn": {"type": "string",
                    "description": "AeroDyn primary file of the blade's aerodynamics (standstill_damping "
                                   "requirements), relative to the spec file"},
    },
}

WINDOW = {
    "type": "object",
    "additionalProperties": False,
    "required": ["mode", "hz"],
    "properties": {
        "mode": _MODE_NAME,
        "hz": {"type": "array", "items": {"type": "number", "minimum": 0}, "minItems": 2, "maxItems": 2,
               "description": "allowed frequency window [low, high], Hz"},
        "rpm": {"anyOf": [_RPM, {"const": "operating"}],
                "description": "rotor speed, rpm, or 'operating' for the whole operating range (default 0)"},
    },
}

RESONANCE = {
    "type": "object",
    "additionalProperties": False,
    "required": ["modes", "harmonics", "margin_percent"],
    "properties": {
        "modes": {"type": "array", "items": _MODE_NAME, "minItems": 1},
        "harmonics": {"type": "array", "items": {"type": "integer", "minimum": 1, "maximum": 100}, "minItems": 1,
                      "description": "rotor harmonics n of the excitations nP"},
        "margin_percent": {"type": "number", "minimum": 0, "exclusiveMaximum": 100,
                           "description": "least |f - nP| / nP over the operating range, per cent"},
    },
}

SOFT_STIFF = {
    "type": "object",
    "additionalProperties": False,
    "required": ["margin_percent"],
    "properties": {
        "modes": {"type": "array", "items": _MODE_NAME, "minItems": 1,
                  "description": "tower modes to keep in the band (default fore-aft 1 and side-side 1)"},
        "margin_percent": {"type": "number", "minimum": 0, "exclusiveMaximum": 100,
                           "description": "least distance above 1P max and below (blades)P min, per cent"},
    },
}

BASELINE = {
    "type": "object",
    "additionalProperties": False,
    "required": ["file", "tolerance_percent"],
    "properties": {
        "file": {"type": "string", "description": "baseline JSON file, relative to the spec file"},
        "rpm": {**_RPM, "description": "rotor speed, rpm (default 0)"},
        "modes": {"type": "integer", "minimum": 1, "maximum": 30, "description": "lowest modes compared (default 4)"},
        "tolerance_percent": {"type": "number", "exclusiveMinimum": 0,
                              "description": "largest relative frequency change per mode, per cent"},
        "min_mac": {"type": "number", "minimum": 0, "maximum": 1,
                    "description": "least MAC between the stored and the present shape (default 0.95)"},
    },
}

ELASTODYN = {
    "type": "object",
    "additionalProperties": False,
    "required": ["tolerance_percent"],
    "properties": {
        "tolerance_percent": {"type": "number", "exclusiveMinimum": 0,
                              "description": "largest relative difference between the frequency ElastoDyn derives "
                                             "from the file's polynomial and the FE frequency, per cent"},
        "rpm": {**_RPM, "description": "rotor speed, rpm (default the main file's)"},
    },
}

_ANGLE = {"type": "number", "minimum": -360, "maximum": 360}

STANDSTILL = {
    "type": "object",
    "additionalProperties": False,
    "required": ["wind_speed_m_s"],
    "properties": {
        "wind_speed_m_s": {"type": "number", "exclusiveMinimum": 0, "maximum": 100,
                           "description": "steady wind speed on the parked rotor, m/s"},
        "pitch_deg": {"type": "number", "minimum": -180, "maximum": 180,
                      "description": "blade pitch, deg (default the model's)"},
        "yaw_deg": {"type": "array", "items": _ANGLE, "minItems": 2, "maxItems": 2,
                    "description": "yaw-misalignment range [start, stop], deg (default [-180, 180])"},
        "yaw_points": {"type": "integer", "minimum": 1, "maximum": 1000,
                       "description": "yaw misalignments over the range (default 73: every 5 deg)"},
        "azimuth_deg": {"type": "array", "items": _ANGLE, "minItems": 1,
                        "description": "rotor azimuths of the blade, deg (default [0])"},
        "tilt_deg": {"type": "number", "minimum": -45, "maximum": 45, "description": "shaft tilt, deg (default 0)"},
        "structural_damping_percent": {"type": "array", "items": {"type": "number", "minimum": 0, "maximum": 100},
                                       "minItems": 2, "maxItems": 3,
                                       "description": "[flap, edge(, torsion)] structural damping, % of critical"},
        "modes": {"type": "array", "items": _MODE_NAME, "minItems": 1,
                  "description": "modes judged (default every mode of the model's n_modes)"},
        "min_percent": {"type": "number", "minimum": -100, "maximum": 100,
                        "description": "least total damping ratio asked, % of critical (default 0)"},
        "quasi_steady": {"type": "boolean",
                         "description": "leave out the AeroDyn file's unsteady switches, as --quasi-steady"},
        "damping_only": {"type": "boolean", "description": "leave out the aerodynamic stiffness, as --damping-only"},
    },
}

FLUTTER = {
    "type": "object",
    "additionalProperties": False,
    "required": ["aero", "rated_rpm", "factor"],
    "properties": {
        "aero": {"type": "string", "description": "AeroDyn primary file, relative to the spec file"},
        "rated_rpm": {"type": "number", "exclusiveMinimum": 0, "maximum": 1e4, "description": "rated rotor speed"},
        "factor": {"type": "number", "minimum": 1, "maximum": 10,
                   "description": "no flutter onset below factor x rated_rpm (the sweep runs up to there)"},
        "wind_speed": {"type": "number", "minimum": 0, "maximum": 100,
                       "description": "wind speed along the shaft, m/s (default 0: still air, no induction)"},
        "points": {"type": "integer", "minimum": 2, "maximum": 200,
                   "description": "rotor speeds swept from rated to factor x rated (default 16)"},
    },
}

KINDS = {"window": WINDOW, "resonance": RESONANCE, "soft_stiff": SOFT_STIFF, "baseline": BASELINE,
         "elastodyn": ELASTODYN, "standstill_damping": STANDSTILL, "flutter": FLUTTER}
#: requirements that need the model's AeroDyn file
AERODYNAMIC = ("standstill_damping",)

REQUIREMENT = {
    "type": "object",
    "required": ["model"],
    "properties": {"name": {"type": "string"}, "model": {"type": "string"}, **KINDS},
    "additionalProperties": False,
    "oneOf": [{"required": [kind]} for kind in KINDS],
}

SPEC_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "$id": SCHEMA_ID,
    "title": "bladefem check spec",
    "description": "Models and the modal design requirements they must meet (bladefem check).",
    "type": "object",
    "additionalProperties": False,
    "required": ["models", "requirements"],
    "properties": {
        "models": {"type": "object", "minProperties": 1, "additionalProperties": MODEL,
                   "description": "models by name"},
        "requirements": {"type": "array", "minItems": 1, "items": REQUIREMENT},
    },
}


def schema_json() -> str:
    """The schema as indented JSON text."""
    return json.dumps(SPEC_SCHEMA, indent=2) + "\n"
