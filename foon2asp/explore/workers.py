"""The explorer's worker processes and its cache of answers.

Each worker (:mod:`foon2asp.explore.worker`) holds the knowledge base and answers one job at a
time, so pages asking at once get their own answers side by side.  The same question asked again,
or asked by a second page while it is answered, is answered once.  A job past its deadline, or
left by every page that waited for it, is stopped with its process, and a fresh worker takes its
place; so is a worker after :data:`JOBS_PER_WORKER` jobs or once its memory has grown by
:data:`GROWTH_KB`, which keeps the memory flat.
"""

from __future__ import annotations

import asyncio
import contextlib
import gzip
import itertools
import json
import os
import signal
import sys
import time
from collections import OrderedDict
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Any

from foon2asp.errors import InputError
from foon2asp.explore.settings import Setup

#: a job left by every page is stopped once it has run this long (a shorter one finishes into the cache)
GRACE_S = 1.0
#: which jobs a free worker takes first (lower first): the tree before what is shown beside it
PRIORITY = {"tree": 0, "missing": 1, "export": 1, "baselines": 2, "schedule": 2}
#: a job is stopped after twice its time limit and this margin: an answer may solve twice (the tree,
#: then what is missing or its schedule), and grounding and drawing come on top
DEADLINE_MARGIN_S = 5.0
#: a worker is replaced after this many jobs, or once its memory has grown by this many kB since it
#: started (warm): the caches of the library and clingo's memory would otherwise grow with the questions
JOBS_PER_WORKER = 200
GROWTH_KB = 6 * 2**10
#: the most bytes of answers the cache keeps (compressed)
CACHE_BYTES = 4 * 2**20
#: the longest answer line a worker may write
LINE_LIMIT = 256 * 2**20


class Stopped(Exception):
    """A job was stopped: its deadline passed, or no page waits for it any more."""


@dataclass
class Job:
    """One question to a worker, and the pages waiting for its answer."""

    key: str
    payload: dict
    seconds: float
    answer: asyncio.Future = field(default_factory=lambda: asyncio.get_running_loop().create_future())
    waiting: int = 0
    started: float | None = None
    left: asyncio.Event = field(default_factory=asyncio.Event)


class Worker:
    """One worker process, started with the setup as its argument."""

    def __init__(self, setup: Setup) -> None:
        self.setup = setup
        self.proc: asyncio.subprocess.Process | None = None
        self.jobs = 0
        #: its memory (kB) once started, and after its last job
        self.memory = self.started_memory = 0
        #: has it loaded the knowledge base; is it answering a job
        self.ready = self.busy = False

    async def start(self) -> None:
        """Start the process and wait until it has loaded the knowledge base."""
        self.jobs, self.ready, self.busy = 0, False, False
        self.proc = await asyncio.create_subprocess_exec(
            sys.executable,
            "-m",
            "foon2asp.explore.worker",
            self.setup.to_json(),
            stdin=asyncio.subprocess.PIPE,
            stdout=asyncio.subprocess.PIPE,
            limit=LINE_LIMIT,
            start_new_session=True,  # a Ctrl+C at the terminal stops the server, which stops its workers
        )
        first = await self._read()
        if "error" in first:
            await self.stop()
            raise InputError(first["error"])
        self.memory = self.started_memory = first.get("memory", 0)
        self.ready = True

    async def ask(self, payload: dict) -> dict:
        """The worker's answer to one job."""
        assert self.proc is not None and self.proc.stdin is not None
        self.jobs += 1
        self.proc.stdin.write(json.dumps(payload).encode("utf-8") + b"\n")
        await self.proc.stdin.drain()
        answer = await self._read()
        self.memory = answer.get("memory", 0)
        return answer

    @property
    def worn(self) -> bool:
        """Should the worker be replaced (many jobs done, or its memory grown)?"""
        return self.jobs >= JOBS_PER_WORKER or self.memory > self.started_memory + GROWTH_KB

    async def _read(self) -> dict:
        assert self.proc is not None and self.proc.stdout is not None
        line = await self.proc.stdout.readline()
        if not line:
            code = await self.proc.wait()
            return {
                "error": f"internal error: a worker stopped (exit status {code}) -- please report it",
                "kind": "internal",
            }
        return json.loads(line)

    async def stop(self) -> None:
        """End the process (killed: it may be in the middle of a solve)."""
        self.ready = self.busy = False
        if self.proc is not None and self.proc.returncode is None:
            self.proc.kill()
            await self.proc.wait()
        self.proc = None


class Cache:
    """Answers by key, the least recently used dropped once they hold more than ``budget`` bytes."""

    def __init__(self, budget: int = CACHE_BYTES) -> None:
        self.budget, self.size = budget, 0
        self._items: OrderedDict[str, tuple[int, bytes]] = OrderedDict()

    def get(self, key: str) -> tuple[int, bytes] | None:
        found = self._items.get(key)
        if found is not None:
            self._items.move_to_end(key)
        return found

    def put(self, key: str, status: int, body: bytes) -> None:
        if key in self._items:
            self.size -= len(self._items.pop(key)[1])
        if len(body) > self.budget:
            return
        self._items[key] = (status, body)
        self.size += len(body)
        while self.size > self.budget:
            _, (_, dropped) = self._items.popitem(last=False)
            self.size -= len(dropped)

    def __len__(self) -> int:
        return len(self._items)


#: an answer as the server sends it: HTTP status and the JSON body, gzip-compressed
Reply = tuple[int, bytes]


def reply(status: int, value: Any) -> Reply:
    return status, gzip.compress(json.dumps(value).encode("utf-8"), 6)


