"""The options the commands share, each declared once.

The data options become one :class:`DataArgs` value (``data``); the request's objective,
time limit, constraints and solver settings become one :class:`foon2asp.api.Options` value
(``options``), filled by every decorator that declares some of them (:func:`request_options`).
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import click

from foon2asp import api, report
from foon2asp.cli.main import main
from foon2asp.cli.output import EXIT_CODES, warn_all
from foon2asp.cli.params import GAP, SECONDS, int32
from foon2asp.errors import InputError


def stacked(func: Callable, decorators: Sequence[Callable]) -> Callable:
    """``func`` under ``decorators``, the first outermost (as if written above it in this order)."""
    for decorate in reversed(decorators):
        func = decorate(func)
    return func


def choice_option(*names: str, choices: Sequence[str], default: str | None = None, help: str | None = None):
    """An option taking one of ``choices`` (the default shown in the help)."""
    return click.option(*names, type=click.Choice(choices), default=default, show_default=True, help=help)


def request_options(keys: dict[str, str], *opts: Callable, check: Callable[[dict], None] | None = None):
    """A decorator adding the click options ``opts``; the values of their parameters (``keys``:
    parameter name -> keyword of :meth:`foon2asp.api.Options.of`) go into ``options``."""

    def decorate(func):
        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            values = {key: kwargs.pop(param) for param, key in keys.items()}
            if check is not None:
                check(values)
            kwargs["options"] = api.Options.of(kwargs.pop("options", None), **values)
            return func(*args, **kwargs)

        return stacked(wrapper, opts)

    return decorate


# ---------------------------------------------------------------- looser matching


@dataclass(frozen=True)
class MatchArgs:
    """--level, --normalize, --synonyms FILE (how objects are compared), --substitutes FILE and
    --max-substitutions N (what may stand in for what)."""

    level: int = 3
    normalize: bool = False
    synonyms: str | None = None
    substitutes: str | None = None
    max_substitutions: int | None = None

    def __post_init__(self) -> None:
        if self.max_substitutions is not None and self.substitutes is None:
            raise InputError("--max-substitutions needs --substitutes FILE")

    @property
    def load_args(self) -> dict:
        """The keywords of :func:`foon2asp.api.load` these options give."""
        return {"level": self.level, "normalize": self.normalize, "synonyms": self.synonyms}

    def request(self, options: api.Options | None = None) -> api.Options:
        """``options`` with the substitutes of these options."""
        if self.substitutes is None:
            return options or api.Options()
        return api.Options.of(options, substitutes=self.substitutes, max_substitutions=self.max_substitutions)


MATCH_OPTIONS = [
    click.option(
        "--level",
        type=click.IntRange(1, 3),
        default=3,
        show_default=True,
        metavar="1|2|3",
        help="FOON's hierarchy level objects are compared at: 1 labels, 2 labels and states (with the container),"
        " 3 also ingredients.",
    ),
    click.option(
        "--normalize",
        is_flag=True,
        help="Compare labels, states and ingredients case-folded, white space collapsed, the last word singular.",
    ),
    click.option(
        "--synonyms", type=click.Path(), metavar="FILE", help="Lines 'name = canonical name': names compared as one."
    ),
    click.option(
        "--substitutes",
        type=click.Path(),
        metavar="FILE",
        help='What may stand in for a missing kitchen item: JSON {"onion": ["red onion"]} or lines'
        " 'onion: red onion, shallot =2'; trees use the fewest (cheapest) substitutions first.",
    ),
    click.option("--max-substitutions", type=int32(min=0), metavar="N", help="At most N substitutions per tree."),
]


def joined_lines(joined: dict[str, list[str]]) -> list[str]:
    """``joined 'Blueberries', 'blueberries' as 'blueberry'``: one line per text spelled several ways."""
    return [f"joined {', '.join(repr(s) for s in spellings[1:])} as {first!r}" for first, spellings in joined.items()]


def _match_args(kwargs: dict) -> MatchArgs:
    return MatchArgs(**{k: kwargs.pop(k) for k in MatchArgs.__dataclass_fields__})


def match_options(func):
    """The looser-matching options (:data:`MATCH_OPTIONS`) as one ``match`` value (:class:`MatchArgs`)."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        return func(*args, match=_match_args(kwargs), **kwargs)

    return stacked(wrapper, MATCH_OPTIONS)


