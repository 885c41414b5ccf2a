"""The polar-against-VPP study's judgement (benchmarks/studies/polar_vs_vpp.py) on polars whose verdicts are
known beforehand: ours a fixed fraction of the VPP's, with a missing heading, with the VPP's missing upwind
equilibrium; the interpolation and the best upwind VMG worked by hand; the tow table's ratios; and the tow
itself run once on the simulator (finite, positive, rising with speed)."""

import math

import numpy as np
import pytest

from benchmarks.studies import polar_vs_vpp as study

ANGLES = np.arange(30.0, 180.0 + 1e-9, 5.0)


def _vpp_polar(rng):
    """Smooth positive speeds [m/s] per wind speed, as a VPP gives."""
    return {tws: (ANGLES.copy(),
                  0.6 + 0.1 * tws + 0.4 * np.sin(np.radians(ANGLES)) + rng.uniform(0.0, 0.05, ANGLES.size))
            for tws in (3.0, 5.0, 7.0, 10.0)}


def _scaled(polar, factor):
    return {tws: (a.copy(), factor * s) for tws, (a, s) in polar.items()}


def test_best_upwind_and_interpolation_by_hand():
    angle = np.array([30.0, 40.0, 50.0, 90.0, 100.0])
    speed = np.array([0.5, 1.0, np.nan, 2.0, 3.0])
    vmg, twa = study.best_upwind(angle, speed)
    assert twa == 40.0 and vmg == pytest.approx(math.cos(math.radians(40.0)))  # 0.766 > 0.5 cos 30 = 0.433
    assert all(math.isnan(v) for v in study.best_upwind(angle, np.where(angle < 90, np.nan, speed)))
    at = study.speed_at(angle, speed, np.array([35.0, 40.0, 45.0, 95.0, 20.0, 120.0]))
    np.testing.assert_allclose(at[[0, 1, 3]], [0.75, 1.0, 2.5])
    assert np.isnan(at[2]) and np.isnan(at[4]) and np.isnan(at[5])  # next to a NaN; outside the angles


def test_criteria_pass_and_fail_as_designed(rng, capsys):
    vpp = _vpp_polar(rng)
    rows = study.compare(_scaled(vpp, 0.8), vpp)
    for row in rows:
        assert row["vmg_ratio"] == pytest.approx(0.8) and row["reach_speed_ratio_min"] == pytest.approx(0.8)
        judged = row["true_wind_speed_mps"] in study.CRITERIA_WIND_SPEEDS
        assert row["vmg_criterion"] == row["reach_criterion"] == ("pass" if judged else "n/a")
        assert row["reach_angles_compared"] == 19  # 60, 65, ..., 150 deg
    assert study.print_criteria(rows)
    assert "overall: PASS" in capsys.readouterr().out

    # 72 % of the VPP: VMG passes (>= 70 %), reaching speeds fail (below 75 %).
    rows = study.compare(_scaled(vpp, 0.72), vpp)
    assert [r["vmg_criterion"] for r in rows[:3]] == ["pass"] * 3
    assert [r["reach_criterion"] for r in rows[:3]] == ["fail"] * 3
    assert not study.print_criteria(rows)

    # 130 % passes the VMG and fails the reach (above 125 %); 120 % passes both.
    assert {r["reach_criterion"] for r in study.compare(_scaled(vpp, 1.3), vpp)[:3]} == {"fail"}
    assert {r["reach_criterion"] for r in study.compare(_scaled(vpp, 1.2), vpp)[:3]} == {"pass"}


def test_missing_headings_and_missing_vpp_equilibria(rng):
    vpp = _vpp_polar(rng)
    ours = _scaled(vpp, 0.9)
    ours[5.0][1][ANGLES == 110.0] = np.nan  # no heading held at 110 deg in 5 m/s
    vpp[7.0][1][ANGLES < 90.0] = np.nan  # the VPP finds no upwind equilibrium in 7 m/s
    vpp[7.0][1][ANGLES == 120.0] = np.nan  # nor at 120 deg: that angle is not judged
    rows = {r["true_wind_speed_mps"]: r for r in study.compare(ours, vpp)}
    assert rows[5.0]["reach_angles_without_speed"] == 1 and rows[5.0]["reach_criterion"] == "fail"
    assert rows[5.0]["vmg_criterion"] == "pass"
    assert math.isnan(rows[7.0]["vmg_vpp_mps"]) and rows[7.0]["vmg_criterion"] == "n/a"
    assert rows[7.0]["reach_angles_without_vpp"] == 7  # 60-85 deg and 120 deg
    assert rows[7.0]["reach_angles_compared"] == 12 and rows[7.0]["reach_criterion"] == "pass"
    assert not study.print_criteria(list(rows.values()))
    # A criterion wind speed missing from either polar is an overall failure.
    assert not study.print_criteria([r for r in rows.values() if r["true_wind_speed_mps"] != 3.0])


def test_tow_table_by_hand():
    rows = study.compare_tow(np.array([8.0, 30.0]), {1.0: 6.7, 1.5: 18.1}, (1.0, 1.5))
    assert rows[0]["ratio"] == pytest.approx(8.0 / 6.7) and rows[0]["criterion"] == "pass"  # +19 %
    assert rows[1]["ratio"] == pytest.approx(30.0 / 18.1) and rows[1]["criterion"] == "fail"  # +66 %


def test_tow_runs_on_the_simulator():
    resistance = study.tow_resistance([0.5, 1.0, 1.5])
    assert np.all(np.isfinite(resistance)) and resistance[0] > 0
    assert np.all(np.diff(resistance) > 0), resistance
    with pytest.raises(ValueError, match="speeds must be positive"):
        study.tow_resistance([0.0, 1.0])
