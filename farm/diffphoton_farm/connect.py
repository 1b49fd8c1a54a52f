"""Reaching a Dask scheduler within a wall-clock bound.

Dask's own Client(address, timeout=...) waits for the scheduler's handshake without a limit, so
an HTTP port or a server that accepts and never answers holds it forever. The address is
therefore probed first with plain sockets under a deadline (connect, exchange the handshakes a
Dask client and server exchange), and the Client itself is created under the rest of it."""

import logging
import pickle
import socket
import struct
import sys
import threading
import time
from urllib.parse import urlsplit

from .errors import FarmError, debugging

SCHEMES = ("tcp", "tls")
_RETRY_S = 0.2  # between tries on a refused port: a scheduler may be starting
_MAX_GREETING = 1 << 20  # a Dask handshake is tens of bytes
_CLIENT_FLOOR_S = 1.0  # the Client's least window after a probe that took nearly all of it
_left_behind = []  # calls given up on while still running, or failed Clients half made


def left_behind():
    """Whether a connection attempt was given up or failed half way: the process had better
    exit without the interpreter's teardown, which would wait on it."""
    return bool(_left_behind)


def parse_address(text):
    """(scheme, host, port) of a scheduler address `tcp://host:port` (or `host:port`, tcp);
    ValueError with the reason otherwise."""
    url = urlsplit(text if "://" in text else "tcp://" + text)
    if url.scheme not in SCHEMES:
        raise ValueError(f"scheme {url.scheme}:// is not one of {', '.join(s + '://' for s in SCHEMES)}")
    if url.path or url.query or url.fragment or url.username or url.password:
        raise ValueError("is not of the form tcp://HOST:PORT")
    try:
        port = url.port
    except ValueError:
        port = -1
    if not url.hostname:
        raise ValueError("has no host (tcp://HOST:PORT)")
    if port is None:
        raise ValueError("has no port (tcp://HOST:PORT, the scheduler's is usually 8786)")
    if not 1 <= port <= 65535:
        raise ValueError(f"port {url.netloc.rpartition(':')[2]!r} is not a number from 1 to 65535")
    return url.scheme, url.hostname, port


def _within(seconds, fn):
    """Runs fn() in a daemon thread for at most `seconds`: (finished, result, exception).
    A call still running is left behind; the process is about to report and exit."""
    box = {}

    def run():
        try:
            box["result"] = fn()
        except BaseException as e:  # handed to the caller
            box["error"] = e

    thread = threading.Thread(target=run, daemon=True, name="diffphoton-farm-connect")
    thread.start()
    thread.join(max(0.0, seconds))
    if thread.is_alive():
        _left_behind.append(thread)
        return False, None, None
    return True, box.get("result"), box.get("error")


def _handshake():
    """The bytes a Dask client sends first: its handshake, as distributed's TCP comm frames it
    (total length, frame count, frame lengths, then a msgpack map)."""
    import msgpack  # a dependency of distributed, light to import

    body = msgpack.packb({"compression": None, "python": tuple(sys.version_info)[:3],
                          "pickle-protocol": pickle.HIGHEST_PROTOCOL}, use_bin_type=True)
    prelude = struct.pack("QQ", 1, len(body))
    return struct.pack("Q", len(prelude) + len(body)) + prelude + body


def _open(host, port, deadline):
    """A connected socket, or the reason there is none by the deadline."""
    found, addresses, error = _within(deadline - time.monotonic(),
                                      lambda: socket.getaddrinfo(host, port, type=socket.SOCK_STREAM))
    if not found:
        return None, f"no answer: looking up {host} took too long"
    if error is not None:
        return None, f"unknown host {host}" if isinstance(error, socket.gaierror) else str(error)
    reason = "no answer"
    while True:
        for family, kind, proto, _, where in addresses:
            left = deadline - time.monotonic()
            if left <= 0:
                return None, reason
            sock = socket.socket(family, kind, proto)
            sock.settimeout(left)
            try:
                sock.connect(where)
                return sock, None
            except socket.timeout:
                reason = "no answer"
            except ConnectionRefusedError:
                reason = "connection refused"
            except OSError as e:
                reason = (e.strerror or str(e)).lower()
            sock.close()
        time.sleep(max(0.0, min(_RETRY_S, deadline - time.monotonic())))