# ---------------------------------------------------------------- the data


@dataclass(frozen=True)
class DataArgs:
    """The data options of a command (--data, --foon, --kitchen, --motion, --utensils, --utensil-rule, --strict)."""

    data_dir: str | None
    foon: tuple[str, ...]
    kitchen: str | None
    motion: str | None
    utensils: str | None
    utensil_rule: str
    strict: bool
    match: MatchArgs = MatchArgs()

    def load(self, goals_file: str | None = None) -> api.KnowledgeBase:
        """The knowledge base these options name (``goals_file``: a ``--goals FILE`` to read); its
        warnings go to stderr.  Never the demo data unless asked."""
        if self.data_dir is None and not self.foon:
            raise InputError(
                "no data given: use --data DIR, --foon FILE (with kitchen.json ... beside it) or --data demo"
            )
        files = {k: getattr(self, k) for k in ("kitchen", "motion", "utensils", "utensil_rule", "strict")}
        goals = goals_file if goals_file not in (None, "all", "all-objects") else None
        foon = list(self.foon) if self.foon else None
        kb = api.load(self.data_dir, foon=foon, goals=goals, **files, **self.match.load_args)
        warn_all(kb.warnings)
        return kb

    def load_goals(
        self, goal: tuple[str, ...], goals: str | None, together: bool = False
    ) -> tuple[api.KnowledgeBase, list]:
        """The knowledge base (:meth:`load`) and the goals ``--goal`` and ``--goals`` name
        (``together``: one meal of them, a tuple)."""
        kb = self.load(goals)
        ids = kb.select_goals(goal, goals)
        return kb, [tuple(dict.fromkeys(ids))] if together else ids


STRICT_HELP = "Treat skipped units of FOON and tree files (warnings) as errors."
KITCHEN_HELP = (
    "kitchen.json, or 'leaves': every object no unit of the FOON makes (merged generated trees have no kitchen)."
)

#: --motion, --utensils, --utensil-rule and --strict
FILE_OPTIONS = [
    click.option("--motion", type=click.Path(), help="motion.txt (motion TAB success rate)"),
    click.option("--utensils", type=click.Path(), help="utensils.txt"),
    choice_option(
        "--utensil-rule",
        choices=api.UTENSIL_RULES,
        default="starter",
        help="When a utensil holding one ingredient is not a required input.",
    ),
    click.option("--strict", is_flag=True, help=STRICT_HELP),
]


def file_options(func):
    """:data:`FILE_OPTIONS` (for a command without the other data options)."""
    return stacked(func, FILE_OPTIONS)


def data_options(func, with_kitchen: bool = True):
    """--data DIR and the per-file overrides, plus --utensil-rule, --strict and the looser-matching
    options, passed on as one ``data`` value (:class:`DataArgs`); a command that takes ``options``
    gets the substitutes there too.  ``with_kitchen=False`` leaves out ``--kitchen FILE``."""
    opts = [
        click.option(
            "--data",
            "data_dir",
            type=click.Path(),
            help="Directory with FOON.txt, kitchen.json, goal_nodes.json, motion.txt, utensils.txt;"
            " 'demo' for the demo data set shipped with foon2asp.",
        ),
        click.option(
            "--foon",
            "foon",
            type=click.Path(),
            multiple=True,
            help="FOON file(s), several are merged; without --data the other files are read from beside the first.",
        ),
        *([click.option("--kitchen", type=click.Path(), help=KITCHEN_HELP)] if with_kitchen else []),
        *FILE_OPTIONS,
    ]
    takes_options = "options" in inspect.signature(func).parameters

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        match = _match_args(kwargs)
        values = {
            k: kwargs.pop(k) for k in DataArgs.__dataclass_fields__ if k != "match" and (with_kitchen or k != "kitchen")
        }
        values.setdefault("kitchen", None)
        if takes_options:  # the substitutes go into the request (the request options inside add to it)
            kwargs["options"] = match.request(kwargs.get("options"))
        return func(*args, data=DataArgs(**values, match=match), **kwargs)

    return stacked(wrapper, opts + MATCH_OPTIONS)


