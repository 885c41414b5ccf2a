"""struct_from: every field of a Warp struct set from configs by name or from keywords; none left unset."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import warp as wp

from ocean_warp.device_structs import struct_fields, struct_from
from ocean_warp.hydrodynamics_config import HydrodynamicsConfig
from ocean_warp.water_config import WaterConfig


@wp.struct
class _Probe:
    speed: float
    count: int
    inverse_length: float


@dataclasses.dataclass
class _First:
    speed: float
    count: int


@dataclasses.dataclass
class _Second:
    speed: float
    length: float


def test_fields_come_from_the_first_source_that_has_them_and_from_keywords():
    rng = np.random.default_rng(11)
    a, b = _First(float(rng.uniform(1, 5)), int(rng.integers(1, 100))), _Second(-1.0, float(rng.uniform(2, 9)))
    probe = struct_from(_Probe, a, b, inverse_length=1.0 / b.length)
    assert struct_fields(_Probe) == ["speed", "count", "inverse_length"]
    assert probe.speed == pytest.approx(a.speed) and probe.count == a.count  # a before b
    assert probe.inverse_length == pytest.approx(1.0 / b.length)
    assert struct_from(_Probe, b, a, inverse_length=0.5).speed == -1.0  # b first now


def test_a_field_nothing_gives_or_an_unknown_keyword_is_an_error():
    with pytest.raises(ValueError, match="_Probe: nothing gives inverse_length"):
        struct_from(_Probe, _First(1.0, 2))
    with pytest.raises(ValueError, match="_Probe: no field lenght"):
        struct_from(_Probe, _First(1.0, 2), inverse_length=1.0, lenght=3.0)


def test_the_water_model_matches_a_copy_made_by_hand():
    """The simulator's WaterModel from a hull model and a water with fresh values, against each field set by
    hand."""
    from ocean_warp.simulator import _water_model

    rng = np.random.default_rng(5)
    config = HydrodynamicsConfig(form_factor=float(rng.uniform(0.05, 0.3)))
    fluid = WaterConfig(density=float(rng.uniform(990, 1030)), gravity=float(rng.uniform(9.78, 9.83)),
                        kinematic_viscosity=float(rng.uniform(1.0e-6, 1.4e-6)))
    substep = float(rng.uniform(0.005, 0.02))
    water = _water_model(config, fluid, substep)
    assert water.density == pytest.approx(fluid.density)
    assert water.gravity == pytest.approx(fluid.gravity)
    assert water.kinematic_viscosity == pytest.approx(fluid.kinematic_viscosity, rel=1e-6)
    assert water.inverse_reference_speed == pytest.approx(1.0 / config.reference_speed)
    assert water.friction_factor == pytest.approx(1.0 + config.form_factor)
    assert water.skin_friction == int(config.skin_friction) and water.slamming == int(config.slamming)
    assert water.inverse_slamming_max_acceleration == pytest.approx(1.0 / config.slamming_max_acceleration)
    assert water.substep == pytest.approx(substep)
    for name in ("pressure_drag_linear", "pressure_drag_quadratic", "pressure_drag_falloff", "suction_linear",
                 "suction_quadratic", "suction_falloff", "slamming_power"):
        assert getattr(water, name) == pytest.approx(getattr(config, name)), name
