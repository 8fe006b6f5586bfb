"""Run a batch on a Dask cluster (the optional extra ``dask``: ``pip install 'foon2asp[dask]'``).

The spec is scattered to every worker once; each builds its runners once per thread (a clingo
control is not shared between threads) and answers chunks of (goal, method) pairs.
"""

from __future__ import annotations

import threading
import uuid
from collections.abc import Callable, Iterator

from foon2asp.batch.pool import BatchSpec, Worker
from foon2asp.errors import InputError

_LOCAL = threading.local()


def _run_chunk(token: str, spec: BatchSpec, tasks: list[tuple[int, str]]) -> list[tuple[int, str, str]]:
    """On a Dask worker: the results of ``tasks`` (runners built once per thread and spec)."""
    if getattr(_LOCAL, "token", None) != token:
        _LOCAL.token, _LOCAL.worker = token, Worker(spec)
    return [(goal, method, _LOCAL.worker.run(goal, method)) for goal, method in tasks]


def executor(scheduler, chunk: int = 8) -> Callable[[BatchSpec, list[tuple[int, str]]], Iterator[tuple[int, str, str]]]:
    """A batch executor for :func:`foon2asp.batch.results.run_batch` on ``scheduler``
    (an address such as ``tcp://host:8786`` or a ``distributed.Client``)."""
    try:
        import distributed
    except ModuleNotFoundError:
        raise InputError(
            "--scheduler needs Dask: install the extra with  pip install 'foon2asp[dask]'  (dask[distributed])"
        ) from None

    def run(spec: BatchSpec, tasks: list[tuple[int, str]]) -> Iterator[tuple[int, str, str]]:
        if not tasks:
            return
        own = not isinstance(scheduler, distributed.Client)
        try:
            client = distributed.Client(scheduler) if own else scheduler
        except (OSError, ValueError, TypeError) as exc:
            raise InputError(f"cannot reach the Dask scheduler {scheduler}: {exc}") from None
        try:
            token = uuid.uuid4().hex
            [shared] = client.scatter([spec], broadcast=True)
            futures = [
                client.submit(_run_chunk, token, shared, tasks[i : i + chunk], pure=False)
                for i in range(0, len(tasks), chunk)
            ]
            for future in distributed.as_completed(futures):
                yield from future.result()
        finally:
            if own:
                client.close()

    return run
