"""Shared fixtures: paths to ../shared and the demo data, small problem builders."""

from __future__ import annotations

import signal
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
# the signal tests interrupt this process and its children: a run started in the background of
# a non-interactive shell inherits SIGINT ignored, which would make them meaningless
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.path.insert(0, str(HERE))  # for `import helpers`

REPO = HERE.parent
sys.path.insert(0, str(REPO / "bench"))  # for `import synth`: the seeded synthetic FOONs
SHARED = REPO.parent / "shared"
DEMO = REPO / "data"


@pytest.fixture(scope="session")
def shared_foon_dir() -> Path:
    path = SHARED / "foon"
    if not (path / "FOON.txt").is_file():
        pytest.skip("../shared/foon is not beside the checkout")
    return path


@pytest.fixture(scope="session")
def shared_111_dir() -> Path:
    path = SHARED / "foon-111"
    if not path.is_dir():
        pytest.skip("../shared/foon-111 is not beside the checkout")
    return path


@pytest.fixture(scope="session")
def shared_problem(shared_foon_dir):
    from foon2asp.foon.loaders import Dataset
    from foon2asp.foon.problem import Problem

    data = Dataset.load(shared_foon_dir)
    return data, Problem.from_dataset(data)


@pytest.fixture(scope="session")
def demo_problem():
    from foon2asp.foon.loaders import Dataset
    from foon2asp.foon.problem import Problem

    data = Dataset.load(DEMO)
    return data, Problem.from_dataset(data)


@pytest.fixture(scope="session")
def hard():
    """The hard-4k preset's problem and its goals' ids (generated once per test run)."""
    from synth import preset

    syn = preset("hard-4k")
    problem = syn.problem()
    return problem, [problem.foon.object_ids[g] for g in syn.goals]
