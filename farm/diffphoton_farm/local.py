"""A LocalCluster whose worker processes leave Ctrl-C to this one.

A terminal's Ctrl-C reaches every process of the group: the workers would die on it, each
printing its own traceback, while this process closes them anyway."""

import logging
import signal
import threading
from contextlib import contextmanager

from distributed import Client, LocalCluster, WorkerPlugin

from .errors import debugging


class IgnoreInterrupts(WorkerPlugin):
    """Set on every worker, those that replace a lost one included."""

    def setup(self, worker):
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextmanager
def _interrupts_ignored():
    """SIGINT ignored while the first workers start, so that they inherit it (a blocked mask
    would not do: the threads that start them do not share it). A Ctrl-C in these seconds is
    lost; the next one stops the render."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def local_client(workers):
    """(client, cluster): a LocalCluster of `workers` single-threaded processes."""
    with _interrupts_ignored():
        # Their logs (a failed shard's traceback, cancelled tasks) would repeat what this
        # reports in one line. A dashboard on a free port: 8787 may be taken, and Dask says so.
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                               silence_logs=logging.WARNING if debugging() else logging.CRITICAL)
    client = Client(cluster, set_as_default=False)
    client.register_plugin(IgnoreInterrupts(), name="diffphoton-farm-ignore-interrupts")
    return client, cluster