# ---------------------------------------------------------------- goals and methods

GOAL_HELP = (
    "Goal: a label, an object's text as foon2asp prints it ('tomato, diced, in [plate]') or #ID"
    " from 'foon2asp objects'; repeatable."
)
GOALS_HELP = (
    "FILE of goal objects (e.g. 'foon2asp objects --format json' output), 'all' (the goals file) or"
    " 'all-objects' (every made object). Default without --goal: the goals file."
)


def goal_options(func):
    func = click.option("--goals", "goals", metavar="FILE|all|all-objects", help=GOALS_HELP)(func)
    return click.option("--goal", "goal", multiple=True, metavar="TEXT", help=GOAL_HELP)(func)


def method_option(default: str):
    """``--method``/``--methods`` (the same option): registered names, comma-separated or repeated."""
    return click.option(
        "--methods",
        "--method",
        "method_list",
        multiple=True,
        metavar="NAME[,NAME]",
        help=f"Registered method(s) (see 'foon2asp methods'), comma-separated or repeated (default: {default}).",
    )


def methods_of(values: tuple[str, ...], default: list[str] | tuple[str, ...] | None = None) -> list[str]:
    """The names of ``--method`` (each checked), else ``default`` (``asp``)."""
    names = [n.strip() for v in values for n in v.split(",") if n.strip()]
    for name in names:
        api.method(name)
    return list(dict.fromkeys(names)) or list(default or ["asp"])


def is_search(name: str) -> bool:
    """Is ``name`` a search baseline (no solver, no constraints)?"""
    return api.method(name).kind != "asp"


# ---------------------------------------------------------------- formats and progress


def format_option(kind: str):
    """``--format`` with the formats of the answers of ``kind`` (:func:`foon2asp.report.names`)."""
    return choice_option("--format", "fmt", choices=report.names(kind), default="text")


progress_option = click.option(
    "--progress/--no-progress", default=None, help="Progress bar on stderr (default: when it is a terminal)."
)


def together_option(help: str):
    """``--together``: the goals as one meal."""
    return click.option("--together", is_flag=True, help=help)


# ---------------------------------------------------------------- the request

OBJECTIVE_HELP = (
    "ASP objective(s), comma-separated, most important first: units, success, inputs, depth, cost"
    " (with --motion-cost), e.g. cost,units."
)


def objective_option(help: str = OBJECTIVE_HELP):
    """``--objective`` and ``--motion-cost FILE`` into ``options``."""
    return request_options(
        {"objective": "objective", "motion_cost": "motion_cost"},
        click.option("--objective", default="units", show_default=True, help=help),
        motion_cost_option(),
    )


def motion_cost_option():
    """``--motion-cost FILE`` (the request's ``motion_cost``)."""
    return click.option(
        "--motion-cost",
        type=click.Path(),
        metavar="FILE",
        help="Motion costs: a JSON object motion -> cost >= 0, or motion<TAB>cost lines; --objective cost minimises"
        " their sum, and every result then reports its cost. " + api.MOTION_COST_PRECISION + ".",
    )


def time_limit_option(help: str):
    """``--time-limit SECONDS`` into ``options``."""
    return request_options({"time_limit": "time_limit"}, click.option("--time-limit", type=SECONDS, help=help))


def models_option(least: int, help: str):
    """``--models K`` (at least ``least``; the request's ``models``)."""
    return click.option("--models", type=int32(min=least), default=1, show_default=True, help=help)


#: ``--gap G`` into ``options``: stop a goal once its gap is at most G
gap_option = request_options(
    {"gap": "gap"},
    click.option(
        "--gap",
        type=GAP,
        metavar="G",
        help="Stop a goal once its gap (the tree against the proven lower bound, first objective) is at"
        " most G, e.g. 0.05 or 5%; the answer is then 'feasible' with its bound. Default: prove.",
    ),
)


