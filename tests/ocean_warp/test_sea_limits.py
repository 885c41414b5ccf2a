"""One rule for the sea's height (OceanConfig, Ocean and every job's options) and a bound on the time an
Ocean is evaluated at."""

from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest

from ocean_warp import Ocean, OceanConfig, cli
from ocean_warp.envs.apps.demo import DemoConfig

LIMIT_M = 5.0  # the highest significant wave height the project accepts [m]


@pytest.mark.parametrize("hs", [0.0, LIMIT_M])
def test_wave_heights_up_to_the_limit_are_accepted(hs):
    assert OceanConfig(significant_wave_height=hs).significant_wave_height == hs
    assert DemoConfig(sea_state=hs).sea_state == hs


@pytest.mark.parametrize("hs", [math.nextafter(LIMIT_M, math.inf), 5.01, 1e6, -0.1, math.nan])
def test_wave_heights_beyond_the_limit_are_refused_naming_the_field(hs):
    with pytest.raises(ValueError, match=r"^OceanConfig\.significant_wave_height must be a number from 0 to 5 \[m\]"):
        OceanConfig(significant_wave_height=hs)
    with pytest.raises(ValueError, match=r"^DemoConfig\.sea_state must be a number from 0 to 5 \[m\]"):
        DemoConfig(sea_state=hs)


def test_a_running_ocean_cannot_be_raised_beyond_the_limit():
    ocean = Ocean(OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=1.0), device="cpu")
    ocean.set_significant_wave_height(LIMIT_M)
    with pytest.raises(ValueError, match=r"^Ocean\.set_significant_wave_height: hs must be a number from 0 to 5"):
        ocean.set_significant_wave_height(5.5)


@pytest.mark.parametrize("argv, option", [
    (["ocean", "--hs", "5.5"], "--hs"),
    (["ocean", "--hs", "1e6"], "--hs"),
    (["eval", "--sea-state", "7"], "--sea-state"),
    (["demo", "--sea-state", "6"], "DemoConfig.sea_state"),
    (["render", "--sea-state", "5.01"], "RenderConfig.sea_state"),
    pytest.param(["export-usd", "--sea-state", "1e6", "--out", "{tmp}/stage.usdc"], "ExportConfig.sea_state",
                 marks=pytest.mark.skipif(importlib.util.find_spec("pxr") is None,
                                          reason="export-usd needs usd-core (pxr)")),
])
def test_every_job_refuses_a_sea_beyond_the_limit_in_one_line(argv, option, tmp_path, capsys):
    argv = [item.format(tmp=tmp_path) for item in argv]
    if "--out" not in argv:
        argv += ["--out", str(tmp_path / "out")]
    try:
        code = cli.main(argv)
    except SystemExit as exit_info:
        code = exit_info.code
    assert code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"ocean-warp {argv[0]}: error: {option} must be a number from 0 to 5 "
                                               "[m]"), err
    assert list(tmp_path.iterdir()) == []


def test_update_refuses_a_time_beyond_float32_phase_precision():
    """The grid's fastest wave: the corner of the spectrum, |k| = sqrt(2) pi n / L, deep water omega =
    sqrt(g |k|). Its float64 phase reduction errs by up to omega |t| 2^-52, and float32 phases near 2 pi are
    2^-21 apart: |t| may reach 2^31 / omega."""
    tile, n, gravity = 64.0, 16, 9.81
    omega = math.sqrt(gravity * math.sqrt(2.0) * math.pi * n / tile)
    limit = 2.0**31 / omega
    ocean = Ocean(OceanConfig(tile_size=tile, resolution=n, significant_wave_height=1.0), device="cpu")
    assert ocean.time_limit == pytest.approx(limit, rel=1e-6)  # omega is stored in float32
    for t in (0.999 * limit, -0.999 * limit):
        ocean.update(t)
        assert np.all(np.isfinite(ocean.fields.numpy()))
    for t in (1.001 * limit, -1.001 * limit, 1e12):
        with pytest.raises(ValueError, match=r"^Ocean\.update: t must be within \+-6\.506e\+08 s"):
            ocean.update(t)
