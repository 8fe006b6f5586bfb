"""Where the demo data set lives (``data/`` in the source tree, ``foon2asp.demo`` when installed)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

_SOURCE = Path(__file__).resolve().parents[2] / "data"


def demo_dir() -> Path:
    """The folder holding the demo FOON.txt, kitchen.json, goal_nodes.json, motion.txt, utensils.txt."""
    try:
        root = resources.files("foon2asp.demo")
        # an installed namespace package is a MultiplexedPath: go through one of its files
        probe = Path(str(root.joinpath("FOON.txt")))
        if probe.is_file():
            return probe.parent
    except ModuleNotFoundError:
        pass
    return _SOURCE
