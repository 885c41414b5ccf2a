"""CI's check of a non-editable install (run by .ci/check_wheel from outside the source tree): the package
imports from site-packages, every non-Python file of the source's packages was installed, and the package's own
loaders read every shipped policy and data file.

    python wheel_smoke.py SOURCE_ROOT
"""

import pathlib
import sys

import ocean_warp
from ocean_warp.eboat.eboat import load_foil_table
from ocean_warp.eboat.offsets_hull import load_hull_offsets
from ocean_warp.envs.training.policies import SHIPPED_POLICIES, shipped_policy_path
from ocean_warp.envs.training.policy_io import load_policy
from ocean_warp.seakeeping import eboat_hydro_database

source = pathlib.Path(sys.argv[1]).resolve()
installed = pathlib.Path(ocean_warp.__file__).resolve().parent
if source in installed.parents or "site-packages" not in installed.parts:
    sys.exit(f"wheel smoke: ocean_warp was imported from {installed}, not from the installed wheel")

# the installer maps the top-level kernels/ and envs/ under ocean_warp (pyproject's package-dir)
folders = {"ocean_warp": installed, "kernels": installed / "kernels", "envs": installed / "envs"}
missing = [f"{top}/{path.relative_to(source / top)}" for top, target in folders.items()
           for path in sorted((source / top).rglob("*"))
           if path.is_file() and path.suffix not in (".py", ".pyc")
           and not (target / path.relative_to(source / top)).is_file()]
if missing:
    sys.exit(f"wheel smoke: files of the source's packages the wheel did not install: {', '.join(missing)}")

table = load_foil_table()
offsets = load_hull_offsets()
hydrodynamics = eboat_hydro_database()
for task in SHIPPED_POLICIES:
    path = shipped_policy_path(task)
    load_policy(path, task=task)
print(f"wheel smoke: ocean_warp from {installed}; foil table {table.shape}; hull offsets at "
      f"{len(offsets.stations)} stations; E-Boat hydrodynamics at {len(hydrodynamics.frequencies)} frequencies; "
      f"{len(SHIPPED_POLICIES)} shipped policies load ({', '.join(SHIPPED_POLICIES)})")