def _read(sock, count, deadline):
    """Up to `count` bytes, fewer when the peer closes or the deadline passes."""
    data = b""
    while len(data) < count:
        left = deadline - time.monotonic()
        if left <= 0:
            break
        sock.settimeout(left)
        try:
            chunk = sock.recv(count - len(data))
        except socket.timeout:
            break
        except OSError:
            break
        if not chunk:
            break
        data += chunk
    return data


def _greeting_problem(sock, deadline):
    """None when the peer greets as a Dask server does, else what it did instead."""
    head = _read(sock, 8, deadline)
    if not head:
        return "no answer" if time.monotonic() >= deadline else "no Dask handshake: it closed the connection"
    # A status line, or an HTTP/0.9 answer's bare page.
    if head.startswith((b"HTTP/", b"<")):
        return "no Dask handshake: is it an HTTP port?"
    if len(head) < 8:
        return f"no Dask handshake: it sent {head!r}"
    (total,) = struct.unpack("Q", head)
    if not 16 <= total <= _MAX_GREETING:
        return f"no Dask handshake: it sent {head!r}"
    # Read whole: closing with unread bytes would reset the connection before the server has
    # read our handshake, and a scheduler logs that.
    rest = _read(sock, total, deadline)
    if len(rest) < total:
        return "no Dask handshake: it stopped in the middle of one"
    (frames,) = struct.unpack_from("Q", rest)
    if not 1 <= frames <= 64 or 8 * (1 + frames) > total:
        return f"no Dask handshake: it sent {(head + rest)[:16]!r}"
    return None


def probe(address, timeout):
    """Checks within `timeout` seconds that a Dask server answers at `address`; FarmError
    naming the address and the reason otherwise. Returns the deadline it ran under."""
    deadline = time.monotonic() + timeout
    scheme, host, port = parse_address(address)
    sock, reason = _open(host, port, deadline)
    if sock is None:
        raise unreachable(address, timeout, reason)
    with sock:
        if scheme == "tls":
            return deadline  # the TLS handshake is the Client's, with the security it is given
        try:
            sock.settimeout(max(0.001, deadline - time.monotonic()))
            sock.sendall(_handshake())
            # Nothing more to say: an HTTP server that waits for the end of a request line then
            # answers "HTTP/1.x 400"; a Dask server has read a whole handshake and sees us leave.
            sock.shutdown(socket.SHUT_WR)
        except OSError as e:
            raise unreachable(address, timeout, (e.strerror or str(e)).lower()) from None
        reason = _greeting_problem(sock, deadline)
        if reason:
            raise unreachable(address, timeout, reason)
    return deadline


def unreachable(address, timeout, reason):
    return FarmError(f"cannot reach a Dask scheduler at {address} within {timeout:g} s ({reason})")


def quiet_distributed():
    """Distributed logs its own warnings and tracebacks on a failed connection; the one line
    this command prints says it all."""
    if not debugging():
        logging.getLogger("distributed").setLevel(logging.CRITICAL + 1)


def client(address, timeout):
    """A dask.distributed Client on the scheduler at `address`, created within about `timeout`
    seconds in all (probe included), whatever the peer does; FarmError otherwise."""
    deadline = probe(address, timeout)
    from dask.distributed import Client

    window = max(deadline - time.monotonic(), _CLIENT_FLOOR_S)
    level = logging.getLogger("distributed").level
    quiet_distributed()
    finished, made, error = _within(window, lambda: Client(address, timeout=window, set_as_default=False))
    if not finished:
        raise unreachable(address, timeout, "it answered the handshake, then nothing")
    if error is not None:
        _left_behind.append(error)
        if not isinstance(error, Exception):
            raise error
        raise unreachable(address, timeout, str(error).splitlines()[0] if str(error) else type(error).__name__)
    logging.getLogger("distributed").setLevel(level)
    return made
