"""The generator torque law (ServoDyn's simple variable-speed control, VSContrl 1) against OpenFAST's own values
and its regions' closed forms."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from bladefem.builders.servodyn import read_servodyn
from bladefem.models.turbine.control import Generator

ROOT = Path(__file__).resolve().parents[1]
SERVO = ROOT / "cases" / "nrel5mw" / "NRELOffshrBsline5MW_Onshore_ServoDyn.dat"
RPM = math.pi / 30


@pytest.fixture(scope="module")
def generator() -> Generator:
    return Generator.from_servodyn(read_servodyn(SERVO))


def test_torque_law_equals_servodyn_in_openfast(generator):
    """At the steady generator speeds of OpenFAST's torque-law runs (8 m/s: region 2; 11.4 m/s: region 2.5) and
    the imposed 1173.7 rpm of the fixed-speed run (region 3), ServoDyn's GenTq (7 significant digits) and GenPwr."""
    data = json.loads((ROOT / "tests" / "data" / "openfast" / "torque_law.json").read_text())
    for point in data["points"]:
        channels = point["channels"]
        speed = channels["GenSpeed"]["mean"] * RPM
        # the means of a steady window: GenTq varies by 5e-5 (std) in it
        assert generator.torque(speed) / 1e3 == pytest.approx(channels["GenTq"]["mean"], rel=2e-5)
        power = generator.torque(speed) * speed * generator.efficiency / 1e3
        assert power == pytest.approx(channels["GenPwr"]["mean"], rel=5e-5)
    rated = json.loads((ROOT / "tests" / "data" / "openfast" / "rated_fixed_speed.json").read_text())["channels"]
    assert generator.torque(rated["GenSpeed"]["mean"] * RPM) / 1e3 == pytest.approx(rated["GenTq"]["mean"], rel=1e-6)


def test_torque_law_regions_are_continuous(generator):
    """The slip line meets the region-2 parabola at the transition speed and reaches the rated torque at the rated
    speed; no torque at rest or motoring."""
    w_t = generator.transition_speed
    assert generator.region2_constant * w_t**2 == pytest.approx(generator.slope * (w_t - generator.synchronous_speed),
                                                                rel=1e-12)
    assert generator.torque(w_t * (1 - 1e-12)) == pytest.approx(generator.torque(w_t * (1 + 1e-12)), rel=1e-9)
    assert generator.torque(generator.rated_speed * (1 - 1e-12)) == pytest.approx(generator.rated_torque, rel=1e-9)
    assert generator.torque(0.0) == 0.0 and generator.torque(-1.0) == 0.0
    assert Generator().torque(100.0) == 0.0
