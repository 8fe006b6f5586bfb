"""The explorer as an ASGI application (Starlette): the page, its script and style, and the answers
it asks for as JSON, each a one-line error when the question is bad.

``/`` is the page for any question in its address; ``/api/tree``, ``/api/missing``,
``/api/baselines``, ``/api/schedule`` and ``/api/export/FORMAT`` answer the question of their query parameters
(:mod:`foon2asp.explore.params`), ``/api/suggest?q=TEXT`` names the objects ``TEXT`` matches,
``/api/info`` what the page offers and ``/api/status`` how busy the workers are.
"""

from __future__ import annotations

import asyncio
import contextlib
import gzip
import json
from collections.abc import AsyncIterator
from importlib import resources
from typing import Any

from starlette.applications import Starlette
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import HTMLResponse, JSONResponse, Response
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles
from starlette.types import ASGIApp, Receive, Scope, Send

from foon2asp import __version__, api
from foon2asp.errors import BAD_CHAR, InputError, char_name
from foon2asp.explore.panels import BASELINES, EXPORTS, error_line
from foon2asp.explore.params import MAX_QUERY, Question
from foon2asp.explore.settings import DEFAULT_SECONDS, Setup
from foon2asp.explore.workers import Pool, failure

#: the page's files, shipped in the package
STATIC = resources.files("foon2asp.explore") / "static"
#: the answers ``/api/NAME`` gives
PANELS = ("tree", "missing", "baselines", "schedule")
#: the most objects a suggestion lists
MAX_SUGGESTIONS = 30
#: the host names a page on this machine is reached by (anything else, e.g. a rebound DNS name, is refused)
LOOPBACK = ["127.0.0.1", "localhost", "[::1]", "::1"]


