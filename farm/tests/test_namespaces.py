"""The Dask runner across machines, on one machine: a scheduler and two workers each in a Linux
network namespace of its own, joined by a private bridge (10.77.0.0/24, no route out), the
client beside the scheduler. The merged image equals the single-process render bit for bit in
bundle mode and in shared-folder mode, and also when one worker's process is killed mid-shard
(what it held is retried on the other). Needs root or passwordless sudo, iproute2's `ip` and
util-linux's `nsenter`; skipped with one line otherwise. The namespaces and everything in them go on exit.

Run by ctest (label farm) with DIFFPHOTON set to the binary under test."""

import filecmp
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

from support import BALL_ON_FLOOR, BINARY, dp  # noqa: E402  (first: puts the package on the path)

PASSES = 12
PROJECT = BALL_ON_FLOOR % 200000  # a shard of 4 passes takes about a second: long enough to kill mid-way
SCHEDULER = "tcp://10.77.0.1:8786"


def privileged():
    """The command prefix that runs as root (none when this is root), or None."""
    if os.geteuid() == 0:
        return []
    if shutil.which("sudo") and subprocess.run(["sudo", "-n", "true"], capture_output=True).returncode == 0:
        return ["sudo", "-n"]
    return None


class NamespacesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.root = privileged()
        if cls.root is None or not shutil.which("ip") or not shutil.which("nsenter"):
            raise unittest.SkipTest("network namespaces need root or passwordless sudo, iproute2's ip and nsenter")
        suffix = str(os.getpid())
        cls.ns = {"sched": "dpf-s" + suffix, "w1": "dpf-a" + suffix, "w2": "dpf-b" + suffix}
        cls.procs = []
        cls.tmp = tempfile.TemporaryDirectory(prefix="farm-netns-")
        os.chmod(cls.tmp.name, 0o755)
        cls.dir = Path(cls.tmp.name)
        try:
            cls.make_network()
            dp("make-test-image", "photo.exr", "--size", "64", "48", "--value", "0.5", "0.5", "0.5", cwd=cls.dir)
            dp("make-test-image", "probe.exr", "--size", "64", "32", "--probe-sun", "--value", "0.1", "0.1", "0.12",
               cwd=cls.dir)
            cls.project = cls.dir / "scene.json"
            cls.project.write_text(PROJECT)
            cls.single = cls.dir / "single.exr"
            dp("render", "scene.json", "--passes", str(PASSES), "--adaptive", "off", "-o", str(cls.single),
               cwd=cls.dir)
            cls.start_cluster()
        except BaseException:
            cls.tearDownClass()
            raise

    @classmethod
    def net(cls, key):
        """Into namespace `key`'s network only: `ip netns exec` and `ip -n` also make a mount
        namespace, which a chroot (as CI's root) refuses."""
        return ["nsenter", f"--net=/run/netns/{cls.ns[key]}"]

    @classmethod
    def ip(cls, key, *args):
        """`ip ARGS` as root, in namespace `key` (None: where this runs)."""
        where = cls.net(key) if key else []
        subprocess.run(cls.root + where + ["ip", *args], check=True, capture_output=True)

    @classmethod
    def make_network(cls):
        """A bridge in the scheduler's namespace, a veth from it into each worker's."""
        for key, name in cls.ns.items():
            cls.ip(None, "netns", "add", name)
            cls.ip(key, "link", "set", "lo", "up")
        cls.ip("sched", "link", "add", "br0", "type", "bridge")
        cls.ip("sched", "addr", "add", "10.77.0.1/24", "dev", "br0")
        cls.ip("sched", "link", "set", "br0", "up")
        for i, key in enumerate(("w1", "w2")):
            cls.ip("sched", "link", "add", f"v{i}", "type", "veth", "peer", "name", "eth0", "netns", cls.ns[key])
            cls.ip("sched", "link", "set", f"v{i}", "master", "br0", "up")
            cls.ip(key, "addr", "add", f"10.77.0.{i + 2}/24", "dev", "eth0")
            cls.ip(key, "link", "set", "eth0", "up")

    @classmethod
    def in_ns(cls, key, argv):
        """`argv` in namespace `key`, as this user (setpriv drops the root that nsenter needs)."""
        env = ["env", f"HOME={Path.home()}", f"PATH={os.environ.get('PATH', '')}",
               f"PYTHONPATH={os.environ.get('PYTHONPATH', '')}", f"DIFFPHOTON={BINARY}"]
        drop = ["setpriv", f"--reuid={os.getuid()}", f"--regid={os.getgid()}", "--clear-groups"]
        return cls.root + cls.net(key) + drop + env + argv

    @classmethod
    def start_cluster(cls):
        logs = cls.dir / "logs"
        logs.mkdir()

        def start(key, argv):
            with open(logs / f"{key}.txt", "w") as log:  # the child keeps its own descriptor
                cls.procs.append((key, subprocess.Popen(cls.in_ns(key, argv), stdout=log, stderr=log)))

        start("sched", [sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "10.77.0.1",
                        "--port", "8786", "--no-dashboard"])
        for i, key in enumerate(("w1", "w2")):
            start(key, [sys.executable, "-m", "distributed.cli.dask_worker", SCHEDULER, "--host", f"10.77.0.{i + 2}",
                        "--nthreads", "1", "--no-nanny", "--no-dashboard", "--name", key])

    @classmethod
    def tearDownClass(cls):
        for name in getattr(cls, "ns", {}).values():
            pids = subprocess.run(cls.root + ["ip", "netns", "pids", name], capture_output=True, text=True).stdout
            for pid in pids.split():
                subprocess.run(cls.root + ["kill", "-9", pid], capture_output=True)
            subprocess.run(cls.root + ["ip", "netns", "del", name], capture_output=True)
        for _, p in getattr(cls, "procs", []):
            p.wait(timeout=10)
        if hasattr(cls, "tmp"):
            cls.tmp.cleanup()

    def render(self, out, *extra):
        """The farm's command line beside the scheduler; returns the process (not waited for)."""
        argv = [sys.executable, "-m", "diffphoton_farm", "render", str(self.project), "--passes", str(PASSES),
                "--shard", "4", "--scheduler", SCHEDULER, "--binary", BINARY, "--threads", "1", "--connect-timeout",
                "20", "-o", str(out), *extra]
        return subprocess.Popen(self.in_ns("sched", argv), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    def finish(self, proc, out):
        output, _ = proc.communicate(timeout=240)
        self.assertEqual(proc.returncode, 0, output)
        self.assertTrue(filecmp.cmp(self.single, out, shallow=False), f"{out} differs from the single render")
        return output

    def test_1_bundle_mode_across_namespaces_merges_to_the_single_render(self):
        self.finish(self.render(self.dir / "bundle.exr", "--bundle"), self.dir / "bundle.exr")

    def test_2_shared_folder_mode_across_namespaces_merges_to_the_single_render(self):
        parts = self.dir / "parts"
        parts.mkdir()
        self.finish(self.render(self.dir / "shared.exr", "--parts-dir", str(parts)), self.dir / "shared.exr")
        self.assertEqual(len(list(parts.glob("shard-*.dpp"))), 3)

    def pids(self, key):
        return subprocess.run(self.root + ["ip", "netns", "pids", self.ns[key]], capture_output=True,
                              text=True).stdout.split()

    def test_3_a_worker_killed_mid_shard_is_retried_on_the_other(self):
        parts = self.dir / "parts-killed"
        parts.mkdir()
        out = self.dir / "killed.exr"
        proc = self.render(out, "--parts-dir", str(parts))
        # The worker that takes the last shard (8:12, begun once one of the first two is done) dies
        # in the middle of it, as a machine would, without a word: its diffphoton is seen running
        # in its namespace, and everything there is killed.
        victim, deadline = None, time.monotonic() + 120
        while victim is None and time.monotonic() < deadline and proc.poll() is None:
            for key in ("w1", "w2"):
                for pid in self.pids(key):
                    try:
                        if b"--pass-range\x008:12" in Path(f"/proc/{pid}/cmdline").read_bytes():
                            victim = key
                    except OSError:
                        pass
            time.sleep(0.01)
        self.assertIsNotNone(victim, "no worker was caught rendering the last shard")
        for pid in self.pids(victim):
            subprocess.run(self.root + ["kill", "-9", pid], capture_output=True)
        dict(self.procs)[victim].wait(timeout=10)
        self.finish(proc, out)
        # The killed try left its empty file (it was mid-shard); every range has a finished shard.
        files = list(parts.glob("shard-*.dpp"))
        done = {f.name[:24] for f in files if f.stat().st_size > 0}
        self.assertEqual(len(done), 3, [f.name for f in files])
        self.assertTrue(any(f.stat().st_size == 0 for f in files), [(f.name, f.stat().st_size) for f in files])
        self.assertTrue(any(f.name.startswith("shard-00000008-00000012-") and f.stat().st_size > 0 for f in files))

if __name__ == "__main__":
    unittest.main()
