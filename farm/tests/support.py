"""What every farm test module needs first: the package on the path, dask.distributed present
(or a clear reason to skip), and the diffphoton binary the renders run."""
import os
import subprocess
import sys
import unittest
from pathlib import Path

FARM = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(FARM))

try:
    import distributed  # noqa: F401
except ImportError:  # CI installs it (scripts/install-deps.sh); only a local run may skip
    if os.environ.get("DP_FARM_TESTS_OPTIONAL") == "1":
        raise unittest.SkipTest("dask.distributed is not installed (DP_FARM_TESTS_OPTIONAL=1)")
    raise SystemExit("dask.distributed is not installed: run scripts/install-deps.sh "
                     "(or pip install ./farm)")

BINARY = os.environ.get("DIFFPHOTON", "diffphoton")
if os.sep in BINARY:
    BINARY = os.path.abspath(BINARY)  # the commands run in scratch folders


# A ball on a floor under a probe with a sun, `photons` a pass: the farm tests' scene.
BALL_ON_FLOOR = """{
  "schema_version": 1,
  "photo": {"path": "photo.exr"},
  "probe": {"path": "probe.exr"},
  "camera": {"model": "lookat", "eye": [0, 1.5, 4], "target": [0, 0.4, 0], "vfov_deg": 40},
  "real": [{"name": "floor", "shape": {"type": "plane", "size": [10, 10]}, "albedo": [0.5, 0.5, 0.5]}],
  "objects": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.5},
               "transform": {"translation": [0, 0.5, 0]}, "material": {"type": "diffuse", "albedo": [0.8, 0.3, 0.2]}}],
  "render": {"photons_per_pass": %d, "passes": 2}
}
"""


def dp(*args, cwd):
    """Runs diffphoton in `cwd`; AssertionError with its stderr where it fails."""
    done = subprocess.run([BINARY, *args], cwd=cwd, capture_output=True, text=True)
    if done.returncode != 0:
        raise AssertionError(f"diffphoton {' '.join(args)} failed: {done.stderr}")
