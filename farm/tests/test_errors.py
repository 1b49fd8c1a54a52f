"""diffphoton-farm's failures as a person meets them: every bad argument, and an unreachable or
wrong scheduler (refused port, HTTP port, a server that accepts and never answers), exits 2 with
one line on stderr naming the flag or file, no traceback, within --connect-timeout, and leaves
the project's files as they were.

Run by ctest (label farm, test farm.runner) with DIFFPHOTON set to the binary under test."""

import contextlib
import hashlib
import http.server
import io
import os
import signal
import socket
import socketserver
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest
from pathlib import Path
from unittest import mock

from support import BALL_ON_FLOOR, BINARY, FARM, dp  # noqa: E402  (first: puts the package on the path)
from diffphoton_farm import cli  # noqa: E402
TIMEOUT = 2  # --connect-timeout of the scheduler cases
SLACK = 1.5  # seconds past it and past the interpreter's own start a refusal may take
PROJECT = BALL_ON_FLOOR % 5000


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


class _Silent(socketserver.BaseRequestHandler):
    """Accepts and never says a word, until the test ends."""

    def handle(self):
        self.server.stop.wait()


class _Greets(socketserver.BaseRequestHandler):
    """Sends a Dask server's handshake, then nothing: a scheduler hung after accepting."""

    def handle(self):
        import msgpack

        body = msgpack.packb({"compression": None, "python": (3, 11, 0), "pickle-protocol": 5}, use_bin_type=True)
        prelude = struct.pack("QQ", 1, len(body))
        self.request.sendall(struct.pack("Q", len(prelude) + len(body)) + prelude + body)
        self.server.stop.wait()


def serve(handler):
    """A threaded server on a free port of 127.0.0.1; returns (server, port)."""
    server = socketserver.ThreadingTCPServer(("127.0.0.1", 0), handler)
    server.daemon_threads = True
    server.stop = threading.Event()
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, server.server_address[1]


def unwritable_folder(parent):
    """A folder no file can be made in: a read-only one, or for root (whom modes do not stop)
    /sys; None where there is neither."""
    folder = parent / "read-only"
    folder.mkdir(exist_ok=True)
    folder.chmod(0o555)
    for candidate in (folder, Path("/sys")):
        try:
            fd, path = tempfile.mkstemp(dir=candidate)
        except OSError:
            return candidate
        os.close(fd)
        os.unlink(path)
    return None


class RefusalsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="farm-errors-")
        cls.dir = Path(cls.tmp.name)
        dp("make-test-image", "photo.exr", "--size", "32", "24", "--value", "0.5", "0.5", "0.5", cwd=cls.dir)
        dp("make-test-image", "probe.exr", "--size", "32", "16", "--probe-sun", "--value", "0.1", "0.1", "0.12",
           cwd=cls.dir)
        (cls.dir / "scene.json").write_text(PROJECT)
        cls.inputs = [cls.dir / name for name in ("scene.json", "photo.exr", "probe.exr")]
        cls.env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(FARM), os.environ.get("PYTHONPATH", "")]),
                       DIFFPHOTON=BINARY)
        cls.env.pop("DIFFPHOTON_FARM_DEBUG", None)

    @classmethod
    def tearDownClass(cls):
        (cls.dir / "read-only").exists() and (cls.dir / "read-only").chmod(0o755)
        cls.tmp.cleanup()

    def snapshot(self):
        return {p: (hashlib.sha256(p.read_bytes()).hexdigest(), p.stat().st_mtime_ns) for p in self.inputs}

    def farm(self, *args, env=None):
        """Runs the command as a person does; (exit code, stdout, stderr, seconds)."""
        start = time.monotonic()
        done = subprocess.run([sys.executable, "-m", "diffphoton_farm", *args], cwd=self.dir, env=env or self.env,
                              capture_output=True, text=True, timeout=120)
        return done.returncode, done.stdout, done.stderr, time.monotonic() - start

    def assert_refused(self, args, names, within=None, output="out.exr"):
        """Exit 2, one line on stderr beginning with the command's name and holding each of
        `names`, no traceback, nothing written, the inputs untouched."""
        before = self.snapshot()
        code, out, err, seconds = self.farm(*args)
        self.assertNotIn("Traceback", err)
        self.assertEqual(code, 2, err)
        lines = err.splitlines()
        self.assertEqual(len(lines), 1, f"stderr is not one line: {err!r}")
        self.assertTrue(lines[0].startswith("diffphoton-farm: "), lines[0])
        for name in names:
            self.assertIn(name, lines[0])
        self.assertEqual(out, "")
        if within is not None:
            self.assertLessEqual(seconds, within, lines[0])
        self.assertEqual(self.snapshot(), before, "a refused command changed the project's files")
        self.assertFalse((self.dir / output).exists(), f"a refused command wrote {output}")
        return lines[0]

    def render(self, *extra, project="scene.json", output="out.exr"):
        return ["render", project, "--passes", "4", "-o", output, *extra]

    # Arguments

    def test_a_missing_project_names_the_file(self):
        self.assert_refused(self.render(project="missing.json"), ["missing.json", "does not exist"])

    def test_a_project_that_is_not_a_regular_file_is_refused_before_it_is_opened(self):
        (self.dir / "folder.json").mkdir(exist_ok=True)
        self.assert_refused(self.render(project="folder.json"), ["folder.json", "a folder"])
        fifo = self.dir / "fifo.json"
        if not fifo.exists():
            os.mkfifo(fifo)
        self.assert_refused(self.render(project="fifo.json"), ["fifo.json", "not a regular file"])

    @unittest.skipIf(os.geteuid() == 0, "root reads any file")
    def test_an_unreadable_project_names_the_file(self):
        locked = self.dir / "locked.json"
        locked.write_text(PROJECT)
        locked.chmod(0)
        try:
            self.assert_refused(self.render(project="locked.json"), ["locked.json", "cannot read"])
        finally:
            locked.chmod(0o644)

    def test_a_project_that_is_not_json_or_misses_a_file_names_it(self):
        (self.dir / "broken.json").write_text('{"photo": ')
        self.assert_refused(self.render(project="broken.json"), ["broken.json", "not a JSON project"])
        (self.dir / "lost.json").write_text(PROJECT.replace("probe.exr", "gone.exr"))
        self.assert_refused(self.render(project="lost.json"), ["gone.exr", "probe.path", "does not exist"])

    def test_numbers_out_of_range_name_their_flag(self):
        cases = [
            (["--passes", "0"], "--passes"), (["--passes", "abc"], "--passes"), (["--shard", "-3"], "--shard"),
            (["--workers", "0"], "--workers"), (["--threads", "-1"], "--threads"), (["--retries", "-1"], "--retries"),
            (["--seed", "-1"], "--seed"), (["--photons", "1e5"], "--photons"), (["--photons", "0"], "--photons"),
            (["--connect-timeout", "-1"], "--connect-timeout"), (["--connect-timeout", "nan"], "--connect-timeout"),
            (["--connect-timeout", "inf"], "--connect-timeout"),
        ]
        for extra, flag in cases:
            with self.subTest(extra=extra):
                self.assert_refused(self.render(*extra), [flag])  # the last --passes counts

    def test_bad_scheduler_addresses_name_the_flag(self):
        for address in ("tcp://host:notaport", "tcp://host:0", "tcp://host:65536", "tcp://host",
                        "http://host:8786", "tcp://host:8786/path", "tcp://:8786"):
            with self.subTest(address=address):
                self.assert_refused(self.render("--scheduler", address), ["--scheduler", address])
        self.assert_refused(self.render("--scheduler", "tcp://127.0.0.1:9", "--workers", "2"), ["--workers"])

    def test_unknown_options_and_commands_take_one_line(self):
        self.assert_refused(self.render("--frobnicate"), ["--frobnicate"])
        self.assert_refused(["paint", "scene.json"], ["paint"])
        self.assert_refused(["render", "scene.json", "--passes", "4"], ["--output"])

    def test_an_output_that_cannot_be_written_is_refused_before_the_render(self):
        self.assert_refused(self.render(output="no-such-folder/out.exr"), ["--output", "no-such-folder"],
                            output="no-such-folder/out.exr")
        self.assert_refused(self.render(output="out.png"), ["--output", "out.png", ".exr"], output="out.png")
        (self.dir / "a-folder.exr").mkdir(exist_ok=True)
        self.assert_refused(self.render(output="a-folder.exr"), ["--output", "a-folder.exr", "folder"])
        locked = unwritable_folder(self.dir)
        if locked is None:
            self.skipTest("no folder here refuses a new file")
        target = str(locked / "out.exr")
        self.assert_refused(self.render(output=target), ["--output", target, "cannot write"], output=target)

    def test_an_output_that_is_one_of_the_inputs_is_refused(self):
        for name, field in (("photo.exr", "photo.path"), ("probe.exr", "probe.path"),
                            ("scene.json", "project file")):
            with self.subTest(output=name):
                line = self.assert_refused(self.render(output=name), ["--output", name, field], output="out.exr")
                self.assertIn("never overwrites its inputs", line)

    def test_other_missing_places_name_their_flag(self):
        self.assert_refused(self.render("--parts-dir", "no-parts"), ["--parts-dir", "no-parts"])
        self.assert_refused(self.render("--binary", str(self.dir)), ["--binary", str(self.dir)])

    # Schedulers

    def startup_seconds(self):
        """What a refusal that connects nowhere takes now: the interpreter's start and imports,
        which grow on a loaded machine and are not the connect's time."""
        return self.farm(*self.render("--passes", "0"))[3]

    def assert_unreachable(self, port, reason):
        address = f"tcp://127.0.0.1:{port}"
        within = TIMEOUT + self.startup_seconds() + SLACK
        line = self.assert_refused(self.render("--scheduler", address, "--connect-timeout", str(TIMEOUT)),
                                   [f"cannot reach a Dask scheduler at {address} within {TIMEOUT} s", reason],
                                   within=within)
        return line

    def test_a_refused_port_is_reported_within_the_timeout(self):
        self.assert_unreachable(free_port(), "connection refused")

    def test_an_http_port_is_reported_as_one_within_the_timeout(self):
        server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), _Quiet)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        try:
            self.assert_unreachable(server.server_address[1], "is it an HTTP port?")
        finally:
            server.shutdown()
            server.server_close()

    def test_a_server_that_never_answers_is_given_up_within_the_timeout(self):
        server, port = serve(_Silent)
        try:
            self.assert_unreachable(port, "no answer")
        finally:
            server.stop.set()
            server.shutdown()
            server.server_close()

    def test_a_server_that_stops_after_the_handshake_is_given_up_within_the_timeout(self):
        server, port = serve(_Greets)
        try:
            self.assert_unreachable(port, "answered the handshake, then nothing")
        finally:
            server.stop.set()
            server.shutdown()
            server.server_close()

    def test_a_client_that_fails_half_made_leaves_no_traceback_at_exit(self):
        # tls:// without a TLS configuration: Dask's Client fails after the port answered, and a
        # half-made Client would print its own traceback when the interpreter collects it.
        server, port = serve(_Silent)
        try:
            address = f"tls://127.0.0.1:{port}"
            self.assert_refused(self.render("--scheduler", address, "--connect-timeout", str(TIMEOUT)),
                                [f"cannot reach a Dask scheduler at {address}", "TLS"],
                                within=TIMEOUT + self.startup_seconds() + SLACK)
        finally:
            server.stop.set()
            server.shutdown()
            server.server_close()

    def test_a_real_scheduler_passes_the_probe_and_renders(self):
        from dask.distributed import LocalCluster

        cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp",
                               host="127.0.0.1", dashboard_address=":0")
        with cluster:
            code, out, err, _ = self.farm(*self.render("--scheduler", cluster.scheduler_address, "--shard", "2",
                                                       "--connect-timeout", "30", output="remote.exr"))
        self.assertEqual(code, 0, err)
        self.assertNotIn("Traceback", err)
        self.assertIn("shards 2", out)
        self.assertTrue((self.dir / "remote.exr").is_file())

    def test_ctrl_c_on_a_local_cluster_exits_130_with_no_word_from_its_workers(self):
        # As a terminal does it: SIGINT to the whole process group, workers included, once the
        # progress bar shows the shards submitted.
        before = self.snapshot()
        args = self.render("--passes", "400", "--shard", "2", "--workers", "2", output="interrupted.exr")
        farm = subprocess.Popen([sys.executable, "-m", "diffphoton_farm", *args], cwd=self.dir, env=self.env,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        try:
            seen = []
            for line in farm.stderr:
                seen.append(line)
                if line.startswith("shards 0/"):
                    break
            os.killpg(farm.pid, signal.SIGINT)
            out, err = farm.communicate(timeout=60)
        finally:
            if farm.poll() is None:
                os.killpg(farm.pid, signal.SIGKILL)
        err = "".join(seen) + err
        self.assertEqual(farm.returncode, 130, err)
        self.assertNotIn("Traceback", err)
        self.assertEqual([line for line in err.splitlines() if not line.startswith("shards ")], [])
        self.assertEqual(out, "")
        self.assertFalse((self.dir / "interrupted.exr").exists())
        self.assertEqual(self.snapshot(), before)

    # The guard

    def run_main(self, error, env=None):
        """cli.main on a good command whose render raises `error`: (code, stderr)."""
        err = io.StringIO()
        args = self.render("--binary", BINARY, project=str(self.dir / "scene.json"), output=str(self.dir / "out.exr"))
        with mock.patch.object(cli, "render", side_effect=error), mock.patch.dict(os.environ, env or {}), \
                contextlib.redirect_stderr(err):
            code = cli.main(args)
        return code, err.getvalue()

    def test_an_unexpected_error_is_one_line_with_exit_1_and_a_traceback_only_when_asked(self):
        code, err = self.run_main(ZeroDivisionError("boom"))
        self.assertEqual(code, 1)
        self.assertEqual(err.splitlines(), ["diffphoton-farm: internal error: ZeroDivisionError: boom "
                                            "(set DIFFPHOTON_FARM_DEBUG=1 for the traceback)"])
        with self.assertRaises(ZeroDivisionError):
            self.run_main(ZeroDivisionError("boom"), env={"DIFFPHOTON_FARM_DEBUG": "1"})

    def test_an_interrupt_exits_130_without_a_word(self):
        code, err = self.run_main(KeyboardInterrupt())
        self.assertEqual((code, err), (130, ""))


if __name__ == "__main__":
    unittest.main()
