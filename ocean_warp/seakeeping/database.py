"""A hull's hydrodynamic database: potential-flow added mass and damping over frequency, the infinite-frequency
added mass, state-space fits of the radiation memory, and optionally the wave excitation and the diffraction
weights of the wave points; as a small JSON file.

Every matrix is about the body origin (the point (0, 0, 0) of the hull mesh, which floats ``rest_height`` above
still water, upright) in body axes (FLU: x to the bow, y to port, z up), degrees of freedom in the order surge,
sway, heave, roll, pitch, yaw; units kg, kg m, kg m^2 for added mass and N s/m, N s, N m s for damping. The
radiation memory force of Cummins' equation is mu = sum over terms of c x with dx/dt = a x + b nu[col]: the
water pushes the hull with -mu (see :mod:`ocean_warp.seakeeping.radiation_fit`).

``ocean-warp bem`` computes a database (:mod:`ocean_warp.seakeeping.bem`); :meth:`HydroDatabase.load` reads one
and refuses, in one line naming the file, anything it cannot trust.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import warnings

import numpy as np

from ..atomic_files import atomic_output
from .diffraction_weights import DiffractionWeights

__all__ = ["FORMAT_VERSION", "RadiationTerm", "HydroDatabase", "hull_fingerprint", "database_for",
           "NoHydroDatabaseWarning"]

FORMAT_VERSION = 2
"""The version of the file format this module writes and reads (2: the diffraction weights)."""
FORMAT_NAME = "ocean_warp hydrodynamic database"
MAX_TERM_ORDER = 12
"""The most states one radiation term may have."""
_SIGNIFICANT_DIGITS = 7
"""Digits kept of the BEM's coefficients in the file (the BEM is good to a few per cent)."""


class NoHydroDatabaseWarning(UserWarning):
    """A hull sails without a hydrodynamic database: constant added mass, drag-only damping."""


def hull_fingerprint(hull) -> str:
    """The sha256 (hex) of ``hull``'s mesh (an :class:`ocean_warp.Hull`): its vertices rounded to 1e-6 m and its
    triangles, so that a database is used only with the mesh it was computed for."""
    vertices = np.rint(np.asarray(hull.vertices, dtype=np.float64) * 1e6).astype("<i8")
    triangles = np.asarray(hull.triangles).astype("<i8")
    digest = hashlib.sha256()
    digest.update(f"{vertices.shape} {triangles.shape}".encode())
    digest.update(vertices.tobytes())
    digest.update(triangles.tobytes())
    return digest.hexdigest()


def _frozen_array(value, dtype=np.float64) -> np.ndarray:
    array = np.array(value, dtype=dtype)
    array.flags.writeable = False
    return array


@dataclasses.dataclass(frozen=True)
class RadiationTerm:
    """One SISO state-space block of the radiation memory: mu[row] += c x, dx/dt = a x + b nu[col] (D = 0)."""

    row: int
    """DOF the force acts in, 0..5 (surge, sway, heave, roll, pitch, yaw)."""
    col: int
    """DOF whose velocity drives it, 0..5."""
    a: np.ndarray
    """(m, m) [1/s], every eigenvalue with a negative real part."""
    b: np.ndarray
    """(m,)."""
    c: np.ndarray
    """(m,): c (jw I - a)^-1 b is the kernel K[row, col](jw), in the units of damping[:, row, col]."""
    fit_error: float = math.nan
    """RMS of |K_fit - K| over the fitted frequencies relative to the RMS of |K| (NaN: not recorded)."""

    def __post_init__(self):
        for name in ("a", "b", "c"):
            object.__setattr__(self, name, _frozen_array(getattr(self, name)))
        object.__setattr__(self, "fit_error", float(self.fit_error))
        problem = _term_problem(self)
        if problem is not None:
            raise ValueError(f"RadiationTerm: {problem}")

    @property
    def order(self) -> int:
        return len(self.b)

    def response(self, omega) -> np.ndarray:
        """(F,) complex c (jw I - a)^-1 b at ``omega`` (F,) [rad/s]."""
        w = np.atleast_1d(np.asarray(omega, dtype=np.float64))
        resolvent = 1j * w[:, None, None] * np.eye(self.order)[None] - self.a[None]
        rhs = np.broadcast_to(self.b, (len(w), self.order))[..., None]
        return np.linalg.solve(resolvent, rhs)[..., 0] @ self.c


