"""Serving the explorer on this machine: 127.0.0.1 and a free port unless told otherwise, the
address printed once the page can be asked, the browser opened on request."""

from __future__ import annotations

import asyncio
import ipaddress
import socket
import sys
import threading
import webbrowser
from collections.abc import Callable

import uvicorn

from foon2asp import api
from foon2asp.errors import InputError
from foon2asp.explore.app import Explorer
from foon2asp.explore.settings import Setup

#: the most bytes of a request's head uvicorn reads: a longer address than the explorer takes gets its
#: one-line error, not a closed connection
HEAD_BYTES = 256 * 2**10


def is_loopback(host: str) -> bool:
    """Is ``host`` this machine's loopback address (127.0.0.0/8, ::1, localhost)?"""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def listen(host: str, port: int | None) -> socket.socket:
    """A socket listening on ``host`` at ``port`` (None or 0: a free port)."""
    if port is not None and (isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535):
        raise InputError(f"--port must be 0..65535, not {port!r}")
    bare = host.strip("[]")
    try:
        family = socket.AF_INET6 if ":" in bare else socket.AF_INET
        sock = socket.socket(family, socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        sock.bind((bare, port or 0))
        sock.listen(128)
    except OSError as exc:
        raise InputError(f"cannot listen on {host} port {port or 0}: {exc.strerror or exc}") from None
    sock.setblocking(False)
    return sock


def address(sock: socket.socket, host: str) -> str:
    """The page's address on ``sock``."""
    port = sock.getsockname()[1]
    shown = f"[{host.strip('[]')}]" if ":" in host else host
    return f"http://{shown}:{port}/"


def serve(
    setup: Setup,
    kb: api.KnowledgeBase | None = None,
    *,
    host: str = "127.0.0.1",
    port: int | None = None,
    open_browser: bool = False,
    say: Callable[[str], None] | None = None,
    warn: Callable[[str], None] | None = None,
) -> None:
    """Serve the explorer of ``setup`` (``kb``: its knowledge base, loaded already) until
    interrupted; ``say`` gets the address, ``warn`` the warnings (default: printed)."""
    say = say or (lambda text: print(text, flush=True))
    warn = warn or (lambda text: print(f"foon2asp: warning: {text}", file=sys.stderr, flush=True))
    if kb is None:
        kb = setup.load()
        for warning in kb.warnings:
            warn(warning)
    loopback = is_loopback(host)
    if not loopback:
        warn(f"listening on {host}: anyone who can reach this machine there can use the explorer (it has no login)")
    sock = listen(host, port)
    url = address(sock, host)
    explorer = Explorer(setup, kb)
    # the workers are started and stopped here, not in uvicorn's lifespan: a second Ctrl+C skips that
    config = uvicorn.Config(
        explorer.app(loopback, lifespan=False),
        log_level="warning",
        access_log=False,
        lifespan="off",
        h11_max_incomplete_event_size=HEAD_BYTES,
    )
    server = uvicorn.Server(config)

    async def run() -> None:
        await explorer.pool.start()
        try:
            say(f"foon2asp explore: {url} (Ctrl+C stops it)")  # the socket listens already
            if open_browser:
                threading.Thread(target=webbrowser.open, args=(url,), daemon=True).start()
            await server.serve(sockets=[sock])
        finally:
            await explorer.pool.close()

    try:
        asyncio.run(run())
    finally:
        explorer.pool.kill()  # a second Ctrl+C may have cut their stop short
        sock.close()
    if not server.started:
        raise InputError("the explorer did not start (see the messages above)")
