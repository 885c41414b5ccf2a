"""The E-Boat's actions to its commands, one thread per boat: the kernel of its vessel face
(``ocean_warp.eboat.vessel``).

Actions are (N, 3) in [-1, 1] (clipped): a0 the propeller, level int(5 a0) truncated toward zero; a1 the sheet,
(a1 + 1) 45 deg; a2 the rudder, 60 deg a2, positive turning the boat to port. A column can be switched off
(``enabled[k] == 0``, e.g. the propeller of a task under sail alone): it then commands its neutral value (level 0;
sheet and rudder are never switched off by the tasks, but would go to 0 rad likewise).
"""

from __future__ import annotations

import warp as wp

__all__ = ["MAX_LEVEL", "RUDDER_LIMIT", "SHEET_HALF", "propeller_level", "commanded_level", "write_commands",
           "apply_eboat_actions"]

MAX_LEVEL = wp.constant(5)
"""The propeller's highest level (the seed's electric motor: -5 ... 5)."""
RUDDER_LIMIT = wp.constant(60.0 / (180.0 / 3.141592653589793))
"""The rudder command at a2 = 1 [rad] (the seed's 60 deg)."""
SHEET_HALF = wp.constant(45.0 / (180.0 / 3.141592653589793))
"""Half the sheet's range [rad]: a1 = -1 sheets in (0), a1 = 1 lets the boom out to 90 deg."""


@wp.func
def propeller_level(action: float) -> int:
    """int(5 a), truncated toward zero, of a clipped action."""
    return int(float(MAX_LEVEL) * wp.clamp(action, -1.0, 1.0))


@wp.func
def commanded_level(use_propeller: bool, action: float) -> int:
    """The propeller level commanded for a0 = ``action``: ``propeller_level(action)``, or 0 without the
    propeller (switched off)."""
    if use_propeller:
        return propeller_level(action)
    return 0


@wp.func
def write_commands(
    boat: int,
    use_propeller: bool,
    actions: wp.array2d(dtype=float),
    rudder: wp.array(dtype=float),
    sheet: wp.array(dtype=float),
    propeller: wp.array(dtype=int),
):
    """Boat ``boat``'s actions in [-1, 1] (clipped) to commands: propeller int(5 a0) (0 unless
    ``use_propeller``), sheet (a1 + 1) 45 deg [rad], rudder 60 deg a2 [rad]. A non-finite action (a0 too,
    even when ignored) becomes a NaN rudder command, which the simulator flags as bad input."""
    a0 = actions[boat, 0]
    a1 = actions[boat, 1]
    a2 = actions[boat, 2]
    if not (wp.isfinite(a0) and wp.isfinite(a1) and wp.isfinite(a2)):
        rudder[boat] = wp.nan
        propeller[boat] = 0
        return
    propeller[boat] = commanded_level(use_propeller, a0)
    sheet[boat] = (wp.clamp(a1, -1.0, 1.0) + 1.0) * SHEET_HALF
    rudder[boat] = RUDDER_LIMIT * wp.clamp(a2, -1.0, 1.0)


@wp.kernel(enable_backward=False)
def apply_eboat_actions(
    actions: wp.array2d(dtype=float),
    enabled: wp.array(dtype=wp.int32),
    rudder: wp.array(dtype=float),
    sheet: wp.array(dtype=float),
    propeller: wp.array(dtype=int),
):
    """Actions (N, 3) to commands (see ``write_commands``); ``enabled`` (3,): the propeller column is used only
    where ``enabled[0]`` is non-zero."""
    write_commands(wp.tid(), enabled[0] != 0, actions, rudder, sheet, propeller)
