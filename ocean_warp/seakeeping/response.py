"""Linear seakeeping of a free-floating hull from its database: the rigid-body mass matrix and hydrostatic
stiffness about the body origin, and the response amplitude operators (RAOs) in regular waves.

    (-w^2 (M + A(w)) + i w (B(w) + B_extra) + C) xi = X(w, heading)

with xi the complex amplitudes of the six motions of the body origin per metre of wave amplitude (translations
[m/m], rotations [rad/m]), phases against the wave's elevation at the body origin, in the convention
x(t) = Re(xi e^(i w t)). Numpy only: the database file is all it needs (no BEM at run time).
"""

from __future__ import annotations

import math

import numpy as np

from ..hull import Hull
from ..hull_form import areas_and_normals, clip_triangles
from .database import HydroDatabase

__all__ = ["rigid_body_mass_matrix", "hydrostatic_stiffness", "response_amplitude_operators", "natural_period"]


def _skew(vector) -> np.ndarray:
    x, y, z = vector
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def rigid_body_mass_matrix(mass: float, center_of_mass, inertia) -> np.ndarray:
    """(6, 6) M_RB about the body origin (Fossen): [[m I, -m S(r_g)], [m S(r_g), I_g - m S(r_g)^2]], from ``mass``
    [kg], ``center_of_mass`` r_g (3,) [m] from the origin and ``inertia`` I_g (3, 3) [kg m^2] about the centre
    of mass, body axes."""
    r = np.asarray(center_of_mass, dtype=np.float64)
    inertia = np.asarray(inertia, dtype=np.float64)
    if not (math.isfinite(mass) and mass > 0) or r.shape != (3,) or inertia.shape != (3, 3):
        raise ValueError(f"rigid_body_mass_matrix: need mass > 0 [kg], center_of_mass (3,) and inertia (3, 3), got "
                         f"{mass!r}, {r.shape}, {inertia.shape}")
    s = _skew(r)
    matrix = np.zeros((6, 6))
    matrix[:3, :3] = mass * np.eye(3)
    matrix[:3, 3:] = -mass * s
    matrix[3:, :3] = mass * s
    matrix[3:, 3:] = inertia - mass * s @ s
    return matrix


def _product_integral(area: np.ndarray, f: np.ndarray, g: np.ndarray) -> np.ndarray:
    """Integral of f g over each triangle, f and g linear (values at the corners, (T, 3)): A/12 (sum f_i g_i +
    sum f_i sum g_i)."""
    return area / 12.0 * (np.sum(f * g, axis=1) + f.sum(axis=1) * g.sum(axis=1))


def hydrostatic_stiffness(hull: Hull, rest_height: float, mass: float, center_of_mass, *,
                          water_density: float = 1025.0, gravity: float = 9.81, appendage_volume: float = 0.0,
                          appendage_center=(0.0, 0.0, 0.0)) -> np.ndarray:
    """(6, 6) linear hydrostatic and gravity restoring matrix C about the body origin of ``hull`` floating upright
    with its origin ``rest_height`` [m] above still water, holding ``mass`` [kg] with its centre at
    ``center_of_mass`` (3,) [m] (body frame). With Awp the waterplane's area, Sx and Sy its first moments and
    Ixx, Iyy, Ixy the integrals of y^2, x^2 and x y over it, V the displaced volume and (x_B, y_B, z_B) its
    centre, (x_G, y_G, z_G) the centre of mass, all measured from the body origin:

        C33 = rho g Awp         C34 = C43 = rho g Sy       C35 = C53 = -rho g Sx
        C44 = rho g (Ixx + V z_B) - m g z_G                C55 = rho g (Iyy + V z_B) - m g z_G
        C45 = C54 = -rho g Ixy  C46 = -rho g V x_B + m g x_G    C56 = -rho g V y_B + m g y_G

    The waterplane integrals come from the wet skin by the divergence theorem (over the plane, f dA equals
    -f n_z dS over the skin, for f independent of z); the hull needs no waterplane of its own. Parts always under
    water outside the mesh (a keel fin and bulb, a rudder: ``appendage_volume`` [m^3] centred at
    ``appendage_center`` (3,) [m]) add their buoyancy's terms, rho g V_a z_a to C44 and C55, -rho g V_a x_a to
    C46 and -rho g V_a y_a to C56."""
    waterline = -float(rest_height)
    triangles = hull.vertices[hull.triangles].astype(np.float64)
    wet = clip_triangles(triangles, waterline - triangles[:, :, 2])
    area, vector = areas_and_normals(wet)
    nz = np.divide(vector[:, 2], area, out=np.zeros_like(area), where=area > 0)  # unit normal's z
    x, y, depth = wet[:, :, 0], wet[:, :, 1], wet[:, :, 2] - waterline
    one = np.ones_like(x)
    plane = lambda f, g: -float(np.sum(nz * _product_integral(area, f, g)))  # noqa: E731
    waterplane, first_x, first_y = plane(one, one), plane(x, one), plane(y, one)
    second_xx, second_yy, second_xy = plane(x, x), plane(y, y), plane(x, y)
    # Volume and its centre: div(f (z - waterline) e_z) for f = 1, x, y; div((z - waterline)^2 / 2 e_z).
    volume = float(np.sum(nz * _product_integral(area, depth, one)))
    if volume <= 0.0:
        raise ValueError(f"hydrostatic_stiffness: hull {hull.name!r} is out of the water at rest height "
                         f"{rest_height!r} m")
    x_b = float(np.sum(nz * _product_integral(area, depth, x))) / volume
    y_b = float(np.sum(nz * _product_integral(area, depth, y))) / volume
    z_b = waterline + 0.5 * float(np.sum(nz * _product_integral(area, depth, depth))) / volume
    x_g, y_g, z_g = (float(v) for v in center_of_mass)
    rg, mg = water_density * gravity, mass * gravity
    c = np.zeros((6, 6))
    c[2, 2] = rg * waterplane
    c[2, 3] = c[3, 2] = rg * first_y
    c[2, 4] = c[4, 2] = -rg * first_x
    c[3, 3] = rg * (second_yy + volume * z_b) - mg * z_g
    c[4, 4] = rg * (second_xx + volume * z_b) - mg * z_g
    c[3, 4] = c[4, 3] = -rg * second_xy
    c[3, 5] = -rg * volume * x_b + mg * x_g
    c[4, 5] = -rg * volume * y_b + mg * y_g
    x_a, y_a, z_a = (float(v) for v in appendage_center)
    c[3, 3] += rg * appendage_volume * z_a
    c[4, 4] += rg * appendage_volume * z_a
    c[3, 5] -= rg * appendage_volume * x_a
    c[4, 5] -= rg * appendage_volume * y_a
    return c