def _term_problem(term: RadiationTerm) -> str | None:
    """What is wrong with ``term`` in words, or None."""
    for name in ("row", "col"):
        value = getattr(term, name)
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 0 <= value <= 5:
            return f"{name} must be a DOF index 0..5, got {value!r}"
    m = term.b.shape[0] if term.b.ndim == 1 else -1
    if not (1 <= m <= MAX_TERM_ORDER and term.a.shape == (m, m) and term.c.shape == (m,)):
        return (f"term ({term.row}, {term.col}) must have a (m, m), b (m,) and c (m,) with 1 <= m <= "
                f"{MAX_TERM_ORDER}, got {term.a.shape}, {term.b.shape}, {term.c.shape}")
    if not all(np.all(np.isfinite(v)) for v in (term.a, term.b, term.c)):
        return f"term ({term.row}, {term.col}) has NaN or infinite values in a, b or c"
    growth = float(np.max(np.linalg.eigvals(term.a).real))
    if not growth < 0.0:
        return (f"term ({term.row}, {term.col}) is not stable: an eigenvalue of a has real part {growth:.6g} 1/s "
                "(must be < 0)")
    return None


@dataclasses.dataclass(frozen=True)
class HydroDatabase:
    """A hull's potential-flow coefficients at zero speed in deep water, about its body origin at its rest pose
    (see the module's docstring for frames and units). Invalid values raise ``ValueError``."""

    hull_name: str
    hull_fingerprint: str
    """:func:`hull_fingerprint` of the hull the BEM ran on."""
    water_density: float
    """rho of the run [kg/m^3]."""
    gravity: float
    """g of the run [m/s^2]."""
    rest_height: float
    """Height [m] of the body origin above still water at which the hull was cut (upright, at rest)."""
    frequencies: np.ndarray
    """(F,) [rad/s], increasing."""
    added_mass: np.ndarray
    """(F, 6, 6) A(w) [kg, kg m, kg m^2]."""
    damping: np.ndarray
    """(F, 6, 6) B(w) [N s/m, N s, N m s]."""
    added_mass_infinite: np.ndarray
    """(6, 6) A_inf, symmetric and positive semi-definite."""
    radiation: tuple
    """:class:`RadiationTerm` per fitted (row, col); the kernels not listed are taken as zero."""
    excitation_headings: np.ndarray | None = None
    """(H,) wave headings [rad] of ``excitation``: the direction the waves travel, counter-clockwise from the
    bow (180 deg: head seas, travelling toward -x; 90 deg: beam seas travelling toward +y, from starboard)."""
    excitation: np.ndarray | None = None
    """(F, H, 6) complex wave force per metre of wave amplitude [N/m, N m/m] (Froude-Krylov and diffraction),
    phase against the wave's elevation at the body origin: the force is Re(X e^(i w t)) for the elevation
    Re(e^(i w t)) there."""
    diffraction: DiffractionWeights | None = None
    """How the hull pass turns its wave points' readings into the effective water velocity of the diffraction load
    (:mod:`ocean_warp.seakeeping.wave_points`; None: the rigid-motion fit of the velocities)."""
    provenance: dict = dataclasses.field(default_factory=dict)
    """How it was computed (tool versions, panels, settings), strings and numbers; informative only."""

    def __post_init__(self):
        object.__setattr__(self, "hull_name", str(self.hull_name))
        for name in ("frequencies", "added_mass", "damping", "added_mass_infinite"):
            object.__setattr__(self, name, _frozen_array(getattr(self, name)))
        if self.excitation is not None:
            object.__setattr__(self, "excitation", _frozen_array(self.excitation, np.complex128))
        if self.excitation_headings is not None:
            object.__setattr__(self, "excitation_headings", _frozen_array(self.excitation_headings))
        object.__setattr__(self, "radiation", tuple(self.radiation))
        object.__setattr__(self, "provenance", dict(self.provenance))
        problem = _database_problem(self)
        if problem is not None:
            raise ValueError(f"HydroDatabase: {problem}")

    # --- the radiation model ----------------------------------------------------------------------------
    def radiation_force_response(self, omega) -> np.ndarray:
        """(len(omega), 6, 6) complex: the fitted kernels K(jw) = C (jw I - A)^-1 B at ``omega`` [rad/s] (zero
        where no term is fitted), to compare with B(w) + jw (A(w) - A_inf)."""
        w = np.atleast_1d(np.asarray(omega, dtype=np.float64))
        response = np.zeros((len(w), 6, 6), dtype=np.complex128)
        for term in self.radiation:
            response[:, term.row, term.col] += term.response(w)
        return response

    def kernels(self) -> np.ndarray:
        """(F, 6, 6) complex K(jw) = B(w) + jw (A(w) - A_inf) at the database's frequencies: what the fits
        approximate."""
        w = self.frequencies[:, None, None]
        return self.damping + 1j * w * (self.added_mass - self.added_mass_infinite[None])

    def stacked_state_space(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every term as one block-diagonal system: (A (n, n), B (n, 6), C (6, n)) with dx/dt = A x + B nu and
        mu = C x, n the total state count."""
        n = sum(term.order for term in self.radiation)
        a, b, c = np.zeros((n, n)), np.zeros((n, 6)), np.zeros((6, n))
        start = 0
        for term in self.radiation:
            end = start + term.order
            a[start:end, start:end] = term.a
            b[start:end, term.col] = term.b
            c[term.row, start:end] = term.c
            start = end
        return a, b, c

    # --- files ----------------------------------------------------------------------------------------------
    def to_json(self) -> dict:
        """The file's content as a JSON-able dict."""
        data = {
            "format": FORMAT_NAME, "format_version": FORMAT_VERSION,
            "hull_name": self.hull_name, "hull_fingerprint": self.hull_fingerprint,
            "water_density": self.water_density, "gravity": self.gravity, "rest_height": self.rest_height,
            "dofs": ["surge", "sway", "heave", "roll", "pitch", "yaw"],
            "frequencies": _rounded(self.frequencies), "added_mass": _rounded(self.added_mass),
            "damping": _rounded(self.damping), "added_mass_infinite": _rounded(self.added_mass_infinite),
            "radiation": [{"row": int(t.row), "col": int(t.col), "a": t.a.tolist(), "b": t.b.tolist(),
                           "c": t.c.tolist(), "fit_error": None if math.isnan(t.fit_error) else t.fit_error}
                          for t in self.radiation],
        }
        if self.excitation is not None:
            data["excitation"] = {"headings_deg": np.degrees(self.excitation_headings).tolist(),
                                  "real": _rounded(self.excitation.real), "imag": _rounded(self.excitation.imag)}
        if self.diffraction is not None:
            data["diffraction"] = self.diffraction.to_json()
        data["provenance"] = self.provenance
        return data

    def save(self, path: str | os.PathLike) -> None:
        """Write the database to ``path`` (JSON, kilobytes), atomically: a reader sees the old file or the new."""
        text = _json_text(self.to_json())
        with atomic_output(path, suffix=".json") as temporary, open(temporary, "w", encoding="utf-8") as handle:
            handle.write(text)

    @classmethod
    def from_json(cls, data, source: str = "hydrodynamic database") -> "HydroDatabase":
        """A database from a dict as :meth:`to_json` makes; any problem is one ``ValueError`` line that begins
        with ``source``."""
        try:
            return _parse(cls, data)
        except (ValueError, TypeError, KeyError, IndexError) as error:
            message = error.args[0] if isinstance(error, ValueError) and error.args else _describe(error)
            message = str(message).removeprefix("HydroDatabase: ").removeprefix("RadiationTerm: ")
            raise ValueError(f"{source}: {message}") from None

    @classmethod
    def load(cls, path: str | os.PathLike, hull=None) -> "HydroDatabase":
        """Read and check the database at ``path``: its format version, shapes, finite values, a symmetric and
        positive semi-definite A_inf, stable fits; with ``hull`` (an :class:`ocean_warp.Hull`), that it was
        computed for that mesh. Any problem is one ``ValueError`` line naming the file."""
        path = os.fspath(path)
        source = f"hydrodynamic database {path}"
        try:
            with open(path, encoding="utf-8") as handle:
                data = json.load(handle)
        except FileNotFoundError:
            raise ValueError(f"{source}: no such file") from None
        except IsADirectoryError:
            raise ValueError(f"{source}: is a folder, not a file") from None
        except (UnicodeDecodeError, json.JSONDecodeError) as error:
            raise ValueError(f"{source}: not JSON ({error})") from None
        except OSError as error:
            raise ValueError(f"{source}: cannot be read ({error.strerror or error})") from None
        database = cls.from_json(data, source)
        if hull is not None:
            database.check_hull(hull, source)
        return database

    def check_hull(self, hull, source: str = "hydrodynamic database") -> None:
        """Raise ``ValueError`` unless this database was computed for ``hull``'s mesh."""
        fingerprint = hull_fingerprint(hull)
        if fingerprint == self.hull_fingerprint:
            return
        if hull.name == self.hull_name:
            raise ValueError(f"{source}: was computed for another mesh of hull {self.hull_name!r} (fingerprint "
                             f"{self.hull_fingerprint[:12]}..., this one's {fingerprint[:12]}...); recompute it "
                             "with ocean-warp bem")
        raise ValueError(f"{source}: was computed for hull {self.hull_name!r}, not {hull.name!r} (fingerprints "
                         f"{self.hull_fingerprint[:12]}... and {fingerprint[:12]}...)")


def _rounded(array: np.ndarray):
    """Nested lists of ``array``'s values to ``_SIGNIFICANT_DIGITS`` digits."""
    return np.vectorize(lambda v: float(f"{v:.{_SIGNIFICANT_DIGITS}g}"), otypes=[float])(array).tolist()


def _json_text(data: dict) -> str:
    """JSON with one top-level key a line (arrays compact), so that the file reads and diffs by field."""
    lines = [f"  {json.dumps(key)}: {json.dumps(value, separators=(',', ':'), allow_nan=False)}"
             for key, value in data.items()]
    return "{\n" + ",\n".join(lines) + "\n}\n"


def _describe(error: Exception) -> str:
    if isinstance(error, KeyError):
        return f"missing field {error.args[0]!r}"
    return f"malformed content ({error})"


def _number(data: dict, key: str) -> float:
    value = data[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{key} must be a number, got {value!r}")
    return float(value)


def _array(data: dict, key: str, shape: tuple, within: str = "") -> np.ndarray:
    """``data[key]`` as a float array of ``shape`` (-1: any length); a ValueError naming the field (``within``
    the object that holds it) otherwise."""
    name = f"{within}.{key}" if within else key
    if key not in data:
        raise ValueError(f"missing field {name!r}")
    try:
        array = np.array(data[key], dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of numbers") from None
    expected = tuple(array.shape[i] if size == -1 and i < array.ndim else size for i, size in enumerate(shape))
    if array.shape != expected:
        raise ValueError(f"{name} must have shape {tuple('n' if s == -1 else s for s in shape)}, got {array.shape}")
    return array


def _parse(cls, data) -> HydroDatabase:
    if not isinstance(data, dict) or data.get("format") != FORMAT_NAME:
        raise ValueError(f"not an {FORMAT_NAME} (no \"format\": \"{FORMAT_NAME}\" field)")
    version = data.get("format_version")
    if version != FORMAT_VERSION:
        newer = isinstance(version, int) and not isinstance(version, bool) and version > FORMAT_VERSION
        raise ValueError(f"format version {version!r} is not {FORMAT_VERSION}, the one this ocean_warp reads"
                         + ("; it was written by a newer ocean_warp" if newer else ""))
    frequencies = _array(data, "frequencies", (-1,))
    count = len(frequencies)
    terms = data["radiation"]
    if not isinstance(terms, list):
        raise ValueError("radiation must be a list of terms")
    radiation = []
    for index, term in enumerate(terms):
        if not isinstance(term, dict):
            raise ValueError(f"radiation[{index}] must be an object with row, col, a, b, c")
        error = term.get("fit_error")
        within = f"radiation[{index}]"
        radiation.append(RadiationTerm(row=term.get("row"), col=term.get("col"), a=_array(term, "a", (-1, -1), within),
                                       b=_array(term, "b", (-1,), within), c=_array(term, "c", (-1,), within),
                                       fit_error=math.nan if error is None else error))
    headings = excitation = None
    if data.get("excitation") is not None:
        wave = data["excitation"]
        if not isinstance(wave, dict):
            raise ValueError("excitation must be an object with headings_deg, real and imag")
        headings = np.radians(_array(wave, "headings_deg", (-1,), "excitation"))
        shape = (count, len(headings), 6)
        excitation = _array(wave, "real", shape, "excitation") + 1j * _array(wave, "imag", shape, "excitation")
    diffraction = None if data.get("diffraction") is None else DiffractionWeights.from_json(data["diffraction"])
    provenance = data.get("provenance", {})
    if not isinstance(provenance, dict):
        raise ValueError("provenance must be an object")
    return cls(hull_name=str(data["hull_name"]), hull_fingerprint=data["hull_fingerprint"],
               water_density=_number(data, "water_density"), gravity=_number(data, "gravity"),
               rest_height=_number(data, "rest_height"), frequencies=frequencies,
               added_mass=_array(data, "added_mass", (count, 6, 6)), damping=_array(data, "damping", (count, 6, 6)),
               added_mass_infinite=_array(data, "added_mass_infinite", (6, 6)), radiation=tuple(radiation),
               excitation_headings=headings, excitation=excitation, diffraction=diffraction, provenance=provenance)


def _database_problem(db: HydroDatabase) -> str | None:
    """What is wrong with ``db`` in words, or None."""
    fingerprint = db.hull_fingerprint
    if not (isinstance(fingerprint, str) and len(fingerprint) == 64
            and all(ch in "0123456789abcdef" for ch in fingerprint)):
        return f"hull_fingerprint must be a sha256 in hex (64 characters), got {fingerprint!r}"
    for name, unit in (("water_density", "kg/m^3"), ("gravity", "m/s^2")):
        value = getattr(db, name)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value > 0):
            return f"{name} must be a finite number > 0 [{unit}], got {value!r}"
    if isinstance(db.rest_height, bool) or not isinstance(db.rest_height, (int, float)) \
            or not math.isfinite(db.rest_height):
        return f"rest_height must be a finite number [m], got {db.rest_height!r}"
    w = db.frequencies
    if w.ndim != 1 or len(w) < 2:
        return f"frequencies must have shape (F >= 2,), got {w.shape}"
    if not (np.all(np.isfinite(w)) and w[0] > 0 and np.all(np.diff(w) > 0)):
        return "frequencies must be finite, > 0 and increasing [rad/s]"
    for name in ("added_mass", "damping"):
        array = getattr(db, name)
        if array.shape != (len(w), 6, 6):
            return f"{name} must have shape ({len(w)}, 6, 6), got {array.shape}"
        bad = ~np.isfinite(array)
        if bad.any():
            index = np.argwhere(bad)[0]
            return (f"{name} has {int(bad.sum())} NaN or infinite values (first at frequency {w[index[0]]:.4g} "
                    f"rad/s, row {index[1]}, col {index[2]})")
    problem = _added_mass_infinite_problem(db.added_mass_infinite)
    if problem is not None:
        return problem
    seen = set()
    for term in db.radiation:
        if not isinstance(term, RadiationTerm):
            return f"radiation must hold RadiationTerm, got {type(term).__name__}"
        if (term.row, term.col) in seen:
            return f"radiation has two terms for ({term.row}, {term.col})"
        seen.add((term.row, term.col))
    if (db.excitation is None) != (db.excitation_headings is None):
        return "excitation and excitation_headings must be given together"
    if db.excitation is not None:
        headings = db.excitation_headings
        if headings.ndim != 1 or len(headings) == 0 or not np.all(np.isfinite(headings)):
            return f"excitation_headings must be (H >= 1,) finite angles [rad], got shape {headings.shape}"
        if db.excitation.shape != (len(w), len(headings), 6):
            return f"excitation must have shape ({len(w)}, {len(headings)}, 6), got {db.excitation.shape}"
        if not np.all(np.isfinite(db.excitation)):
            return "excitation has NaN or infinite values"
    if db.diffraction is not None and not isinstance(db.diffraction, DiffractionWeights):
        return f"diffraction must be a DiffractionWeights or None, got {type(db.diffraction).__name__}"
    return None


def _added_mass_infinite_problem(matrix: np.ndarray) -> str | None:
    if matrix.shape != (6, 6):
        return f"added_mass_infinite must have shape (6, 6), got {matrix.shape}"
    if not np.all(np.isfinite(matrix)):
        return "added_mass_infinite has NaN or infinite values"
    diagonal = np.diag(matrix)
    if np.any(diagonal < 0):
        i = int(np.argmin(diagonal))
        return f"added_mass_infinite is not positive: its diagonal term {i} is {diagonal[i]:.6g}"
    # Compare entries of mixed units (kg, kg m, kg m^2) through the scaled matrix A_ij / sqrt(A_ii A_jj).
    root = np.sqrt(np.maximum(diagonal, 1e-12 * max(diagonal.max(), 1e-300)))
    scaled = matrix / np.outer(root, root)
    asymmetry = float(np.max(np.abs(scaled - scaled.T)))
    if asymmetry > 1e-6:
        i, j = np.unravel_index(np.argmax(np.abs(scaled - scaled.T)), scaled.shape)
        return (f"added_mass_infinite is not symmetric: [{i}, {j}] = {matrix[i, j]:.6g} but [{j}, {i}] = "
                f"{matrix[j, i]:.6g}")
    smallest = float(np.linalg.eigvalsh(0.5 * (scaled + scaled.T)).min())
    if smallest < -1e-6:
        return ("added_mass_infinite is not positive semi-definite: the smallest eigenvalue of A_ij / sqrt(A_ii A_jj) "
                f"is {smallest:.6g}")
    return None


def database_for(hull, path: str | os.PathLike | None) -> HydroDatabase | None:
    """The database at ``path`` checked against ``hull`` (:meth:`HydroDatabase.load`); with ``path`` None, None and
    a :class:`NoHydroDatabaseWarning` that the hull falls back to its constant added mass and drag-only damping."""
    if path is None:
        warnings.warn(f"hull {hull.name!r} has no hydrodynamic database: it keeps its constant added mass and "
                      "drag-only damping (no radiation memory); ocean-warp bem computes one",
                      NoHydroDatabaseWarning, stacklevel=2)
        return None
    return HydroDatabase.load(path, hull=hull)
