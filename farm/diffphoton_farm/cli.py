"""`diffphoton-farm render PROJECT --passes N --shard S [--scheduler tcp://HOST:8786] -o final.exr`

Exit codes: 0 done; 2 a bad argument, an unreachable or wrong scheduler, or a render that could
not be farmed, with one line on stderr; 1 an internal error (one line; the traceback with
DIFFPHOTON_FARM_DEBUG=1); 130 interrupted."""

import argparse
import json
import math
import os
import stat
import sys
import tempfile
from pathlib import Path

from . import connect
from .bundle import input_fields
from .errors import DEBUG_ENV, FarmError, debugging
from .runner import render

PROG = "diffphoton-farm"
INT_MAX = 2**31 - 1  # diffphoton's own limit on passes and threads
MAX_WORKERS = 1024
MAX_CONNECT_TIMEOUT = 3600.0


class UsageError(Exception):
    """A bad argument; the message names the flag or file."""


class _Parser(argparse.ArgumentParser):
    # argparse prints its usage and a message on two or more lines; one line says the same.
    def error(self, message):
        raise UsageError(f"{message} (see {self.prog} --help)")


def _parser():
    parser = _Parser(
        prog=PROG,
        description="Render a diffphoton project's passes in shards on a Dask cluster and merge them "
        "into the image one `diffphoton render --passes N --adaptive off` writes, bit for bit.")
    sub = parser.add_subparsers(dest="command", required=True)
    r = sub.add_parser("render", help="render a project on the cluster")
    r.add_argument("project", help="project file (JSON)")
    r.add_argument("-o", "--output", required=True, help="merged image (.exr)")
    r.add_argument("--passes", type=int, required=True, help="passes in all")
    r.add_argument("--shard", type=int, default=64, help="passes per shard (default 64)")
    r.add_argument("--scheduler", help="Dask scheduler address, e.g. tcp://host:8786 (default: a local cluster)")
    r.add_argument("--workers", type=int, help="local cluster only: worker processes (default: half the cores)")
    r.add_argument("--bundle", action="store_true",
                   help="send the project and its files to the workers (default: they read it from a "
                   "folder every machine shares, at the same path)")
    r.add_argument("--parts-dir", help="shared folder the workers write shards to (default: through Dask)")
    r.add_argument("--binary", help="diffphoton binary on the workers (default: $DIFFPHOTON or PATH)")
    r.add_argument("--threads", type=int, help="threads of each shard's diffphoton (0: all cores)")
    r.add_argument("--seed", help="random seed (overrides the project)")
    r.add_argument("--photons", help="photons per pass (overrides the project)")
    r.add_argument("--retries", type=int, default=3, help="tries of a shard whose diffphoton fails (default 3)")
    r.add_argument("--connect-timeout", type=float, default=5.0,
                   help=f"seconds to reach the scheduler (default 5, at most {MAX_CONNECT_TIMEOUT:g})")
    return parser


def _in_range(flag, value, low, high):
    if value is not None and not low <= value <= high:
        raise UsageError(f"{flag}: {value} is not a whole number from {low} to {high}")


def _whole(flag, text, low, high):
    """A whole number written in digits, as diffphoton reads --seed and --photons."""
    if text is not None and not (text.isascii() and text.isdigit() and low <= int(text) <= high):
        raise UsageError(f"{flag}: {text[:40]!r} is not a whole number from {low} to {high}")


def _check_numbers(a):
    for flag, value in (("--passes", a.passes), ("--shard", a.shard)):
        _in_range(flag, value, 1, INT_MAX)
    _in_range("--workers", a.workers, 1, MAX_WORKERS)
    _in_range("--threads", a.threads, 0, INT_MAX)
    _in_range("--retries", a.retries, 0, INT_MAX)
    _whole("--seed", a.seed, 0, 2**64 - 1)
    _whole("--photons", a.photons, 1, 2**63 - 1)
    if not (math.isfinite(a.connect_timeout) and 0 < a.connect_timeout <= MAX_CONNECT_TIMEOUT):
        raise UsageError(f"--connect-timeout: {a.connect_timeout:g} is not a number of seconds above 0 "
                         f"and at most {MAX_CONNECT_TIMEOUT:g}")


