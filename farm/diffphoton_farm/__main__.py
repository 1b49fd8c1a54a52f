"""`python3 -m diffphoton_farm render ...`: the diffphoton-farm command."""

import sys

from .cli import entry

sys.exit(entry())
