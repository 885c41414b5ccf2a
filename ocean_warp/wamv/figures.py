"""The WAM-V's figures as VRX (github.com/osrf/vrx) and Bingham et al. (2019) give them, each with its source.

Bingham, Aguero, McCarrin et al., "Toward maritime robotic simulation in Gazebo", OCEANS 2019, describe the
16 ft WAM-V of the RobotX challenge and VRX's model of it; the numbers below are read from VRX's files (paths in
the osrf/vrx repository). The body frame is VRX's ``base_link`` turned into FLU (x to the bow, y to port, z up;
VRX's frames are FLU already): its origin lies midway between the pontoons' axes, at their height.
"""

from __future__ import annotations

__all__ = ["MASS", "INERTIA", "PONTOON_LENGTH", "PONTOON_RADIUS", "PONTOON_SPACING", "PONTOON_CENTER_X",
           "ENGINE_PIVOTS", "PROPELLER_OFFSET", "MAX_FORCE_FORWARD", "MAX_FORCE_REVERSE", "MAX_THRUSTER_ANGLE",
           "GLF_FORWARD", "GLF_REVERSE", "GLF_DEAD_BAND", "VRX_LINEAR_DAMPING", "VRX_QUADRATIC_DAMPING",
           "VRX_ADDED_MASS", "WIND_COEFFICIENTS", "GPS_MOUNT", "DECK_HEIGHT", "DECK_SIZE"]

MASS = 180.0
"""[kg] The base link's mass, "from WAM-V spec sheet" (``vrx_urdf/wamv_description/urdf/wamv_base.urdf.xacro``,
``<inertial><mass value="180.0"/>``; Bingham et al. 2019). The engines (15 kg and a 0.5 kg propeller each,
``vrx_urdf/wamv_description/urdf/thrusters/engine.xacro``) and the sensors are separate links in VRX and are
left out here."""
INERTIA = (120.0, 393.0, 446.0)
"""(Ixx, Iyy, Izz) [kg m^2] about the centre of mass, no products (``wamv_base.urdf.xacro``, ``<inertia ixx="120.0"
iyy="393" izz="446.0"/>``)."""
PONTOON_LENGTH = 4.9
"""[m] Each pontoon's length as VRX's buoyancy sees it (``vrx_urdf/wamv_gazebo/urdf/dynamics/
wamv_gazebo_dynamics_plugin.xacro``, ``<hull_length>4.9</hull_length>``); the 16 ft WAM-V is 4.88 m long."""
PONTOON_RADIUS = 0.213
"""[m] Each pontoon's radius (``wamv_gazebo_dynamics_plugin.xacro``, ``<hull_radius>0.213</hull_radius>``)."""
PONTOON_SPACING = 2.06
"""[m] Between the pontoons' axes: VRX's buoyancy points sit at y = +-1.03 m (``wamv_gazebo_dynamics_plugin.xacro``,
``<point>0.6 1.03 0</point>``...), the collision floats too (``wamv_base.urdf.xacro``, ``${1.03*reflect}``)."""
PONTOON_CENTER_X = -0.4
"""[m] Middle of each pontoon along x: the midpoint of VRX's two buoyancy points x = 0.6 and -1.4 m
(``wamv_gazebo_dynamics_plugin.xacro``), each carrying half of the 4.9 m hull; the main collision float is centred
there too (``wamv_base.urdf.xacro``, ``<origin xyz="-0.4 ...``)."""
ENGINE_PIVOTS = ((-2.373776, 1.027135, 0.318237), (-2.373776, -1.027135, 0.318237))
"""[m] (left, right) engine joints, the azimuth pivots (``vrx_urdf/wamv_gazebo/urdf/thruster_layouts/
wamv_aft_thrusters.xacro``, ``<xacro:engine prefix="left" position="-2.373776 1.027135 0.318237" />``)."""
PROPELLER_OFFSET = (-0.278156, 0.0, -0.509371)
"""[m] The propeller from its engine's pivot, in the engine's frame (``engine.xacro``, the
``engine_propeller_joint``'s ``<origin xyz="-0.278156 0 -0.509371"/>``); the thrust acts there."""
MAX_FORCE_FORWARD = 250.0
"""[N] ``maxForceFwd`` of each thruster (``wamv_gazebo/urdf/thruster_layouts/wamv_gazebo_thruster_config.xacro``,
classic VRX; the GLF mapping below peaks at 242.6 N, under it)."""
MAX_FORCE_REVERSE = 100.0
"""[N] magnitude of ``maxForceRev`` = -100 (same file)."""
MAX_THRUSTER_ANGLE = 1.5707963267948966
"""[rad] ``maxAngle`` = pi / 2 of each thruster (same file)."""
GLF_FORWARD = (0.01, 59.82, 5.0, 0.38, 0.56, 0.28)
"""(A, K, B, nu, C, M) of the generalised logistic function T(c) = A + (K - A) / (C + exp(-B (c - M)))^(1 / nu)
[N] for commands c > 0.01 (``usv_gazebo_plugins/src/usv_gazebo_thrust_plugin.cc``, ``GlfThrustCmd``, the
``mappingType`` 1 that ``wamv_gazebo_thruster_config.xacro`` selects: a fit of the WAM-V's trolling motors)."""
GLF_REVERSE = (-199.13, -0.09, 8.84, 5.34, 0.99, -0.57)
"""The same for commands c < 0.01 (same function)."""
GLF_DEAD_BAND = 0.01
"""The command at which the plugin switches between the two curves (exactly 0.01 gives no thrust)."""
VRX_LINEAR_DAMPING = (51.3, 40.0, 500.0, 100.0, 100.0, 400.0)
"""(xU, yV, zW, kP, mQ, nR) [N s/m, N m s/rad] (``vrx_urdf/wamv_gazebo/urdf/dynamics/
wamv_gazebo_dynamics_plugin.xacro``, the ``vrx::SimpleHydrodynamics`` plugin)."""
VRX_QUADRATIC_DAMPING = (72.4, 0.0, 0.0, 0.0, 0.0, 0.0)
"""(xUU, yVV, -, -, -, nRR) [N s^2/m^2, N m s^2/rad^2] (same plugin: xUU 72.4, yVV 0, nRR 0)."""
VRX_ADDED_MASS = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
"""(xDotU, yDotV, -, -, -, nDotR) [kg, kg m^2] (same plugin: all 0)."""
WIND_COEFFICIENTS = (0.5, 0.5, 0.33)
"""VRX's wind law on the WAM-V, (c_x, c_y [N s^2/m^2], c_z [N m s^2/m^2]): ``<coeff_vector>.5 .5 .33`` of the
``vrx::USVWind`` plugin's ``wamv`` wind object in VRX's worlds (``vrx_gz/worlds/sydney_regatta.sdf``; the law in
``vrx_gazebo``'s ``usv_gazebo_wind_plugin.cc``)."""
GPS_MOUNT = (-0.85, 0.0, 1.3)
"""[m] The GPS antenna: x = -0.85 (``wamv_gazebo/urdf/wamv_gazebo.urdf.xacro``, ``<xacro:wamv_gps name="gps_wamv"
x="-0.85" />``), y and z the macro's defaults 0 and 1.3 (``vrx_urdf/wamv_gazebo/urdf/components/wamv_gps.xacro``)."""
DECK_HEIGHT = 1.25
"""[m] Height of the top plate (``wamv_base.urdf.xacro``, collision ``top_base`` at z = 1.25)."""
DECK_SIZE = (1.85, 1.0, 0.1)
"""[m] Its box (same collision, ``<box size="1.85 1 0.1" />``)."""
