"""The error the runner reports to its caller; kept apart so every module can raise it."""


class FarmError(RuntimeError):
    """A render that cannot be farmed as asked (unreachable scheduler, bad arguments, a shard
    that failed on every try); the message says why."""