def _regular_file(path, what):
    """Refuses what is missing, not a regular file (a folder, a FIFO, /dev/zero) or unreadable;
    checked before it is opened, so a FIFO does not block."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise UsageError(f"{path}: {what} does not exist") from None
    except OSError as e:
        raise UsageError(f"{path}: cannot read {what}: {e.strerror}") from None
    if not stat.S_ISREG(mode):
        kind = "a folder" if stat.S_ISDIR(mode) else "not a regular file"
        raise UsageError(f"{path}: {what} is {kind}")
    try:
        with open(path, "rb"):
            pass
    except OSError as e:
        raise UsageError(f"{path}: cannot read {what}: {e.strerror}") from None


def _load_project(path):
    _regular_file(path, "the project file")
    try:
        doc = json.loads(Path(path).read_bytes())
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise UsageError(f"{path}: not a JSON project: {e}") from None
    except OSError as e:
        raise UsageError(f"{path}: cannot read the project file: {e.strerror}") from None
    if not isinstance(doc, dict):
        raise UsageError(f"{path}: not a JSON project: the top level is not an object")
    return doc


def _project_files(path):
    """The project file and every file it reads, as {resolved path: field}; each checked to be
    a readable regular file (the client merges, so it needs them all, bundle or not)."""
    doc = _load_project(path)
    files = {Path(path).resolve(): "the project file"}
    for field, holder, key in input_fields(doc):
        value = holder[key]
        if not isinstance(value, str):
            raise UsageError(f"{path}: {field}: {value!r} is not a file name")
        source = Path(value) if os.path.isabs(value) else Path(path).resolve().parent / value
        _regular_file(source, f"{field} of {path}")
        files[source.resolve()] = f"{field} of {path}"
    return files


def _check_writable_folder(folder, flag, output):
    """A file can be made there: tried, since permissions alone do not say (root, read-only
    mounts)."""
    if not folder.is_dir():
        raise UsageError(f"{flag} {output}: folder {folder} does not exist")
    try:
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".diffphoton-farm-")
    except OSError as e:
        raise UsageError(f"{flag} {output}: cannot write in {folder}: {e.strerror}") from None
    os.close(fd)
    os.unlink(probe)


def _check_output(output, inputs):
    path = Path(output)
    resolved = path.resolve()
    if resolved in inputs:
        raise UsageError(f"--output {output}: is {inputs[resolved]}; the render never overwrites its inputs")
    if path.is_dir():
        raise UsageError(f"--output {output}: is a folder")
    if path.suffix.lower() != ".exr":
        raise UsageError(f"--output {output}: the merge writes an EXR file (.exr)")
    if path.exists() and (not path.is_file() or not os.access(path, os.W_OK)
                          or not path.stat().st_mode & 0o222):
        raise UsageError(f"--output {output}: exists and cannot be overwritten (read-only or not a file)")
    _check_writable_folder(resolved.parent, "--output", output)


def _check_places(a):
    if a.scheduler is not None:
        try:
            connect.parse_address(a.scheduler)
        except ValueError as e:
            raise UsageError(f"--scheduler {a.scheduler}: {e}") from None
        if a.workers is not None:
            raise UsageError("--workers: only for a local cluster, not with --scheduler")
    if a.parts_dir is not None and not Path(a.parts_dir).is_dir():
        raise UsageError(f"--parts-dir {a.parts_dir}: no such folder")


def _check(a):
    """Every argument, before a connection or a process is started (render() checks the
    binary itself, first)."""
    _check_numbers(a)
    _check_places(a)
    inputs = _project_files(a.project)
    _check_output(a.output, inputs)


def _render(a):
    extra = []
    if a.seed is not None:
        extra += ["--seed", a.seed]
    if a.photons is not None:
        extra += ["--photons", a.photons]
    figures = render(a.project, a.output, a.passes, a.shard, scheduler=a.scheduler, workers=a.workers,
                     binary=a.binary, bundle=a.bundle, render_args=extra, shard_threads=a.threads,
                     parts_dir=a.parts_dir, retries=a.retries, connect_timeout=a.connect_timeout)
    print(f"wrote {a.output}  passes {figures['passes']}  shards {figures['shards']}  "
          f"seconds {figures['total_s']:.2f}")


def _say(text):
    """One line on stderr, whatever the message holds (a shard's diffphoton writes several)."""
    line = "; ".join(part.strip() for part in str(text).splitlines() if part.strip())
    print(f"{PROG}: {line}", file=sys.stderr, flush=True)


def main(argv=None):
    """Runs the command; returns its exit code (tests call it in process)."""
    try:
        a = _parser().parse_args(argv)
        _check(a)
        _render(a)
        return 0
    except (UsageError, FarmError) as e:
        connect.quiet_distributed()
        _say(e)
        return 2
    except KeyboardInterrupt:
        connect.quiet_distributed()
        return 130
    except SystemExit as e:  # --help
        return e.code if isinstance(e.code, int) else 0
    except Exception as e:
        connect.quiet_distributed()
        if debugging():
            raise
        _say(f"internal error: {type(e).__name__}: {e} (set {DEBUG_ENV}=1 for the traceback)")
        return 1


def entry():
    """The console command: main(), then out without the interpreter's teardown when a
    connection attempt was left running (it would wait on it, and a half-made Dask client
    prints its own errors when collected)."""
    code = main()
    if connect.left_behind():
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    return code


if __name__ == "__main__":
    sys.exit(entry())
