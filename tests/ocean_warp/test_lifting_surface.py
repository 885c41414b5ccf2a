"""Keel and rudder as lifting surfaces: coefficients and the rig's keel force against lifting-line
formulas worked by hand."""

import math

import numpy as np
import pytest
import warp as wp

from ocean_warp.eboat import EBoat, EBoatConfig
from ocean_warp.kernels.foils import FoilTables, foil_force
from ocean_warp.lifting_surface import LiftingSurface

NU = 1.19e-6


def by_hand(span, root, tip, factor, e, t, speed, alpha):
    """(C_L, C_D) below stall: Helmbold's lift slope and the lifting line's induced drag; Hoerner's
    profile drag with the ITTC-1957 friction at the mean chord."""
    area = 0.5 * span * (root + tip)
    ar = factor * span**2 / area
    slope = 2 * math.pi * ar / (2 + math.sqrt(ar**2 + 4))
    cf = 0.075 / (math.log10(speed * area / span / NU) - 2) ** 2
    cl = slope * alpha
    return cl, 2 * cf * (1 + 2 * t + 60 * t**4) + cl**2 / (math.pi * e * ar)


def test_coefficients_below_stall(rng):
    span, root = rng.uniform(0.3, 1.5), rng.uniform(0.1, 0.4)
    tip, factor, e, t = root * rng.uniform(0.4, 1.0), rng.uniform(1.0, 2.0), rng.uniform(0.7, 1.0), rng.uniform(0.06, 0.2)
    fin = LiftingSurface(span=span, root_chord=root, tip_chord=tip, end_plate_factor=factor, span_efficiency=e,
                         thickness_ratio=t, max_lift=1.2)
    alphas = np.radians(rng.uniform(0.5, 6.0, size=5))
    cl, cd = fin.coefficients(alphas)
    for k, alpha in enumerate(alphas):
        lift, drag = by_hand(span, root, tip, factor, e, t, fin.design_speed, alpha)
        assert cl[k] == pytest.approx(lift, rel=1e-9) and cd[k] == pytest.approx(drag, rel=1e-9)
    minus_lift, minus_drag = fin.coefficients(-alphas)
    np.testing.assert_allclose(minus_lift, -cl, rtol=1e-12)
    np.testing.assert_allclose(minus_drag, cd, rtol=1e-12)


def test_stall_and_reversed_flow():
    fin = LiftingSurface(span=0.85, root_chord=0.3, tip_chord=0.25, end_plate_factor=2.0, max_lift=1.0)
    cl, cd = fin.tables()
    assert fin.coefficients(fin.stall_angle)[0] == pytest.approx(1.0, abs=1e-9)
    assert cl.max() <= 1.0 + 1e-12  # held at max_lift, no higher
    peak = int(np.argmax(cl))
    assert abs(peak - math.degrees(fin.stall_angle)) <= 1.0
    assert cl[peak + 20] < 0.75 * cl[peak] and cd[peak + 20] > 3 * cd[peak]  # stalled: lift lost, drag up
    assert cl[90] == pytest.approx(0.0, abs=1e-9) and cd[90] == pytest.approx(fin.profile_drag + 1.2, rel=1e-9)
    np.testing.assert_allclose(cl[91:], -cl[89::-1], atol=1e-12)  # C_L odd, C_D even about 90 deg
    np.testing.assert_allclose(cd[91:], cd[89::-1], atol=1e-12)


def test_keel_lift_over_drag_is_a_fins():
    """The issue's measure: the seed's table gave the keel a lift/drag of 2.5-3.6 at 5-10 deg; a fin of the
    keel's aspect ratio on a hull gives well over 10."""
    keel = EBoat().keel
    cl, cd = keel.coefficients(np.radians([4.0, 6.0]))
    assert np.all(cl / cd > 10.0)


@wp.kernel(enable_backward=False)
def _keel_forces(flows: wp.array(dtype=wp.vec3), area: float, density: float, tables: FoilTables,
                 out: wp.array(dtype=wp.vec4)):
    i = wp.tid()
    out[i] = foil_force(flows[i], wp.vec3(-1.0, 0.0, 0.0), wp.vec3(0.0, 0.0, -1.0), area, density,
                        tables.keel_lift, tables.keel_drag, 3.14159265)


# The keels' planforms: (span [m], root chord [m], tip chord [m], t/c). Real (sheet, real geometry): a
# constant-chord fin of 0.235 m, t/c 0.106, 0.74 m outside the hull. Procedural (sheet): 0.23779 m^2 on a
# 0.854 m span, taper 0.8 (assumed), t/c 0.12.
KEELS = {"real": (0.74, 0.235, 0.235, 0.106),
         "procedural": (0.854, 2 * 0.23779 / (0.854 * 1.8), 0.8 * 2 * 0.23779 / (0.854 * 1.8), 0.12)}


@pytest.mark.parametrize("hull", KEELS)
def test_keel_force_in_the_kernel(device, rng, hull):
    """The physics profile's keel at leeway: 1/2 rho A U^2 (C_L, C_D) with the coefficients worked by hand
    from the keel's planform (root on the hull)."""
    eboat = EBoat(EBoatConfig(hull=hull))
    tables = eboat.foil_tables(device)
    span, root, tip, thickness = KEELS[hull]
    area = 0.5 * span * (root + tip)
    leeway = np.radians(rng.uniform(1.0, 5.0, size=4))
    speed = rng.uniform(0.8, 2.0)
    flows = speed * np.stack([-np.cos(leeway), np.sin(leeway), np.zeros(4)], axis=1)  # water from ahead, to port
    out = wp.zeros(4, dtype=wp.vec4, device=device)
    wp.launch(_keel_forces, dim=4, device=device, inputs=[wp.array(flows, dtype=wp.vec3, device=device), area,
                                                          1025.0, tables], outputs=[out])
    forces = out.numpy()[:, :3].astype(np.float64)
    for k, alpha in enumerate(leeway):
        lift, drag = by_hand(span, root, tip, 2.0, 0.9, thickness, 1.5, alpha)
        # The table is read by linear interpolation at 1 deg steps: the drag's curvature costs < 1e-3 of C_D.
        q = 0.5 * 1025.0 * area * speed**2
        direction = flows[k] / speed
        assert forces[k] @ direction == pytest.approx(q * drag, rel=2e-2)
        assert abs(forces[k] @ np.cross([0, 0, -1.0], direction)) == pytest.approx(q * lift, rel=1e-3)


@pytest.mark.parametrize("field, value", [("span", -1.0), ("root_chord", 0.0), ("tip_chord", float("nan")),
                                          ("end_plate_factor", 3.0), ("max_lift", float("nan"))])
def test_bad_planform_names_the_field(field, value):
    arguments = dict(span=0.8, root_chord=0.3, tip_chord=0.2)
    arguments[field] = value
    with pytest.raises(ValueError, match=field):
        LiftingSurface(**arguments)
