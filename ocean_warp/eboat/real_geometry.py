"""The real E-Boat's appendages and sail, measured from the seed team's CAD: the figures of the sheet's section
"The real geometry, measured from the CAD (2026-11-27)" and of the measurements beside it
(``shared/eboat/vpp_inputs_real.json``, "measured"), in the URDF's base frame [m] (x to the bow, z up; the
waterline at rest at z +0.094, ``offsets_hull.BASE_TO_WATERLINE``). Where neither gives a figure, the value
here is an assumption and says so.
"""

from __future__ import annotations

__all__ = ["KEEL_CHORD", "KEEL_THICKNESS_RATIO", "KEEL_SPAN", "KEEL_LEADING_EDGE_X", "KEEL_QUARTER_CHORD_X",
           "KEEL_JOINT_X", "KEEL_ROOT_Z", "BULB_SIZE", "BULB_CENTER", "KEEL_VOLUME", "KEEL_VOLUME_CENTER",
           "FIN_VOLUME", "BULB_VOLUME", "RUDDER_AREA", "RUDDER_SPAN", "RUDDER_ROOT_CHORD", "RUDDER_TIP_CHORD",
           "RUDDER_STOCK_X", "RUDDER_CENTROID_Z", "RUDDER_THICKNESS_RATIO", "RUDDER_VOLUME", "RUDDER_VOLUME_CENTER",
           "SAIL_AREA", "SAIL_CENTROID_Z", "SAIL_FOOT_Z", "SAIL_HEAD_Z", "SAIL_FOOT_LENGTH", "SAIL_HEAD_LENGTH",
           "DECK_Z", "MAST_TOP_ABOVE_STEP", "LEAD_BULB_MASS", "GRP_DENSITY"]

# Keel: a constant-chord fin with a bulb at its tip.
KEEL_CHORD = 0.235
"""Sheet, real geometry: constant-chord fin 0.235 m."""
KEEL_THICKNESS_RATIO = 0.106
"""Sheet, real geometry: fin t/c 0.106."""
KEEL_SPAN = 0.74
"""Sheet, real geometry: 0.74 m of span outside the hull."""
KEEL_LEADING_EDGE_X = -0.022
"""Sheet, real geometry: the fin's leading edge at x_b -0.022."""
KEEL_QUARTER_CHORD_X = -0.081
"""Sheet, real geometry: the fin's quarter chord at x_b -0.081 (where its lift acts)."""
KEEL_JOINT_X = -0.140
"""Sheet, real geometry: the keel joint (mid-chord) at x_b -0.140."""
KEEL_ROOT_Z = -0.0215
"""Where the fin leaves the hull, z_b [m] (vpp_inputs_real.json, measured: fin_root_z -0.02154)."""
BULB_SIZE = (0.459, 0.124, 0.122)
"""Sheet, real geometry: the bulb is 0.459 x 0.124 x 0.122 m (length, width, height)."""
BULB_CENTER = (KEEL_JOINT_X, 0.0, -0.825)
"""Sheet, real geometry: the bulb centred at z_b -0.825; fore and aft under the keel joint (assumed; the CAD's
keel volume centroid puts it within 1 cm of there)."""
KEEL_VOLUME = 0.0075356
"""Fin and bulb outside the hull [m^3]: sheet, real geometry "7.5 L outside the hull" (vpp_inputs_real.json,
measured: V_keel_out 0.0075356)."""
KEEL_VOLUME_CENTER = (-0.13454, 0.0, -0.61850)
"""Centroid of that volume [m] (vpp_inputs_real.json, measured: keel_out_centroid)."""
FIN_VOLUME = 0.0036277
"""The fin's part of it [m^3] (vpp_inputs_real.json, measured: fin_V)."""
BULB_VOLUME = 0.0039080
"""The bulb's part [m^3]: sheet, real geometry "3.9 L" (vpp_inputs_real.json, measured: bulb_V)."""

# Rudder: a tapered blade on a stock near mid-chord, below the hull near the transom.
RUDDER_AREA = 0.0991
"""Sheet, real geometry: 0.0991 m^2 below the hull."""
RUDDER_SPAN = 0.617
"""Sheet, real geometry: span 0.617 m."""
RUDDER_ROOT_CHORD, RUDDER_TIP_CHORD = 0.170, 0.145
"""Sheet, real geometry: chord 0.170 m at the root to 0.145 m at the tip."""
RUDDER_STOCK_X = -1.086
"""Sheet, real geometry: the stock at x_b -1.086, near mid-chord (taken at mid-chord)."""
RUDDER_CENTROID_Z = -0.237
"""Sheet, real geometry: the blade's area centroid at z_b -0.237."""
RUDDER_THICKNESS_RATIO = 0.063
"""t/c of the rudder's section (vpp_inputs_real.json, rudder: Tc_ratio 0.063)."""
RUDDER_VOLUME = 0.00075860
"""The blade's volume below the hull [m^3] (vpp_inputs_real.json, measured: V_rud_out)."""
RUDDER_VOLUME_CENTER = (-1.09279, 0.0, -0.23902)
"""Its centroid [m] (vpp_inputs_real.json, measured: rud_out_centroid)."""

# Sail and rig.
SAIL_AREA = 3.188
"""Sheet: 3.188 m^2."""
SAIL_CENTROID_Z = 2.15
"""Sheet, real geometry: the sail's centroid at z_b 2.15 m."""
SAIL_FOOT_Z, SAIL_HEAD_Z = 1.0466, 3.6366
"""Heights of the sail's foot and head, z_b [m] (vpp_inputs_real.json, measured: foot_z, head_z; luff 2.59 m)."""
SAIL_FOOT_LENGTH, SAIL_HEAD_LENGTH = 1.776, 0.686
"""Length of the foot and width of the head aft of the luff [m] (vpp_inputs_real.json, measured: foot_width,
head_width): a trapezoid of 3.19 m^2 with its centroid 1.104 m above the foot, at z_b 2.150."""
DECK_Z = 0.40996
"""The sheer (deck edge), z_b [m]: the offsets table's z = 0 (sheet: z_b = z + 0.40996)."""
MAST_TOP_ABOVE_STEP = 3.765
"""The masthead (wind vane and top camera joints) above the mast joint [m] (URDF: biruta_joint and
camera_top_joint at z 3.765 of mast_link)."""

# An alternative keel, assumed.
LEAD_BULB_MASS = 44.0
"""Sheet, real geometry: "a lead bulb (44 kg) on a GRP fin" (the bulb's 3.9 L of lead): a labelled assumption,
not a fact."""
GRP_DENSITY = 1900.0
"""Glass-reinforced plastic of a solid fin [kg/m^3] (assumed)."""