def response_amplitude_operators(database: HydroDatabase, mass_matrix, stiffness, *, heading_deg: float,
                                 extra_damping=None) -> np.ndarray:
    """(F, 6) complex RAOs at the database's frequencies for waves of heading ``heading_deg`` (one of the
    database's excitation headings; 180 head seas, 90 beam seas), of the hull with ``mass_matrix`` (6, 6) and
    ``stiffness`` (6, 6) about its body origin (:func:`rigid_body_mass_matrix`, :func:`hydrostatic_stiffness`)
    and optionally ``extra_damping`` (6, 6) (viscous roll damping, say). See the module's docstring.

    Give M and C of an equilibrium: a centre of mass that is not over the centre of buoyancy leaves C46 and
    C56 nonzero, which couple yaw (no stiffness of its own) into roll and pitch (the E-Boat, upright, has its
    centre of mass 4 cm aft of its hull's and appendages' centre of buoyancy: it trims 0.6 deg by the stern)."""
    if database.excitation is None:
        raise ValueError(f"database of hull {database.hull_name!r} holds no excitation forces")
    headings = np.degrees(database.excitation_headings)
    distance = np.abs((headings - heading_deg + 180.0) % 360.0 - 180.0)
    if distance.min() > 1e-6:
        raise ValueError(f"heading {heading_deg!r} deg is not among the database's excitation headings "
                         f"{[round(float(h), 6) for h in headings]}")
    forces = database.excitation[:, int(np.argmin(distance)), :]
    mass_matrix, stiffness = np.asarray(mass_matrix, dtype=np.float64), np.asarray(stiffness, dtype=np.float64)
    extra = np.zeros((6, 6)) if extra_damping is None else np.asarray(extra_damping, dtype=np.float64)
    w = database.frequencies[:, None, None]
    impedance = -w**2 * (mass_matrix[None] + database.added_mass) + 1j * w * (database.damping + extra[None]) \
        + stiffness[None]
    return np.linalg.solve(impedance, forces[..., None])[..., 0]


def natural_period(database: HydroDatabase, mass: float, stiffness: float, dof: int) -> float:
    """The undamped natural period [s] of one degree of freedom ``dof`` with ``mass`` (its M_RB diagonal term)
    and ``stiffness`` (its C diagonal term): T = 2 pi / w_n where w_n^2 (mass + A_dof,dof(w_n)) = stiffness,
    A interpolated linearly over the database's frequencies (held constant outside them), by bisection; NaN
    for a stiffness <= 0."""
    if not stiffness > 0:
        return math.nan
    w = database.frequencies
    added = database.added_mass[:, dof, dof]
    low, high = 1e-4, 1e4  # w^2 (m + A(w)) - C is negative at the one end and positive at the other
    for _ in range(100):
        middle = math.sqrt(low * high)
        if middle**2 * (mass + float(np.interp(middle, w, added))) < stiffness:
            low = middle
        else:
            high = middle
    return 2 * math.pi / math.sqrt(low * high)
