#!/usr/bin/env python3
"""A FOON with real choice from recipes: all files of ../shared/foon-111 merged into one.

Each recipe file is a small subgraph; merged, an object that several recipes make (a chopped
onion, whipped cream, ...) gets several producers, so goals have real alternatives.  The
kitchen is every object that no unit makes (the recipes' raw items, tools and containers);
the goals are the objects that some unit makes and no unit uses (the recipes' dishes).
motion.txt and utensils.txt come from ../shared/foon.

    python bench/foon111.py --shared ../shared DIR     # writes DIR/FOON.txt, kitchen.json, ...

``build(shared)`` returns the data folder's Dataset without writing anything.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from foon2asp.foon.loaders import Dataset  # noqa: E402
from foon2asp.foon.model import Foon, FoonObject  # noqa: E402
from foon2asp.foon.parser import read_foons, write_foon  # noqa: E402


def kitchen_and_goals(foon: Foon) -> tuple[list[FoonObject], list[FoonObject]]:
    """(objects no unit makes, objects made and used by no unit), each in first-seen order."""
    made = {o for u in foon.units for o in u.outputs}
    used = {o for u in foon.units for o in u.inputs}
    seen: dict[FoonObject, None] = {}
    for u in foon.units:
        for o in (*u.inputs, *u.outputs):
            seen.setdefault(o, None)
    kitchen = [o for o in seen if o not in made]
    goals = [o for o in seen if o in made and o not in used and not o.is_bare()]
    return kitchen, goals


def write(shared: Path, out: Path) -> tuple[int, int, int]:
    """Write the merged FOON and its kitchen and goals to ``out``: (units, kitchen items, goals)."""
    files = sorted((shared / "foon-111").glob("*.txt"))
    foon = read_foons(files)
    kitchen, goals = kitchen_and_goals(foon)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "FOON.txt", "w", encoding="utf-8") as fh:
        write_foon(foon, fh, header=f"foon-111 merged: {len(files)} recipes")
    (out / "kitchen.json").write_text(json.dumps([o.to_json() for o in kitchen], indent=1), encoding="utf-8")
    (out / "goal_nodes.json").write_text(json.dumps([o.to_json() for o in goals], indent=1), encoding="utf-8")
    for name in ("motion.txt", "utensils.txt"):
        shutil.copy(shared / "foon" / name, out / name)
    return len(foon.units), len(kitchen), len(goals)


def build(shared: Path, out: Path) -> Dataset:
    """The merged data set (written to ``out`` first)."""
    write(shared, out)
    return Dataset.load(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shared", default=str(ROOT.parent / "shared"))
    ap.add_argument("out")
    args = ap.parse_args()
    units, kitchen, goals = write(Path(args.shared), Path(args.out))
    print(f"{units} units, {kitchen} kitchen items, {goals} goals -> {args.out}")


if __name__ == "__main__":
    main()
