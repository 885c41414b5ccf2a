"""Wave spectra, directional spreading and the dispersion relation, in numpy (float64, host side).

Conventions: angular frequency omega [rad/s], wavenumber k [rad/m], spectral densities one-sided in
frequency, S(omega) [m^2 s/rad], so that the variance of the surface is m0 = integral of S d omega and the
significant wave height is Hs = 4 sqrt(m0). Directions are the direction the waves travel [rad], from +x
counter-clockwise.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "GRAVITY",
    "dispersion_omega",
    "dispersion_domega_dk",
    "wavenumber_from_omega",
    "jonswap",
    "pierson_moskowitz",
    "pierson_moskowitz_wind",
    "pierson_moskowitz_wind_sea_state",
    "cos2s_spreading",
]

GRAVITY = 9.81
"""Standard gravity used by default [m/s^2]."""

# Phillips constant and shape constant of the Pierson-Moskowitz (1964) spectrum, wind at 19.5 m.
PM_ALPHA = 8.1e-3
PM_BETA = 0.74


def dispersion_omega(k, depth: float = math.inf, gravity: float = GRAVITY):
    """Angular frequency [rad/s] of linear gravity waves of wavenumber ``k`` [rad/m]:
    omega^2 = g k tanh(k h), with h = ``depth`` [m] (inf for deep water, omega^2 = g k)."""
    k = np.asarray(k, dtype=np.float64)
    if math.isinf(depth):
        return np.sqrt(gravity * k)
    return np.sqrt(gravity * k * np.tanh(k * depth))


def dispersion_domega_dk(k, depth: float = math.inf, gravity: float = GRAVITY):
    """Group speed d omega / d k [m/s] of the dispersion relation above, at wavenumber ``k`` > 0."""
    k = np.asarray(k, dtype=np.float64)
    omega = dispersion_omega(k, depth, gravity)
    if math.isinf(depth):
        return 0.5 * omega / np.where(k > 0, k, 1.0)
    kh = k * depth
    sech2 = 1.0 / np.cosh(np.minimum(kh, 350.0)) ** 2
    numerator = gravity * (np.tanh(kh) + kh * sech2)
    return numerator / (2.0 * np.where(omega > 0, omega, 1.0))


def wavenumber_from_omega(omega, depth: float = math.inf, gravity: float = GRAVITY):
    """Invert the dispersion relation: wavenumber k [rad/m] of waves of angular frequency ``omega``.
    Newton iterations from the deep-water value; converges for every depth > 0."""
    omega = np.asarray(omega, dtype=np.float64)
    k = omega**2 / gravity
    if math.isinf(depth):
        return k
    # Start from the larger of the deep- and shallow-water wavenumbers: Newton then approaches monotonically.
    k = np.maximum(k, omega / math.sqrt(gravity * depth))
    for _ in range(50):
        residual = dispersion_omega(k, depth, gravity) ** 2 - omega**2
        slope = gravity * (np.tanh(k * depth) + k * depth / np.cosh(np.minimum(k * depth, 350.0)) ** 2)
        step = residual / slope
        k = k - step
        if np.all(np.abs(step) <= 1e-14 * np.maximum(k, 1e-30)):
            break
    return k


def jonswap(omega, significant_wave_height: float, peak_period: float, gamma: float = 3.3):
    """JONSWAP frequency spectrum S(omega) [m^2 s/rad], in the form of DNV-RP-C205 (2010), sec. 3.5.5:

    S(w) = A_g * 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (w/wp)^-4) * gamma^exp(-(w - wp)^2 / (2 sigma^2 wp^2)),
    with wp = 2 pi / Tp, sigma = 0.07 for w <= wp and 0.09 above, and A_g = 1 - 0.287 ln(gamma) the
    normalising factor that keeps m0 close to Hs^2 / 16 (within about 1 % for 1 <= gamma <= 7).
    """
    omega = np.asarray(omega, dtype=np.float64)
    omega_p = 2.0 * math.pi / peak_period
    safe = np.where(omega > 0, omega, 1.0)
    ratio = safe / omega_p
    pm_shape = 5.0 / 16.0 * significant_wave_height**2 * omega_p**4 * safe**-5 * np.exp(-1.25 * ratio**-4)
    sigma = np.where(omega <= omega_p, 0.07, 0.09)
    peak = gamma ** np.exp(-((safe - omega_p) ** 2) / (2.0 * sigma**2 * omega_p**2))
    normalise = 1.0 - 0.287 * math.log(gamma)
    return np.where(omega > 0, normalise * pm_shape * peak, 0.0)


def pierson_moskowitz(omega, significant_wave_height: float, peak_period: float):
    """Two-parameter Pierson-Moskowitz spectrum (ITTC/Bretschneider form) [m^2 s/rad]:
    S(w) = 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (w/wp)^-4); its m0 is exactly Hs^2 / 16. Equal to
    :func:`jonswap` with gamma = 1."""
    return jonswap(omega, significant_wave_height, peak_period, gamma=1.0)


def pierson_moskowitz_wind(omega, wind_speed: float, gravity: float = GRAVITY):
    """Pierson-Moskowitz (1964) fully developed sea for a wind of ``wind_speed`` [m/s] at 19.5 m:
    S(w) = alpha g^2 w^-5 exp(-beta (g / (U w))^4), alpha = 8.1e-3, beta = 0.74 [m^2 s/rad]."""
    omega = np.asarray(omega, dtype=np.float64)
    safe = np.where(omega > 0, omega, 1.0)
    omega_0 = gravity / wind_speed
    value = PM_ALPHA * gravity**2 * safe**-5 * np.exp(-PM_BETA * (omega_0 / safe) ** 4)
    return np.where(omega > 0, value, 0.0)


def pierson_moskowitz_wind_sea_state(wind_speed: float, gravity: float = GRAVITY) -> tuple[float, float]:
    """Significant wave height [m] and peak period [s] of :func:`pierson_moskowitz_wind`, in closed form:
    Hs = 4 sqrt(alpha / (4 beta)) U^2 / g and wp = (4 beta / 5)^(1/4) g / U."""
    hs = 4.0 * math.sqrt(PM_ALPHA / (4.0 * PM_BETA)) * wind_speed**2 / gravity
    omega_p = (0.8 * PM_BETA) ** 0.25 * gravity / wind_speed
    return hs, 2.0 * math.pi / omega_p


def cos2s_spreading(theta, mean_direction: float, s: float):
    """Directional spreading D(theta) [1/rad] of the cos-2s type (Longuet-Higgins et al. 1963):
    D = G(s) cos^(2s)((theta - theta0) / 2), with G(s) = Gamma(s + 1) / (2 sqrt(pi) Gamma(s + 1/2)) so that
    the integral over one full turn is 1. Larger ``s`` means a narrower spread (s = 0 is isotropic)."""
    theta = np.asarray(theta, dtype=np.float64)
    log_norm = math.lgamma(s + 1.0) - math.lgamma(s + 0.5) - math.log(2.0 * math.sqrt(math.pi))
    half = np.abs(np.cos(0.5 * (theta - mean_direction)))
    return math.exp(log_norm) * half ** (2.0 * s)