def failure(message: str, status: int = 400) -> Reply:
    """A one-line error as the page shows it."""
    return reply(status, {"error": message})


class Pool:
    """The worker processes, the queue of jobs and the cache."""

    def __init__(self, setup: Setup) -> None:
        self.setup = setup
        self.cache = Cache()
        self._queue: asyncio.PriorityQueue[tuple[int, int, Job]] = asyncio.PriorityQueue()
        self._order = itertools.count()
        self._jobs: dict[str, Job] = {}
        self._workers = [Worker(setup) for _ in range(setup.workers)]
        self._runners: list[asyncio.Task] = []

    async def start(self) -> None:
        await asyncio.gather(*(w.start() for w in self._workers))
        self._runners = [asyncio.create_task(self._run(w)) for w in self._workers]

    async def close(self) -> None:
        for task in self._runners:
            task.cancel()
        await asyncio.gather(*self._runners, return_exceptions=True)
        await asyncio.gather(*(w.stop() for w in self._workers))

    def kill(self) -> None:
        """Kill every worker process now, without the event loop (what an interrupted close left)."""
        for worker in self._workers:
            if worker.proc is not None and worker.proc.returncode is None:
                with contextlib.suppress(ProcessLookupError):
                    os.kill(worker.proc.pid, signal.SIGKILL)

    def status(self) -> dict[str, int]:
        """How many workers there are, are ready and are busy; jobs waiting; answers cached."""
        ready = sum(w.ready for w in self._workers)
        busy = sum(w.busy for w in self._workers)
        return {
            "workers": len(self._workers),
            "ready": ready,
            "busy": busy,
            "waiting": self._queue.qsize(),
            "cached": len(self.cache),
        }

    async def answer(self, key: str, payload: dict, seconds: float, gone: Callable[[], Awaitable[Any]]) -> Reply:
        """The reply to ``payload`` (cached under ``key``), solved within ``seconds`` plus a
        margin; given up (and the job stopped when no other page waits) once ``gone()`` is done."""
        cached = self.cache.get(key)
        if cached is not None:
            return cached
        job = self._jobs.get(key)
        if job is None or job.left.is_set():  # a job being given up is not joined: it is asked again
            job = self._jobs[key] = Job(key, payload, seconds)
            self._queue.put_nowait((PRIORITY.get(payload["panel"], 3), next(self._order), job))
        job.waiting += 1
        leaving = asyncio.ensure_future(gone())
        try:
            await asyncio.wait({job.answer, leaving}, return_when=asyncio.FIRST_COMPLETED)
            if job.answer.done():
                return job.answer.result()
            return failure("cancelled", 499)
        finally:
            leaving.cancel()
            job.waiting -= 1
            if job.waiting == 0 and not job.answer.done():
                job.left.set()

    async def _run(self, worker: Worker) -> None:
        """Take jobs off the queue one by one and answer each on ``worker``."""
        while True:
            *_, job = await self._queue.get()
            if job.left.is_set():
                self._finish(job, failure("cancelled", 499), keep=False)
                continue
            job.started = time.monotonic()
            asked = asyncio.ensure_future(worker.ask(job.payload))
            worker.busy = True
            try:
                answer = await self._watch(job, asked)
            except Stopped as why:
                await worker.stop()
                self._finish(job, failure(str(why), 504 if "within" in str(why) else 499), keep=False)
                await self._restart(worker)
                continue
            except Exception as exc:  # the worker's pipes broke: it is gone
                await worker.stop()
                self._finish(job, failure(f"internal error: a worker failed ({type(exc).__name__})", 500), keep=False)
                await self._restart(worker)
                continue
            worker.busy = False
            if "ok" in answer:
                self._finish(job, reply(200, answer["ok"]), keep=True)
            else:
                internal = answer.get("kind") == "internal"
                self._finish(job, failure(answer["error"], 500 if internal else 400), keep=not internal)
                if internal and (worker.proc is None or worker.proc.returncode is not None):
                    await self._restart(worker)
                    continue
            if worker.worn:
                await worker.stop()
                await self._restart(worker)

    async def _watch(self, job: Job, asked: asyncio.Future) -> dict:
        """The worker's answer to ``job``; :class:`Stopped` past the deadline or once every page left."""
        deadline = 2 * job.seconds + DEADLINE_MARGIN_S
        left = asyncio.ensure_future(job.left.wait())
        try:
            while True:
                elapsed = time.monotonic() - (job.started or 0.0)
                if elapsed >= deadline:
                    raise Stopped(f"no answer within {deadline:g} s: stopped (time-limit {job.seconds:g} s)")
                wait = deadline - elapsed
                if left.done():
                    if elapsed >= GRACE_S:
                        raise Stopped("cancelled")
                    wait = min(wait, GRACE_S - elapsed)
                    await asyncio.wait({asked}, timeout=wait)
                else:
                    await asyncio.wait({asked, left}, timeout=wait, return_when=asyncio.FIRST_COMPLETED)
                if asked.done():
                    return asked.result()
        finally:
            left.cancel()
            if not asked.done():
                asked.cancel()

    def _finish(self, job: Job, answer: Reply, keep: bool) -> None:
        if keep:
            self.cache.put(job.key, *answer)
        if self._jobs.get(job.key) is job:
            del self._jobs[job.key]
        if not job.answer.done():
            job.answer.set_result(answer)

    async def _restart(self, worker: Worker) -> None:
        """A fresh process for ``worker`` (tried again a second later while starting one fails)."""
        while True:
            try:
                await worker.start()
                return
            except Exception as exc:
                print(f"foon2asp: warning: a worker could not start: {exc}", file=sys.stderr)
                await asyncio.sleep(1.0)
