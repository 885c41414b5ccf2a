"""Studies: one question each, answered with a table or a figure for RESULTS.md: the autopilot's mission,
hull fidelity at a triangle budget, the righting arm, tacking, the polar against the VPP, learning curves,
the seed's SB3 recipe, and the behaviour fingerprint that shows a refactor changed nothing. Run from the
repository root: ``python -m benchmarks.studies.<name> --help``."""
