"""What every farm test module needs first: the package on the path, dask.distributed present
(or a clear reason to skip), and the diffphoton binary the renders run."""
import os
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
