"""The error the runner reports to its caller, and the switch that shows what is behind one;
kept apart so every module can use them."""

import os

DEBUG_ENV = "DIFFPHOTON_FARM_DEBUG"


def debugging():
    """DIFFPHOTON_FARM_DEBUG=1: tracebacks and Dask's own logs are shown, not one line."""
    return os.environ.get(DEBUG_ENV) == "1"


class FarmError(RuntimeError):
    """A render that cannot be farmed as asked (unreachable scheduler, bad arguments, a shard
    that failed on every try); the message says why."""
