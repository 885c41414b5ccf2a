"""Foil forces against 1/2 rho A V^2 C, with C interpolated by the test itself from the packaged table,
whose rows are checked against figures typed in from the sheet."""

import csv
import importlib.resources
import math

import numpy as np
import pytest
import warp as wp

from ocean_warp.eboat import EBoat, EBoatConfig
from ocean_warp.kernels.foils import FoilTables, foil_force

# Rows of the sheet's foil_coefficients.csv, typed in: alpha [deg] -> sail C_L, sail C_D, foil C_L, foil C_D.
SHEET_ROWS = {
    0: (0.0, 0.05, 0.0, 0.0043),
    15: (0.74, 0.12, 0.4363, 0.1695),
    29: (1.3063, 0.3562, 0.9293, 0.24),
    45: (1.125, 0.7, 1.1979, 1.1979),
    90: (0.26, 1.2392, 0.0, 1.9298),
    135: (-0.8131, 1.0, -1.1979, 1.1979),
    180: (-0.88, 0.5, 0.0, 0.0043),
}


def packaged_table():
    """alpha -> (sail C_L, sail C_D, foil C_L, foil C_D) of the packaged table, read with the csv module."""
    with importlib.resources.files("ocean_warp.eboat").joinpath("foil_coefficients.csv").open() as handle:
        rows = list(csv.DictReader(handle))
    return {int(r["alpha_deg"]): tuple(float(r[k]) for k in ("sail_cl", "sail_cd", "foil_cl", "foil_cd")) for r in rows}


def interpolated(table, angle_deg, column):
    lower = min(int(math.floor(angle_deg)), 179)
    t = angle_deg - lower
    return (1 - t) * table[lower][column] + t * table[lower + 1][column]


def expected_coefficients(table, alpha_deg, which, lift_limit_deg):
    """Linear interpolation in the table; C_L odd, C_D even in alpha; C_L read no further than the limit."""
    a = abs(alpha_deg)
    lift = interpolated(table, min(a, lift_limit_deg), 2 * which)
    return (lift if alpha_deg >= 0 else -lift), interpolated(table, a, 2 * which + 1)


@wp.kernel
def _forces(flows: wp.array(dtype=wp.vec3), chord: wp.vec3, span: wp.vec3, area: float, density: float,
            tables: FoilTables, which: int, lift_limit: float, out: wp.array(dtype=wp.vec4)):
    i = wp.tid()
    if which == 0:
        out[i] = foil_force(flows[i], chord, span, area, density, tables.sail_lift, tables.sail_drag, lift_limit)
    elif which == 1:
        out[i] = foil_force(flows[i], chord, span, area, density, tables.keel_lift, tables.keel_drag, lift_limit)
    else:
        out[i] = foil_force(flows[i], chord, span, area, density, tables.rudder_lift, tables.rudder_drag, lift_limit)


def test_packaged_table_holds_the_sheets_figures():
    table = packaged_table()
    assert sorted(table) == list(range(181))
    for alpha, row in SHEET_ROWS.items():
        np.testing.assert_allclose(table[alpha], row, atol=5e-5)
    assert max(table[a][2] for a in range(181)) == pytest.approx(1.386, abs=5e-4)  # sheet: foil C_L peak (stall)
    for a in range(0, 91):  # foil C_L antisymmetric, C_D symmetric about 90 deg (a symmetric section)
        assert table[90 + a][2] == pytest.approx(-table[90 - a][2], abs=1e-4)
        assert table[90 + a][3] == pytest.approx(table[90 - a][3], abs=1e-4)


@pytest.mark.parametrize("lift_limit_deg", [180.0, 90.0], ids=["table", "lift limited"])
@pytest.mark.parametrize("which", [0, 1, 2], ids=["sail", "keel", "rudder"])
def test_foil_force_is_half_rho_a_v2_c(device, rng, which, lift_limit_deg):
    """The seed profile: the sheet's table for the sail, and its foil columns for keel and rudder alike."""
    table = packaged_table()
    tables = EBoat(EBoatConfig(profile="seed")).foil_tables(device)
    # (Not +-180: the sail's C_L there, -0.88, changes sign with the side the flow comes from.)
    tabulated = [0.0, 10.0, 29.0, 32.0, -45.0, 90.0, -135.0, 179.0]
    interpolated_angles = list(rng.uniform(-179.5, 179.5, size=12))
    angles = np.array(tabulated + interpolated_angles)
    speed = rng.uniform(0.5, 12.0)
    area, density = rng.uniform(0.1, 4.0), rng.uniform(1.0, 1100.0)
    chord, span = np.array([-1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
    # Flow at angle alpha from the chord about the span, plus a spanwise part that must not count.
    alphas = np.radians(angles)
    section = speed * np.stack([-np.cos(alphas), -np.sin(alphas), np.zeros_like(alphas)], axis=1)
    flows = section + rng.uniform(-3, 3, size=(len(angles), 1)) * span
    out = wp.zeros(len(angles), dtype=wp.vec4, device=device)
    wp.launch(_forces, dim=len(angles), device=device,
              inputs=[wp.array(flows, dtype=wp.vec3, device=device), wp.vec3(*chord), wp.vec3(*span), area, density,
                      tables, which, math.radians(lift_limit_deg)], outputs=[out])
    forces, attack = out.numpy()[:, :3].astype(np.float64), out.numpy()[:, 3]
    np.testing.assert_allclose(np.degrees(attack), angles, atol=1e-3)
    for k, alpha in enumerate(angles):
        c_lift, c_drag = expected_coefficients(table, alpha, min(which, 1), lift_limit_deg)
        q = 0.5 * density * area * speed**2
        direction = section[k] / speed
        lift_direction = np.cross(span, direction)
        np.testing.assert_allclose(forces[k] @ direction, q * c_drag, rtol=2e-5, atol=1e-6 * q)
        np.testing.assert_allclose(forces[k] @ lift_direction, q * c_lift, rtol=2e-5, atol=1e-6 * q)
        assert abs(forces[k] @ span) < 1e-6 * q