def _tree_has(flag: str, which: str) -> list[Callable]:
    """``--FLAG-motion M`` and ``--FLAG-object LABEL``: ``which`` unit of the tree has it."""
    return [
        click.option(
            f"--{flag}-motion", multiple=True, metavar="M", help=f"{which} unit of the tree has motion M; repeatable."
        ),
        click.option(
            f"--{flag}-object",
            multiple=True,
            metavar="LABEL",
            help=f"{which} unit of the tree has an input or output labelled LABEL; repeatable.",
        ),
    ]


#: --constraint FILE.lp, --rule TEXT and the convenience flags, into ``options.constraints``.
constraint_options = request_options(
    {
        "constraint": "constraint_files",
        "rule": "rules",
        "forbid_motion": "forbid_motions",
        "forbid_object": "forbid_objects",
        "require_motion": "require_motions",
        "require_object": "require_objects",
        "max_units": "max_units",
    },
    click.option(
        "--constraint",
        type=click.Path(),
        multiple=True,
        help="ASP file with extra rules over the vocabulary (use/1, motion/2, label/2, ...); repeatable.",
    ),
    click.option("--rule", multiple=True, help="An extra ASP rule, e.g. ':- use(U), motion(U,\"fry\").'; repeatable."),
    *_tree_has("forbid", "No"),
    *_tree_has("require", "Some"),
    click.option("--max-units", type=int32(min=0), help="The tree has at most N units."),
)


def _opt_strategy(ctx, param, value):
    if value is not None and value.split(",")[0] not in ("bb", "usc"):
        raise click.BadParameter("expected bb or usc, optionally with clingo's refinements (e.g. usc,oll or bb,hier)")
    return value


#: --opt-strategy and --threads into ``options`` (None and 1: the defaults of foon2asp.asp.options).
strategy_options = request_options(
    {"opt_strategy": "opt_strategy", "threads": "threads"},
    click.option(
        "--opt-strategy",
        callback=_opt_strategy,
        help="clingo optimisation strategy: bb (branch and bound) or usc (core-guided), e.g. usc,oll;"
        " default usc,oll,succinct,stratify, or with --threads 2+ a portfolio of one bb and one usc solver.",
    ),
    click.option(
        "--threads",
        type=int32(min=1, max=64),
        default=1,
        show_default=True,
        help="clingo solver threads (parallel mode; in a batch, per worker).",
    ),
)


def _exclusive(values: dict) -> None:
    if values["models"] > 1 and values["all_optimal"]:
        raise click.UsageError("--models and --all-optimal exclude each other")


def solver_options(func):
    """--max-depth, --human-steps, --models, --all-optimal, then :func:`strategy_options`, into ``options``."""
    return request_options(
        {"max_depth": "max_depth", "human_steps": "human_steps", "models": "models", "all_optimal": "all_optimal"},
        click.option(
            "--max-depth",
            type=int32(min=1),
            help="Only trees of at most N sequential rounds (the goal's level); with --objective depth, the search stops there.",
        ),
        click.option(
            "--human-steps",
            type=int32(min=0),
            help="At most M units may be done by a person (success 1.0); the solver picks them, the output marks them.",
        ),
        models_option(1, "The K best distinct trees per goal, best first."),
        click.option("--all-optimal", is_flag=True, help="Every optimal tree per goal (at most 100)."),
        check=_exclusive,
    )(strategy_options(func))


# ---------------------------------------------------------------- commands on goals


def goal_command(
    kind: str | None, *, methods: str | None = None, objective: str = OBJECTIVE_HELP, epilog: str = EXIT_CODES
):
    """A command of ``foon2asp`` on goals with, in this order, the data options, --goal and --goals,
    the constraint options, --method (default ``methods``; none when None), --objective and
    --motion-cost, --format (the formats of ``kind``; none when None); the options below it follow."""
    first = [main.command(epilog=epilog), data_options, goal_options, constraint_options]
    more = [method_option(methods)] if methods else []
    last = [format_option(kind)] if kind else []
    return lambda func: stacked(func, [*first, *more, objective_option(objective), *last])
