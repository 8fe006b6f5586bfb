"""The default solver settings, in one place (chosen on the hard benchmark: BENCHMARKS.md).

Every answer that comes from clingo builds its clingo arguments with :func:`solver_args`.
A user who sets nothing gets, on one thread, core-guided optimisation
(:data:`DEFAULT_OPT_STRATEGY`, with :data:`DEFAULT_TUNING`), and with ``--threads N``
(N >= 2) a portfolio of one branch-and-bound and one such core-guided solver
(:data:`PORTFOLIO`, clasp's configuration-file format; more threads repeat its lines).
``--opt-strategy`` always wins: it is passed on as given, for every thread.
"""

from __future__ import annotations

import hashlib
import os
import tempfile

#: the optimisation strategy when the user sets none (one thread)
DEFAULT_OPT_STRATEGY = "usc,oll,succinct,stratify"
#: clasp options that go with it: shrink each core by binary search, clasp's "trendy" configuration
DEFAULT_TUNING = ("--opt-usc-shrink=bin", "--configuration=trendy")

#: the portfolio for --threads >= 2 without --opt-strategy: one solver per line, ``[name]: <clasp options>``
PORTFOLIO = f"[bbsign]: --opt-strategy=bb --opt-heuristic=sign,model\n[usc]: --opt-strategy={DEFAULT_OPT_STRATEGY} {DEFAULT_TUNING[0]}\n"


def portfolio_file(text: str = PORTFOLIO) -> str:
    """A configuration file holding ``text`` for clingo's ``--configuration`` (written once,
    named by its content, in the temporary directory; worker processes share it)."""
    digest = hashlib.sha256(text.encode()).hexdigest()[:16]
    path = os.path.join(tempfile.gettempdir(), f"foon2asp-portfolio-{digest}.cfg")
    try:
        with open(path, encoding="utf-8") as fh:
            if fh.read() == text:
                return path
    except OSError:
        pass
    fd, tmp = tempfile.mkstemp(prefix="foon2asp-portfolio-", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as fh:
        fh.write(text)
    os.replace(tmp, path)  # atomic: a reader sees the old file or the whole new one
    return path


def solver_args(opt_strategy: str | None = None, threads: int = 1, portfolio: str | None = None) -> list[str]:
    """clingo arguments for an optimisation strategy (None: the default), a number of threads
    and (threads > 1, no strategy) a portfolio in clasp's file format (None: :data:`PORTFOLIO`)."""
    parallel = [f"--parallel-mode={threads}"] if threads and threads > 1 else []
    if opt_strategy:
        return [f"--opt-strategy={opt_strategy}", *parallel]
    if parallel:
        return [*parallel, f"--configuration={portfolio_file(portfolio or PORTFOLIO)}"]
    return [f"--opt-strategy={DEFAULT_OPT_STRATEGY}", *DEFAULT_TUNING]
