"""The Dask runner against the real binary on a LocalCluster of two worker processes: its merged
image equals the single-process render bit for bit, also when a worker is killed mid-shard, and
an unreachable scheduler is reported within seconds.

Run by ctest (label farm) with DIFFPHOTON set to the binary under test."""

import filecmp
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

from support import BINARY, dp  # noqa: E402  (first: puts the package on the path)
from diffphoton_farm import FarmError, plan_shards, render  # noqa: E402
from diffphoton_farm.cli import main as farm_main  # noqa: E402
PASSES = 12
PROJECT = """{
  "schema_version": 1,
  "photo": {"path": "photo.exr"},
  "probe": {"path": "%s"},
  "camera": {"model": "lookat", "eye": [0, 1.5, 4], "target": [0, 0.4, 0], "vfov_deg": 40},
  "real": [{"name": "floor", "shape": {"type": "plane", "size": [10, 10]}, "albedo": [0.5, 0.5, 0.5]}],
  "objects": [
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "transform": {"translation": [0, 0.5, 0]},
     "material": {"type": "diffuse", "albedo": [0.8, 0.3, 0.2]}},
    {"name": "glass", "shape": {"type": "sphere", "radius": 0.3}, "transform": {"translation": [0.7, 0.3, 0.4]},
     "material": {"type": "glass", "ior": 1.5}}
  ],
  "render": {"photons_per_pass": 20000, "passes": 3}
}
"""


class FarmTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="farm-test-")
        cls.dir = Path(cls.tmp.name)
        # The probe in a folder of its own, by absolute path: bundle mode must carry it.
        (cls.dir / "assets").mkdir()
        dp("make-test-image", "photo.exr", "--size", "64", "48", "--value", "0.5", "0.5", "0.5", cwd=cls.dir)
        dp("make-test-image", "assets/probe.exr", "--size", "64", "32", "--probe-sun", "--value", "0.1", "0.1",
           "0.12", cwd=cls.dir)
        cls.project = cls.dir / "scene.json"
        cls.project.write_text(PROJECT % (cls.dir / "assets" / "probe.exr"))
        cls.single = cls.dir / "single.exr"
        dp("render", "scene.json", "--passes", str(PASSES), "--adaptive", "off", "-o", str(cls.single), cwd=cls.dir)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def assert_same_as_single(self, path):
        self.assertTrue(filecmp.cmp(self.single, path, shallow=False), f"{path} differs from the single render")

    def test_shards_cover_the_passes_once_with_a_shorter_last_one(self):
        self.assertEqual(plan_shards(10, 4), [(0, 4), (4, 8), (8, 10)])
        self.assertEqual(plan_shards(3, 64), [(0, 3)])
        with self.assertRaises(FarmError):
            plan_shards(0, 4)

    def test_two_local_workers_merge_to_the_single_render_bit_for_bit(self):
        out = self.dir / "local.exr"
        figures = render(self.project, out, PASSES, 5, workers=2, binary=BINARY, progress=None)
        self.assertEqual(figures["shards"], 3)
        self.assert_same_as_single(out)

    def test_a_bundled_project_renders_the_same_image(self):
        out = self.dir / "bundle.exr"
        render(self.project, out, PASSES, 4, workers=2, binary=BINARY, bundle=True, progress=None)
        self.assert_same_as_single(out)

    def test_shards_written_to_a_shared_folder_merge_to_the_same_image(self):
        out, parts = self.dir / "parts.exr", self.dir / "parts"
        parts.mkdir()
        render(self.project, out, PASSES, 5, workers=2, binary=BINARY, parts_dir=str(parts), progress=None)
        self.assert_same_as_single(out)
        self.assertEqual(len(list(parts.glob("shard-*.dpp"))), 3)

    def test_a_worker_killed_mid_shard_is_replaced_and_the_image_is_unchanged(self):
        out = self.dir / "killed.exr"
        killed = []

        def kill_a_busy_worker(client, done, total):
            if killed:
                return
            # A worker with a shard in hand: its process dies as a machine would, without a word.
            for address, keys in client.processing().items():
                if keys:
                    pid = client.run(os.getpid, workers=[address])[address]
                    os.kill(pid, signal.SIGKILL)
                    killed.append(address)
                    return

        render(self.project, out, PASSES, 2, workers=2, binary=BINARY, progress=None,
               on_shard_done=kill_a_busy_worker)
        self.assertTrue(killed, "no worker was busy when the first shard finished")
        self.assert_same_as_single(out)

    def test_an_unreachable_scheduler_is_reported_within_seconds(self):
        start = time.monotonic()
        with self.assertRaises(FarmError) as caught:
            render(self.project, self.dir / "never.exr", PASSES, 4, scheduler="tcp://127.0.0.1:9", binary=BINARY,
                   connect_timeout=2, progress=None)
        self.assertLess(time.monotonic() - start, 10)
        self.assertIn("cannot reach a Dask scheduler at tcp://127.0.0.1:9", str(caught.exception))
        # The command line says so and exits 2.
        code = farm_main(["render", str(self.project), "--passes", "4", "--scheduler", "tcp://127.0.0.1:9",
                          "--connect-timeout", "2", "--binary", BINARY, "-o", str(self.dir / "never.exr")])
        self.assertEqual(code, 2)
        self.assertFalse((self.dir / "never.exr").exists())


if __name__ == "__main__":
    unittest.main()
