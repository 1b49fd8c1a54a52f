"""Submits a render's shards to a Dask cluster, shows their progress and merges them."""

import os
import shutil
import subprocess
import sys
import tempfile
import time
import uuid
from pathlib import Path

from . import connect, worker
from .bundle import make_bundle
from .errors import FarmError


def plan_shards(passes, shard):
    """The pass ranges [begin, end) of `passes` passes in shards of `shard` (the last shorter)."""
    if passes < 1 or shard < 1:
        raise FarmError(f"--passes ({passes}) and --shard ({shard}) must be at least 1")
    return [(b, min(b + shard, passes)) for b in range(0, passes, shard)]


def find_binary(binary=None):
    """The diffphoton binary: `binary`, $DIFFPHOTON, or `diffphoton` on PATH."""
    name = binary or os.environ.get("DIFFPHOTON") or "diffphoton"
    found = shutil.which(name) if os.sep not in name else name
    if not found or not os.path.isfile(found) or not os.access(found, os.X_OK):
        raise FarmError(f"cannot find the diffphoton binary '{name}' (pass --binary or set DIFFPHOTON)")
    return str(Path(found).resolve())


def _bar(done, total, started, stream):
    width = 30
    filled = int(width * done / total) if total else width
    text = f"shards {done}/{total} [{'#' * filled}{'.' * (width - filled)}] {time.monotonic() - started:.1f}s"
    if stream.isatty():
        stream.write("\r" + text + ("\n" if done == total else ""))
    else:
        stream.write(text + "\n")
    stream.flush()


def _client(scheduler, workers, connect_timeout):
    """A Dask client: on the scheduler at `scheduler` (within `connect_timeout` seconds), or on
    a LocalCluster of `workers` single-threaded processes. Returns (client, cluster or None)."""
    if scheduler:
        return connect.client(scheduler, connect_timeout), None
    from .local import local_client

    return local_client(workers)


def render(project, output, passes, shard, scheduler=None, workers=None, binary=None, bundle=False,
           render_args=(), shard_threads=None, parts_dir=None, retries=3, connect_timeout=5.0,
           progress=sys.stderr, on_shard_done=None):
    """Renders `passes` passes of `project` in shards of `shard` passes on Dask and merges them
    into the EXR `output`: bit for bit `diffphoton render project --passes N --adaptive off`.

    scheduler: "tcp://host:8786", or None for a LocalCluster of `workers` processes (default:
    half the cores). bundle: ship the project and its files to the workers instead of reading
    them from a folder every machine shares. render_args: extra `diffphoton render` options
    (--seed, --photons). shard_threads: --threads of each shard (default: the cores divided
    among the local workers; all of a remote worker's cores). parts_dir: a shared folder the
    workers write their shards to (default: shards come back through Dask). A shard whose
    worker dies is rerun by Dask on another; one whose diffphoton fails is retried `retries`
    times. on_shard_done(client, done, total) is called after each shard (tests use it).
    Returns a dict of figures."""
    binary = find_binary(binary)
    project = str(Path(project).resolve())
    if not Path(project).is_file():
        raise FarmError(f"{project}: no such project file")
    ranges = plan_shards(passes, shard)
    cores = os.cpu_count() or 1
    if not scheduler and not workers:
        workers = max(1, cores // 2)
    args = list(render_args)
    threads = shard_threads if shard_threads is not None else (0 if scheduler else max(1, cores // workers))
    if threads:
        args += ["--threads", str(threads)]
    started = time.monotonic()
    client, cluster = _client(scheduler, workers, connect_timeout)
    # Imported after the connection: a wrong address is reported without waiting for dask.
    from dask.distributed import as_completed

    scratch = Path(tempfile.mkdtemp(prefix="diffphoton-farm-"))
    try:
        common = {"args": args, "parts_dir": parts_dir}
        if bundle:
            try:
                data, digest = make_bundle(project)
            except (OSError, ValueError) as e:
                raise FarmError(str(e)) from None
            # Scattered once: each worker fetches the bundle once, not once per shard.
            common.update(bundle=client.scatter(data, broadcast=False, hash=False), bundle_digest=digest)
        else:
            common["project"] = project
        run_id = uuid.uuid4().hex[:8]
        futures = [
            client.submit(worker.render_shard, binary, b, e, key=f"diffphoton-shard-{b}-{e}-{run_id}",
                          retries=retries, pure=False, **common)
            for b, e in ranges
        ]
        range_of = {f.key: r for f, r in zip(futures, ranges)}
        pending = as_completed(futures, loop=client.loop)
        del futures  # as_completed holds them now: each is let go once its shard is here
        parts = {}
        if progress:
            _bar(0, len(ranges), started, progress)
        for future in pending:
            b, e = range_of[future.key]
            try:
                result = future.result()
            except Exception as exc:
                raise FarmError(f"shard {b}:{e} failed on every try: {exc}") from None
            if isinstance(result, (bytes, bytearray)):
                path = scratch / f"shard-{b:08d}-{e:08d}.dpp"
                path.write_bytes(result)
                result = str(path)
            # Released, so that a worker lost later does not make the scheduler render a shard
            # we already hold again.
            future.release()
            parts[(b, e)] = result
            if progress:
                _bar(len(parts), len(ranges), started, progress)
            if on_shard_done:
                on_shard_done(client, len(parts), len(ranges))
        rendered = time.monotonic()
        paths = [parts[r] for r in ranges]
        merge = subprocess.run([binary, "merge", *paths, "-o", str(output), "--project", project],
                               capture_output=True, text=True)
        if merge.returncode != 0:
            raise FarmError(f"merge failed ({merge.returncode}): {merge.stderr.strip()}")
        return {"shards": len(ranges), "passes": passes, "render_s": rendered - started,
                "total_s": time.monotonic() - started}
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
        client.close()
        if cluster is not None:
            cluster.close()
