"""The E-Boat's total mass, centre of mass and inertia, composed from its links (parallel-axis theorem)."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..boat_type import parallel_axis_term
from .sheet import LINK_MASS_DIFFERENCE_V_A, LINKS, Link, Version

__all__ = ["MassProperties", "link_inertia", "composite", "eboat_mass_properties"]


@dataclasses.dataclass(frozen=True)
class MassProperties:
    mass: float
    """[kg]"""
    center_of_mass: np.ndarray
    """(3,) in the base frame [m]."""
    inertia: np.ndarray
    """(3, 3) about the centre of mass, base-frame axes [kg m^2]."""


def link_inertia(link: Link) -> np.ndarray:
    """(3, 3) inertia of a link about its own centre of mass [kg m^2]: the sheet's or the URDF's figures, or those of
    the link's shape (mast: cylinder; boom: rod; sail: thin triangle; rudder: box), or zero for the
    small parts taken as point masses."""
    m = link.mass
    if link.inertia is not None:
        inertia = np.asarray(link.inertia, dtype=np.float64)
        if inertia.shape == (3, 3):
            return inertia
        ixx, iyy, izz, ixz = inertia
        return np.array([[ixx, 0.0, ixz], [0.0, iyy, 0.0], [ixz, 0.0, izz]])
    if link.name == "mast":  # sheet: cylinder r 0.05 m, 3.55 m long, along z
        r, length = 0.05, 3.55
        across = m * (3 * r * r + length * length) / 12
        return np.diag([across, across, 0.5 * m * r * r])
    if link.name == "boom":  # sheet: 1.8 m long, along x
        along = m * 1.8**2 / 12
        return np.diag([0.0, along, along])
    if link.name == "sail":  # a thin triangle in the x-z plane, foot 1.8 m (the boom), height 3.16 m (assumed)
        foot, height = 1.8, 3.16
        return np.diag([m * height**2 / 18, m * (foot**2 + height**2) / 18, m * foot**2 / 18])
    if link.name == "rudder":  # sheet: box 0.189 x 0.015 x 0.608 m
        a, b, c = 0.189, 0.015, 0.608
        return m / 12 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    return np.zeros((3, 3))


def composite(links) -> MassProperties:
    """Total mass, centre of mass and inertia about it of rigid links (parallel-axis theorem)."""
    masses = np.array([link.mass for link in links])
    centers = np.array([link.center_of_mass for link in links], dtype=np.float64)
    total = float(masses.sum())
    center = masses @ centers / total
    inertia = np.zeros((3, 3))
    for link, mass, position in zip(links, masses, centers):
        inertia += link_inertia(link) + parallel_axis_term(mass, position - center)
    return MassProperties(total, center, inertia)


def eboat_mass_properties(version: Version, links=LINKS) -> MassProperties:
    """The E-Boat of ``version`` from its ``links`` (default: the sheet's table, the procedural boat's; the
    real boat's: ``EBoatGeometry.links``), with V-A's lighter total taken off the hull link."""
    links = list(links)
    if version is Version.A:
        hull = next(i for i, link in enumerate(links) if link.name == "hull")
        links[hull] = dataclasses.replace(links[hull], mass=links[hull].mass + LINK_MASS_DIFFERENCE_V_A)
    return composite(links)
