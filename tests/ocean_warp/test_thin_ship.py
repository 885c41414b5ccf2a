"""Michell's thin-ship wave resistance (ocean_warp.thin_ship) against independent quadratures of the same
integral in its theta form, with amplitudes worked out by hand: the Wigley parabolic hull (smooth ends), a
rectangular strut (blunt ends, the oscillating part by scipy's Fourier quadrature) and catamaran pairs, and the
pair's limits."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from ocean_warp.resistance import FROUDE_SAMPLES, FROUDE_STEP
from ocean_warp.thin_ship import HullOffsets, michell_residuary, michell_resistance

RHO, G = 1000.0, 9.81
# The Wigley hull (Wigley 1934; the ITTC's standard thin-ship test case): L/B 10, L/T 16.
L, B, T = 1.0, 0.1, 0.0625


def wigley_offsets(stations=81, depths=41):
    x = np.linspace(-L / 2, L / 2, stations)
    z = np.linspace(-T, 0.0, depths)
    return HullOffsets(x, z, B / 2 * (1 - (2 * x[:, None] / L) ** 2) * (1 - (z[None, :] / T) ** 2))


def wigley_amplitude(k0, secant):
    """A = int int f_x exp(k0 sec^2 z) exp(i k0 sec x) dx dz for the Wigley hull, integrated by hand: f_x is
    (B/2)(-8x/L^2)(1 - z^2/T^2), so A = (B/2) X Z with X = int -8x/L^2 exp(i a x) dx over +-L/2 and
    Z = int_{-T}^0 (1 - z^2/T^2) exp(b z) dz (a = k0 sec, b = k0 sec^2)."""
    a, b, h = k0 * secant, k0 * secant**2, L / 2
    x_part = -8.0 / L**2 * 2j * (math.sin(a * h) / a**2 - h * math.cos(a * h) / a)
    e = math.exp(-b * T)
    z_part = (1 - e) / b - (2 / b**3 - e * (T**2 / b + 2 * T / b**2 + 2 / b**3)) / T**2
    return B / 2 * x_part * z_part


def theta_quadrature(amplitude_squared, speed, pieces=300):
    """R = 4 rho g^2 / (pi U^2) int_0^(pi/2) |A|^2 sec^3 theta dtheta by adaptive quadrature on ``pieces``."""
    edges = np.linspace(0.0, math.pi / 2, pieces + 1)
    integral = sum(quad(lambda t: amplitude_squared(1.0 / math.cos(t)) / math.cos(t) ** 3, a, b, limit=100)[0]
                   for a, b in zip(edges[:-1], edges[1:]))
    return 4.0 * RHO * G**2 / (math.pi * speed**2) * integral


def wigley_wetted_area():
    x, z = np.meshgrid(np.linspace(-L / 2, L / 2, 2001), np.linspace(-T, 0.0, 2001), indexing="ij")
    fx = B / 2 * (-8 * x / L**2) * (1 - (z / T) ** 2)
    fz = B / 2 * (1 - (2 * x / L) ** 2) * (-2 * z / T**2)
    inner = np.trapezoid(np.sqrt(1 + fx**2 + fz**2), z[0], axis=1)
    return 2.0 * np.trapezoid(inner, x[:, 0])


@pytest.mark.parametrize("froude", [0.3, 0.5])
def test_wigley_matches_the_theta_quadrature_of_its_closed_form_amplitude(froude):
    speed = froude * math.sqrt(G * L)
    k0 = G / speed**2
    reference = theta_quadrature(lambda s: abs(wigley_amplitude(k0, s)) ** 2, speed)
    assert michell_resistance(wigley_offsets(), speed, density=RHO, gravity=G)[0] == pytest.approx(reference,
                                                                                                  rel=0.005)


def test_wigley_curve_has_michells_humps_and_hollow():
    """Michell's curve for the Wigley hull (Tuck 1989, J. Austral. Math. Soc. B 30, the Wigley comparisons): a
    hump near Fn 0.3 over a hollow near 0.35, the main hump at Fn 0.45-0.55, and C_w = R / (rho U^2 S / 2) of a
    few thousandths there."""
    froude = np.arange(0.2, 0.76, 0.025)
    speeds = froude * math.sqrt(G * L)
    coefficient = michell_resistance(wigley_offsets(), speeds, density=RHO, gravity=G) / (
        0.5 * RHO * speeds**2 * wigley_wetted_area())
    at = {round(f, 3): c for f, c in zip(froude, coefficient)}
    assert at[0.3] > at[0.25] and at[0.3] > at[0.35]
    assert 0.45 <= froude[np.argmax(coefficient)] <= 0.55
    assert 3e-3 < coefficient.max() < 6e-3
    assert 1e-3 < at[0.3] < 3e-3


def test_a_blunt_strut_matches_its_fourier_quadrature():
    """A rectangular strut (half-breadth h for depth t, length l; both ends blunt): A = -H (exp(i a x1) -
    exp(i a x0)), H = h (1 - exp(-b t)) / b, so |A|^2 = 2 H^2 (1 - cos(k0 l sec)). Its slowly decaying tail is
    what blunt ends bring; the oscillating half goes to scipy's QAWF (a Fourier integral to infinity)."""
    length, half, depth, speed = 2.0, 0.05, 0.1, 1.5
    k0 = G / speed**2
    offsets = HullOffsets([-1.0, -1.0, 1.0, 1.0], [-depth, 0.0], np.array([[0, 0], [half, half], [half, half],
                                                                            [0, 0]], dtype=float))

    def h_squared(secant):
        b = k0 * secant**2
        return (half * (1.0 - math.exp(-b * depth)) / b) ** 2

    # lambda = cosh u on [1, 2] removes 1 / sqrt(lambda^2 - 1); beyond, lambda^2 / sqrt(lambda^2 - 1) is smooth.
    knee = math.acosh(2.0)
    near = quad(lambda u: 2.0 * h_squared(math.cosh(u)) * (1 - math.cos(k0 * length * math.cosh(u)))
                * math.cosh(u) ** 2, 0.0, knee, limit=200)[0]

    def smooth(secant):
        return 2.0 * h_squared(secant) * secant**2 / math.sqrt(secant**2 - 1.0)

    steady = quad(smooth, 2.0, np.inf, limit=200)[0]
    oscillating = quad(smooth, 2.0, np.inf, weight="cos", wvar=k0 * length, limlst=200)[0]
    reference = 4.0 * RHO * G**2 / (math.pi * speed**2) * (near + steady - oscillating)
    assert michell_resistance(offsets, speed, density=RHO, gravity=G)[0] == pytest.approx(reference, rel=0.01)