class SizeLimit:
    """Refuse a request whose address is longer than :data:`MAX_QUERY` characters, in one line."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http" and len(scope.get("query_string", b"")) + len(scope["path"]) > MAX_QUERY:
            message = f"the request is too long (at most {MAX_QUERY} characters of address)"
            await JSONResponse({"error": message}, 414)(scope, receive, send)
            return
        await self.app(scope, receive, send)


async def _gone(request: Request) -> None:
    """Return once the page that sent ``request`` has gone (closed, reloaded or cancelled)."""
    while True:
        message = await request.receive()
        if message["type"] == "http.disconnect":
            return


def _reply(request: Request, status: int, body: bytes) -> Response:
    """A reply (its body gzip-compressed) as the page takes it: compressed when it accepts that."""
    if "gzip" in request.headers.get("accept-encoding", ""):
        headers = {"Content-Encoding": "gzip", "Vary": "Accept-Encoding"}
        return Response(body, status, media_type="application/json", headers=headers)
    return Response(gzip.decompress(body), status, media_type="application/json")


class Explorer:
    """The routes of one explorer: its setup, the knowledge base for suggestions, the workers."""

    def __init__(self, setup: Setup, kb: api.KnowledgeBase | None = None) -> None:
        self.setup = setup
        self.kb = kb if kb is not None else setup.load()
        self.pool = Pool(setup)
        self._page: str | None = None

    async def page(self, request: Request) -> Response:
        """The page, with what it offers (:meth:`offer`) in it."""
        if self._page is None:
            found = json.dumps(self.offer()).replace("</", "<\\/")
            self._page = (STATIC / "index.html").read_text(encoding="utf-8").replace("{INFO}", found)
        return HTMLResponse(self._page)

    async def info(self, request: Request) -> Response:
        return JSONResponse(self.offer())

    def offer(self) -> dict[str, Any]:
        """What the page offers: objectives, limits, default agents, the goals file's goals."""
        objectives = [o for o in api.OBJECTIVES if o != "cost" or self.setup.motion_cost is not None]
        goals = [self.kb.object_info(g) for g in self.kb.file_goals()]
        return {
            "version": __version__,
            "data": self.setup.path or ", ".join(self.setup.foon),
            "objectives": objectives,
            "time_limit": self.setup.time_limit,
            "seconds": min(DEFAULT_SECONDS, self.setup.time_limit),
            "agents": self.setup.agents or "robot=1",
            "baselines": list(BASELINES),
            "exports": list(EXPORTS),
            "goals": [{"id": g["id"], "text": g["text"], "label": g["label"]} for g in goals],
        }

    async def status(self, request: Request) -> Response:
        """The workers: how many, ready, busy; the jobs waiting and the answers cached."""
        return JSONResponse(self.pool.status())

    async def suggest(self, request: Request) -> Response:
        """The objects the text ``q`` names, as ``--goal`` matches them (goals-file goals, then
        objects some unit makes, then the rest); an empty text: the goals file's goals."""
        text = request.query_params.get("q", "")[:1000]
        try:
            found = await asyncio.to_thread(self._suggest, text)
        except InputError as exc:
            return JSONResponse({"error": error_line(exc)}, 400)
        return JSONResponse(found)

    def _suggest(self, text: str) -> dict[str, Any]:
        bad = BAD_CHAR.search(text)
        if bad:
            raise InputError(f"q: {char_name(bad.group(0))} is not allowed")
        goals = self.kb.file_goals()
        ids = self.kb.find_objects(text) if text.strip() else goals
        first = set(goals)
        infos = [self.kb.object_info(i) for i in ids[: 20 * MAX_SUGGESTIONS]]
        infos.sort(key=lambda i: (i["id"] not in first, not i["producers"]))
        shown = [
            {"id": i["id"], "text": i["text"], "label": i["label"], "kitchen": i["in_kitchen"], "made": i["producers"]}
            for i in infos[:MAX_SUGGESTIONS]
        ]
        return {"count": len(ids), "objects": shown}

    async def panel(self, request: Request) -> Response:
        """The answer ``tree``, ``missing``, ``baselines`` or ``schedule`` to the question of the address."""
        name = request.path_params["panel"]
        if name not in PANELS:
            return _reply(request, *failure(f"no such answer {name[:40]!r} (have {', '.join(PANELS)})", 404))
        return _reply(request, *await self._answer(request, name, None))

    async def export(self, request: Request) -> Response:
        """The tree on screen as a file (``foon``, ``json``, ``svg``, ``pddl-domain``, ``pddl-problem``)."""
        fmt = request.path_params["fmt"]
        if fmt not in EXPORTS:
            return _reply(request, *failure(f"unknown export {fmt[:40]!r} (have {', '.join(EXPORTS)})", 404))
        status, body = await self._answer(request, "export", fmt)
        if status != 200:
            return _reply(request, status, body)
        found = json.loads(gzip.decompress(body))
        disposition = f'attachment; filename="{found["name"]}"'
        return Response(found["text"], media_type=found["media"], headers={"Content-Disposition": disposition})

    async def _answer(self, request: Request, panel: str, fmt: str | None) -> tuple[int, bytes]:
        try:
            question = Question.parse(request.query_params.multi_items(), self.setup.time_limit)
        except InputError as exc:
            return failure(error_line(exc))
        asked = question.only("tree" if panel == "export" else panel)
        payload = {"panel": panel, "question": asked.to_dict(), "fmt": fmt}
        key = json.dumps(payload, sort_keys=True)
        seconds = question.time_limit or min(DEFAULT_SECONDS, self.setup.time_limit)
        return await self.pool.answer(key, payload, seconds, lambda: _gone(request))

    def app(self, loopback: bool = True, lifespan: bool = True) -> Starlette:
        """The application of these routes (``lifespan``: it starts and stops the workers; else
        the caller does, with ``pool.start()`` and ``pool.close()``)."""
        routes = [
            Route("/", self.page),
            Route("/api/info", self.info),
            Route("/api/status", self.status),
            Route("/api/suggest", self.suggest),
            Route("/api/export/{fmt}", self.export),
            Route("/api/{panel:str}", self.panel),
            Mount("/static", StaticFiles(directory=str(STATIC)), name="static"),
        ]
        middleware = [Middleware(SizeLimit)]
        if loopback:
            middleware.append(Middleware(TrustedHostMiddleware, allowed_hosts=LOOPBACK))
        return Starlette(
            routes=routes,
            middleware=middleware,
            lifespan=self.lifespan if lifespan else None,
            exception_handlers={Exception: _internal_error},
        )

    @contextlib.asynccontextmanager
    async def lifespan(self, app: Starlette) -> AsyncIterator[None]:
        await self.pool.start()
        try:
            yield
        finally:
            await self.pool.close()


def make_app(setup: Setup, kb: api.KnowledgeBase | None = None, loopback: bool = True) -> Starlette:
    """The explorer of ``setup`` (``kb``: its knowledge base, loaded already), its workers started
    and stopped with the application's lifespan; ``loopback``: only requests addressed to this
    machine's loopback names are answered."""
    return Explorer(setup, kb).app(loopback)


async def _internal_error(request: Request, exc: Exception) -> Response:
    """A failure of the explorer itself: one line for the page (the server's log has the traceback)."""
    message = f"internal error: {type(exc).__name__}: {' '.join(str(exc).split())[:300]} -- please report it"
    return JSONResponse({"error": message}, 500)
