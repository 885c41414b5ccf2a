"""USD export: record a simulation into a stage (ocean surface, any vessel's boats with their moving parts,
route, wind, with UsdPreviewSurface materials, a camera and lights), write a seamless loop of an ocean, check
a stage with USD's validators and draw a preview PNG of it.

Example::

    from ocean_warp.usd import RouteDrawing, StageRecorder, record_vessel, render_preview, validate_stage

    sim = vessel.simulator(16)                     # vessel: EBoatVessel(config), Wamv()... (ocean_warp.vessel)
    with StageRecorder.for_vessel("out/run.usdc", vessel, sim, fps=5.0, route=RouteDrawing(waypoints)) as recorder:
        for step in range(1200):
            if step % 4 == 0:                      # dt 0.05 s: 5 frames per second of simulated time
                record_vessel(recorder, sim)
            sim.step()
    assert validate_stage("out/run.usdc") == []
    render_preview("out/run.usdc")                 # out/run.png

Stages are Z up, 1 metre per unit, with timeCodesPerSecond = framesPerSecond = ``time_codes_per_second``
(default 24; time code = time [s] x that), so they play in real time whatever ``fps`` they were recorded
at. What a recorder draws is given in option groups (:mod:`ocean_warp.usd.stage_options`):
``OceanDrawing``, ``FleetDrawing``, ``RouteDrawing`` and ``WindArrow``. The prim layout and model kinds are
in :mod:`ocean_warp.usd.paths`. Each name here imports ``pxr`` (usd-core) on first use, not before.
"""

from ocean_warp.lazy_names import lazy_attributes

# Each public name and its module, imported on first use (PEP 562): a light module of this package
# (``playback``) loads without ``pxr``.
_PUBLIC = {
    "OceanLattice": "ocean_mesh",
    "render_preview": "preview", "INSTANCING_THRESHOLD": "recorder", "TIME_CODES_PER_SECOND": "playback",
    "StageRecorder": "recorder", "loop_path_for": "recorder", "record_vessel": "recorder",
    "write_ocean_loop": "recorder", "check_stage_path": "stage_file", "FleetDrawing": "stage_options",
    "OceanDrawing": "stage_options", "RouteDrawing": "stage_options", "WindArrow": "stage_options",
    "validate_stage": "stage_validation",
}

__all__ = ["StageRecorder", "record_vessel", "write_ocean_loop", "validate_stage", "render_preview",
           "OceanLattice", "INSTANCING_THRESHOLD", "TIME_CODES_PER_SECOND",
           "loop_path_for", "check_stage_path", "OceanDrawing", "FleetDrawing", "RouteDrawing", "WindArrow"]

__getattr__, __dir__ = lazy_attributes(__name__, _PUBLIC)
