"""What a Dask worker runs for one shard: the diffphoton binary on a pass range."""

import ctypes
import os
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

from .bundle import unpack_bundle


class ShardFailed(RuntimeError):
    """diffphoton exited with an error on a shard (the task is retried elsewhere)."""


# Loaded here, not in the child: between fork and exec a threaded process should do no more than
# one system call.
try:
    _LIBC = ctypes.CDLL("libc.so.6", use_errno=True) if sys.platform.startswith("linux") else None
except OSError:
    _LIBC = None
_PR_SET_PDEATHSIG = 1


def _die_with_parent():
    # A worker killed with SIGKILL cannot stop its child; the kernel does it for us, so a lost
    # worker's diffphoton does not keep the machine busy with a shard rendered again elsewhere.
    _LIBC.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)


def render_shard(binary, begin, end, project=None, bundle=None, bundle_digest=None, args=(), parts_dir=None):
    """Renders passes [begin, end) of a project and returns the shard: its bytes, or its path
    when `parts_dir` (a folder every machine shares) is given.

    The project is `project` (a path on the shared folder) or, in bundle mode, the bundle's
    bytes, unpacked once per machine."""
    if bundle is not None:
        project = unpack_bundle(bundle, bundle_digest)
    folder = parts_dir or tempfile.gettempdir()
    # A name of this attempt's own: a retried shard never meets a half-written earlier try.
    fd, out = tempfile.mkstemp(dir=folder, prefix=f"shard-{begin:08d}-{end:08d}-", suffix=".dpp")
    os.close(fd)
    command = [binary, "render", project, "--pass-range", f"{begin}:{end}", "-o", out, *args]
    try:
        done = subprocess.run(command, capture_output=True, text=True, preexec_fn=_die_with_parent if _LIBC else None)
        if done.returncode != 0:
            raise ShardFailed(f"passes {begin}:{end}: {' '.join(command)} exited with {done.returncode}: "
                              f"{done.stderr.strip()[-2000:]}")
        if parts_dir:
            return out
        data = Path(out).read_bytes()
    except BaseException:
        Path(out).unlink(missing_ok=True)
        raise
    Path(out).unlink(missing_ok=True)
    return data
