"""Bad ocean configs fail at construction with an error naming the field and what is allowed."""

import math

import pytest

from ocean_warp import OceanConfig, Spectrum

BAD_VALUES = [
    ("tile_size", 0.0, r"tile_size must be > 0"),
    ("tile_size", -12.5, r"tile_size must be > 0"),
    ("tile_size", math.inf, r"tile_size must be a finite number > 0"),
    ("tile_size", math.nan, r"tile_size must be a number > 0"),
    ("resolution", 100, r"resolution must be a power of two from 16 to 2048"),
    ("resolution", 8, r"resolution must be an integer in \[16, 2048\]"),
    ("resolution", 4096, r"resolution must be an integer in \[16, 2048\]"),
    ("resolution", 64.0, r"resolution must be an integer"),
    ("spectrum", "bretschneider", r"spectrum must be one of 'jonswap', 'pierson_moskowitz', 'regular'"),
    ("significant_wave_height", -0.5, r"significant_wave_height must be a number from 0 to 5 \[m\]"),
    ("significant_wave_height", math.nan, r"significant_wave_height must be a number from 0 to 5 \[m\]"),
    ("significant_wave_height", 5.5, r"significant_wave_height must be a number from 0 to 5 \[m\]"),
    ("peak_period", 0.0, r"peak_period must be > 0"),
    ("peak_period", -3.0, r"peak_period must be > 0"),
    ("gamma", 0.5, r"gamma must be in \[1, 10\]"),
    ("gamma", math.inf, r"gamma must be finite"),
    ("wind_speed", -4.0, r"wind_speed must be > 0"),
    ("direction", math.nan, r"direction must be finite"),
    ("spreading", -1.0, r"spreading must be >= 0"),
    ("depth", 0.0, r"depth must be > 0"),
    ("depth", -math.inf, r"depth must be a number > 0 or inf"),
    ("choppiness", -0.1, r"choppiness must be >= 0"),
    ("min_wavelength", -1.0, r"min_wavelength must be >= 0"),
    ("min_wavelength", 300.0, r"min_wavelength must be shorter than tile_size"),
    ("amplitude", -1.0, r"amplitude must be >= 0"),
    ("period", 0.0, r"period must be > 0"),
    ("period", math.inf, r"period must be a finite number > 0"),
    ("phase", math.inf, r"phase must be finite"),
    ("seed", -1, r"seed must be an integer"),
    ("seed", 1.5, r"seed must be an integer"),
    ("water", 9.81, r"water must be a WaterConfig"),
    ("inversion_iterations", 100, r"inversion_iterations must be an integer in \[0, 32\]"),
    ("inversion_tolerance", 0.0, r"inversion_tolerance must be > 0 \[m\]"),
    ("loop_period", 0.0, r"loop_period must be > 0 \[s\] or None"),
    ("loop_period", -30.0, r"loop_period must be > 0"),
    ("loop_period", math.inf, r"loop_period must be a finite number > 0"),
    ("loop_period", math.nan, r"loop_period must be a number > 0"),
]


@pytest.mark.parametrize("field,value,message", BAD_VALUES, ids=[f"{f}={v}" for f, v, _ in BAD_VALUES])
def test_bad_value_raises_naming_the_field(field, value, message):
    with pytest.raises(ValueError, match=r"OceanConfig\." + message):
        OceanConfig(**{field: value})


def test_good_config_normalises_spectrum_name():
    config = OceanConfig(spectrum="pierson_moskowitz", wind_speed=8, resolution=64, spreading=0)
    assert config.spectrum is Spectrum.PIERSON_MOSKOWITZ
    assert isinstance(config.wind_speed, float)
    assert config.long_crested
    assert config.cell_size == pytest.approx(256.0 / 64)


def test_regular_wave_that_does_not_fit_the_grid_is_refused():
    from ocean_warp import Ocean

    with pytest.raises(ValueError, match="longer than tile_size"):
        Ocean(OceanConfig(spectrum="regular", tile_size=20.0, resolution=16, period=10.0), device="cpu")
    with pytest.raises(ValueError, match="too short for the grid spacing"):
        Ocean(OceanConfig(spectrum="regular", tile_size=1000.0, resolution=16, period=1.0), device="cpu")


@pytest.mark.parametrize("t", [math.nan, math.inf, "soon", None.__class__])
def test_update_rejects_a_time_that_is_not_a_finite_number(t):
    from ocean_warp import Ocean

    ocean = Ocean(OceanConfig(resolution=16, tile_size=40.0), device="cpu")
    with pytest.raises(ValueError, match="t must be a finite time in seconds"):
        ocean.update(t)
