"""Unit tests of the encodings themselves: tests/lp/*.lp, each with its expectation.

Header lines: ``%! encodings: NAME ...`` (loaded from encodings/), then
``%! unsat`` or ``%! optimum: N[,M...]`` and optionally ``%! use: U ...``
(the used units of the optimum, which must be unique).
"""

from __future__ import annotations

from pathlib import Path

import clingo
import pytest

from foon2asp.asp import encodings

CASES = sorted((Path(__file__).parent / "lp").glob("*.lp"))


def header(text: str) -> dict[str, str]:
    out = {}
    for line in text.splitlines():
        if line.startswith("%!"):
            key, _, value = line[2:].strip().partition(":")
            out[key.strip()] = value.strip()
    return out


@pytest.mark.parametrize("case", CASES, ids=[c.stem for c in CASES])
def test_lp_case(case: Path):
    text = case.read_text()
    spec = header(text)
    ctl = clingo.Control(["--opt-mode=optN", "0"])
    for name in spec["encodings"].split():
        ctl.add("base", [], encodings.encoding(name))
    ctl.add("base", [], text)
    ctl.ground([("base", [])])
    optimal = []
    with ctl.solve(yield_=True) as handle:
        for model in handle:
            if model.optimality_proven:
                optimal.append((list(model.cost), sorted(s.arguments[0].number for s in model.symbols(shown=True))))
        result = handle.get()
    if "unsat" in spec:
        assert result.unsatisfiable
        return
    assert result.satisfiable and optimal
    assert optimal[0][0] == [int(x) for x in spec["optimum"].split(",")]
    if "use" in spec:
        assert [u for _, u in optimal] == [[int(x) for x in spec["use"].split()]]


def test_cases_exist():
    assert len(CASES) >= 4
