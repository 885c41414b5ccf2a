"""How fast a stage plays: its default time codes per second (light to import: no ``pxr``, so the
command line's parsers show it)."""

TIME_CODES_PER_SECOND = 24.0
"""Default time codes (and frames) per second of a stage: Blender's default frame rate, so it plays the
stage in real time."""
