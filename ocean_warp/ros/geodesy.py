"""Latitude, longitude and altitude of the simulator's ENU positions: a datum ties the world frame's origin
to a point of the WGS 84 ellipsoid, and the world frame is that point's local tangent plane (x east, y north,
z up, metres). What a GNSS receiver on the boat would report (``sensor_msgs/NavSatFix``).

The conversion is exact on the ellipsoid (no flat-earth approximation): ENU -> ECEF by the tangent plane's
rotation, then ECEF -> geodetic by Bowring's fixed-point iteration on the latitude (six rounds reach
machine precision within thousands of kilometres of the surface).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

__all__ = ["WGS84_A", "WGS84_F", "GeodeticDatum", "GUANABARA_BAY", "enu_to_geodetic"]

WGS84_A = 6378137.0
"""WGS 84 semi-major axis [m]."""
WGS84_F = 1.0 / 298.257223563
"""WGS 84 flattening."""
_E2 = WGS84_F * (2.0 - WGS84_F)
"""First eccentricity squared."""


@dataclasses.dataclass(frozen=True)
class GeodeticDatum:
    """Where the world frame's origin lies on the WGS 84 ellipsoid: latitude and longitude [deg] (north and
    east positive) and the ellipsoidal height [m] of the still water (z = 0)."""

    latitude_deg: float
    longitude_deg: float
    altitude_m: float = 0.0

    def __post_init__(self):
        for name, low, high in (("latitude_deg", -90.0, 90.0), ("longitude_deg", -180.0, 180.0),
                                ("altitude_m", -1.0e4, 1.0e5)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not low <= value <= high:
                raise ValueError(f"GeodeticDatum.{name} must be a number in [{low:g}, {high:g}], got {value!r}")
            object.__setattr__(self, name, float(value))


GUANABARA_BAY = GeodeticDatum(latitude_deg=-22.9000, longitude_deg=-43.1480, altitude_m=0.0)
"""The default datum: the fairway of Guanabara Bay between Rio de Janeiro and Niteroi (Brazil), the E-Boat
project's home waters. The still water is put on the ellipsoid (altitude 0); the geoid, and so mean sea
level, lies some metres below it there: set ``altitude_m`` for true ellipsoidal heights."""


def _ecef(latitude: np.ndarray, longitude: np.ndarray, height: np.ndarray) -> np.ndarray:
    """(..., 3) Earth-centred, Earth-fixed coordinates [m] of geodetic points (radians, metres)."""
    normal_radius = WGS84_A / np.sqrt(1.0 - _E2 * np.sin(latitude) ** 2)
    return np.stack([(normal_radius + height) * np.cos(latitude) * np.cos(longitude),
                     (normal_radius + height) * np.cos(latitude) * np.sin(longitude),
                     (normal_radius * (1.0 - _E2) + height) * np.sin(latitude)], axis=-1)


def enu_to_geodetic(enu, datum: GeodeticDatum = GUANABARA_BAY) -> np.ndarray:
    """(N, 3) latitude [deg], longitude [deg] and ellipsoidal height [m] of (N, 3) positions ``enu`` (east,
    north, up [m] in ``datum``'s tangent plane: the simulator's world frame)."""
    enu = np.asarray(enu, dtype=np.float64).reshape(-1, 3)
    lat0, lon0 = math.radians(datum.latitude_deg), math.radians(datum.longitude_deg)
    origin = _ecef(np.array(lat0), np.array(lon0), np.array(datum.altitude_m))
    sin_lat, cos_lat, sin_lon, cos_lon = math.sin(lat0), math.cos(lat0), math.sin(lon0), math.cos(lon0)
    # Columns: the east, north and up unit vectors in ECEF.
    rotation = np.array([[-sin_lon, -sin_lat * cos_lon, cos_lat * cos_lon],
                         [cos_lon, -sin_lat * sin_lon, cos_lat * sin_lon],
                         [0.0, cos_lat, sin_lat]])
    x, y, z = (origin + enu @ rotation.T).T
    longitude = np.arctan2(y, x)
    p = np.hypot(x, y)
    latitude = np.arctan2(z, p * (1.0 - _E2))
    for _ in range(6):
        normal_radius = WGS84_A / np.sqrt(1.0 - _E2 * np.sin(latitude) ** 2)
        latitude = np.arctan2(z + _E2 * normal_radius * np.sin(latitude), p)
    # The height along the normal, well conditioned at every latitude.
    height = p * np.cos(latitude) + z * np.sin(latitude) - WGS84_A * np.sqrt(1.0 - _E2 * np.sin(latitude) ** 2)
    return np.column_stack([np.degrees(latitude), np.degrees(longitude), height])
