"""One worker process of the explorer (``python -m foon2asp.explore.worker SETUP``): it loads the
knowledge base once, then reads one job per line on stdin and writes one answer per line on stdout."""

from __future__ import annotations

import ctypes
import json
import os
import resource
import signal
import sys
import traceback
from typing import IO, Any

from foon2asp.errors import InputError, escape
from foon2asp.explore.panels import Answers, error_line
from foon2asp.explore.params import Question
from foon2asp.explore.settings import Setup

#: the most memory (address space, bytes) a worker may take beyond what it holds once loaded: a rule
#: that grounds without end stops there
MEMORY_LIMIT = 3 * 2**30


def run(answers: Answers, job: dict) -> dict[str, Any]:
    """The answer to ``job`` (``panel``, ``question``, ``fmt``): ``{"ok": value}``, or ``{"error":
    one line, "kind": "input" | "internal"}``."""
    try:
        question = Question.from_dict(job["question"])
        return {"ok": answers.answer(job["panel"], question, job.get("fmt"))}
    except InputError as exc:
        return {"error": error_line(exc), "kind": "input"}
    except (RecursionError, MemoryError) as exc:
        return {"error": f"input too large or too deeply nested ({type(exc).__name__})", "kind": "input"}
    except Exception as exc:
        if "bad_alloc" in str(exc):
            return {"error": "the answer needs more memory than a worker may take", "kind": "input"}
        traceback.print_exception(exc)
        text = escape(" ".join(str(exc).split()))[:500]
        return {"error": f"internal error: {type(exc).__name__}: {text} -- please report it", "kind": "internal"}


def send(out: IO[str], answer: dict) -> None:
    out.write(json.dumps(answer) + "\n")
    out.flush()


def resident() -> int:
    """This process's resident memory (kB), after handing freed memory back to the system."""
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass
    return _status("VmRSS:")


def _status(field: str) -> int:
    """A kB figure of /proc/self/status (0 where there is none)."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            return next((int(line.split()[1]) for line in status if line.startswith(field)), 0)
    except OSError:
        return 0


def warm(answers: Answers) -> None:
    """Answer the goals file's first goal once, so that a worker's memory is measured warm."""
    goals = answers.kb.file_goals()
    if goals:
        run(answers, {"panel": "tree", "question": Question(goal=f"#{goals[0]}").to_dict()})


def limit_memory() -> None:
    """Let the process's address space grow by at most :data:`MEMORY_LIMIT` from now on."""
    size = _status("VmSize:") * 1024
    if not size:
        return  # not known here: no limit
    _, hard = resource.getrlimit(resource.RLIMIT_AS)
    wanted = size + MEMORY_LIMIT
    if hard == resource.RLIM_INFINITY or hard > wanted:
        resource.setrlimit(resource.RLIMIT_AS, (wanted, hard))


def main(argv: list[str]) -> int:
    """Load the setup's knowledge base, say ``ready`` (or the error), then answer jobs until stdin
    ends; each answer says the worker's ``memory`` (kB) then."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the server stops its workers itself
    out = os.fdopen(os.dup(1), "w", encoding="utf-8")
    os.dup2(2, 1)  # anything else printed goes to stderr, not into the answers
    try:
        answers = Answers(Setup.from_json(argv[0]))
    except InputError as exc:
        send(out, {"error": error_line(exc), "kind": "input"})
        return 2
    warm(answers)
    limit_memory()
    send(out, {"ready": True, "memory": resident()})
    for line in sys.stdin:
        send(out, {**run(answers, json.loads(line)), "memory": resident()})
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
