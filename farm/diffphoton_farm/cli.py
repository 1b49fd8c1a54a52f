"""`diffphoton-farm render PROJECT --passes N --shard S [--scheduler tcp://HOST:8786] -o final.exr`"""

import argparse
import sys

from .runner import FarmError, render


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="diffphoton-farm",
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
    r.add_argument("--connect-timeout", type=float, default=5.0, help="seconds to reach the scheduler (default 5)")
    a = parser.parse_args(argv)
    extra = []
    if a.seed is not None:
        extra += ["--seed", a.seed]
    if a.photons is not None:
        extra += ["--photons", a.photons]
    try:
        figures = render(a.project, a.output, a.passes, a.shard, scheduler=a.scheduler, workers=a.workers,
                         binary=a.binary, bundle=a.bundle, render_args=extra, shard_threads=a.threads,
                         parts_dir=a.parts_dir, retries=a.retries, connect_timeout=a.connect_timeout)
    except FarmError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(f"wrote {a.output}  passes {figures['passes']}  shards {figures['shards']}  "
          f"seconds {figures['total_s']:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