@pytest.mark.parametrize("froude, separation", [(0.35, 0.3), (0.5, 0.2)])
def test_catamaran_matches_the_theta_quadrature_with_the_interference_factor(froude, separation):
    """Two Wigley hulls ``separation`` L apart: the demihull's |A|^2 times 4 cos^2(k0 sec^2 sin(theta) s / 2)."""
    speed = froude * math.sqrt(G * L)
    k0 = G / speed**2

    def pair(secant):
        transverse = k0 * secant * math.sqrt(secant**2 - 1.0)
        return abs(wigley_amplitude(k0, secant)) ** 2 * 4.0 * math.cos(0.5 * transverse * separation * L) ** 2

    reference = theta_quadrature(pair, speed, pieces=600)
    computed = michell_resistance(wigley_offsets(), speed, separation=separation * L, density=RHO, gravity=G)[0]
    assert computed == pytest.approx(reference, rel=0.005)


def test_pair_limits_and_interference():
    """Side by side (separation 0) the pair is one hull of twice the breadth: 4x the demihull (thin-ship
    resistance is quadratic in the offsets); far apart it is twice the demihull; between, the ratio swings."""
    offsets = wigley_offsets()
    double = HullOffsets(offsets.stations, offsets.depths, 2.0 * offsets.half_breadth)
    speed = 0.4 * math.sqrt(G * L)
    alone = michell_resistance(offsets, speed)[0]
    assert michell_resistance(offsets, speed, separation=0.0)[0] == pytest.approx(4.0 * alone, rel=1e-9)
    assert michell_resistance(double, speed)[0] == pytest.approx(4.0 * alone, rel=1e-9)
    assert michell_resistance(offsets, speed, separation=5.0 * L)[0] == pytest.approx(2.0 * alone, rel=0.005)
    # At Fn 0.35 the pair's divergent waves cancel at 0.2 L apart and add at 0.4 L (the factor's oscillation).
    speed = 0.35 * math.sqrt(G * L)
    alone = michell_resistance(offsets, speed)[0]
    near, middle = michell_resistance(offsets, speed, separation=0.2 * L)[0], michell_resistance(
        offsets, speed, separation=0.4 * L)[0]
    assert near < 1.6 * alone and middle > 2.1 * alone


def test_residuary_table_is_the_resistance_over_the_displacement_weight():
    offsets = wigley_offsets()
    table = michell_residuary(offsets)
    froude = FROUDE_STEP * np.arange(FROUDE_SAMPLES)
    assert table.waterline_length == pytest.approx(L)
    assert table.displaced_volume == pytest.approx(4.0 / 9.0 * L * B * T, rel=1e-3)  # the Wigley hull's volume
    speeds = froude[1:] * math.sqrt(G * L)
    expected = michell_resistance(offsets, speeds, density=RHO, gravity=G) / (RHO * G * table.displaced_volume)
    assert table.upright[0] == 0.0
    np.testing.assert_allclose(table.upright[1:], expected, rtol=1e-9)
    assert not any(table.heel_increase)


@pytest.mark.parametrize("call, named", [
    (lambda: HullOffsets([0.0, 0.5, 1.0], [-0.1, 0.0], [[0.1, 0.1], [0.1, 0.1], [0.0, 0.0]]), "first and last"),
    (lambda: HullOffsets([0.0, 0.5, 1.0], [0.0, -0.1], np.zeros((3, 2))), "depths"),
    (lambda: HullOffsets([0.0, 0.5, 1.0], [-0.1, 0.0], [[0, 0], [float("nan"), 0], [0, 0]]), "half_breadth"),
    (lambda: michell_resistance(wigley_offsets(5, 3), [1.0, -2.0]), "speeds"),
    (lambda: michell_resistance(wigley_offsets(5, 3), 1.0, separation=-1.0), "separation"),
    (lambda: michell_residuary(wigley_offsets(5, 3), hulls=2), "hulls"),
])
def test_bad_input_is_one_line_naming_it(call, named):
    with pytest.raises(ValueError, match=named) as error:
        call()
    assert "\n" not in str(error.value)
