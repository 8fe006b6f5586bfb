"""The options the commands share, each declared once.

:func:`command` declares a command with its options; their values reach it gathered: the data
options as one ``data`` (:class:`DataArgs`), the request's settings as one ``options``
(:class:`foon2asp.api.Options`), the schedule options as one ``spec`` (:class:`foon2asp.api.ScheduleSpec`).
"""

from __future__ import annotations

import difflib
import functools
import gc
import inspect
import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

import click

from foon2asp import api, report
from foon2asp.api.load import Reading
from foon2asp.api.request import KEYWORDS, NOT_A_TIME_LIMIT, SPEC_KEYWORDS, jobs
from foon2asp.cli.main import EXIT_CODES, STRICT, main, warn_all, warn_request
from foon2asp.errors import InputError, escape

# ---------------------------------------------------------------- checked option types


class Checked(click.ParamType):
    """An option type whose ``parse`` raises a ValueError with the message for a bad value."""

    def __init__(self, name: str, parse: Callable[[str], Any]) -> None:
        self.name, self.parse = name, parse

    def convert(self, value, param, ctx):
        try:
            return self.parse(str(value).strip())
        except ValueError as exc:
            self.fail(escape(str(exc)), param, ctx)


def _seconds(text: str) -> float:
    try:
        number = float(text)
    except ValueError:
        raise ValueError(f"{text!r} is not a number of seconds") from None
    if not 0 < number < math.inf:
        raise ValueError(f"{text!r} {NOT_A_TIME_LIMIT} (leave the option out for the default)")
    return number


def _gap(text: str) -> float:
    try:
        number = float(text[:-1]) / 100 if text.endswith("%") else float(text)
    except ValueError:
        number = -1.0
    if not 0 <= number < math.inf:
        raise ValueError(f"expected a number >= 0 (0.05) or a percentage (5%), not {text!r}")
    return number


#: a time limit (a finite number of seconds > 0), a relative gap (0.05 or 5%)
SECONDS, GAP = Checked("seconds", _seconds), Checked("G", _gap)


def int32(min: int = 0, max: int = 2**31 - 1) -> click.IntRange:
    """An integer in ``[min, max]``, at most 2^31 - 1 (the solver's integers are 32-bit)."""
    return click.IntRange(min=min, max=max)


def option(flags: str, help: str | None, **kw):
    """An option: ``flags`` its names, space-separated (then its parameter's name, when not the long name)."""
    return click.option(*flags.split(), help=help, **kw)


def flag(flags: str, help: str, **kw):
    """An on/off option."""
    return option(flags, help, is_flag=True, **kw)


# ---------------------------------------------------------------- the gathered values


@dataclass(frozen=True)
class DataArgs:
    """The data options of a command: --data, --foon and how the files are read (--kitchen, --motion,
    --utensils, --utensil-rule, --strict and the looser matching)."""

    data_dir: str | None = None
    foon: tuple[str, ...] = ()
    reading: Reading = field(default_factory=Reading)

    def load(self, goals_file: str | None = None) -> api.KnowledgeBase:
        """The knowledge base these options name (``goals_file``: a ``--goals FILE`` to read); its
        warnings go to stderr.  Never the demo data unless asked."""
        if self.data_dir is None and not self.foon:
            raise InputError(
                "no data given: use --data DIR, --foon FILE (with kitchen.json ... beside it) or --data demo"
            )
        goals = goals_file if goals_file not in (None, "all", "all-objects") else None
        kb = api.load(self.data_dir, foon=list(self.foon) or None, goals=goals, **asdict(self.reading))
        warn_all(kb.warnings)
        # the FOON lives as long as the command: the garbage collector need not look at it again
        gc.freeze()
        return kb

    def load_goals(self, goal: tuple[str, ...], goals: str | None, together: bool = False) -> tuple:
        """The knowledge base and the goals ``--goal`` and ``--goals`` name (``together``: one meal, a tuple)."""
        kb = self.load(goals)
        return kb, jobs(kb.select_goals(goal, goals), together)

    def require_foon(self, options: api.Options, what: str) -> None:
        """Raise when looser matching is asked for without ``what`` (a FOON) to compare with."""
        r = self.reading
        if (
            Reading(level=r.level, normalize=r.normalize, synonyms=r.synonyms) != Reading()
            or options.substitutes is not None
        ):
            raise InputError(f"--level, --normalize, --synonyms and --substitutes need {what} to compare with")


def _gather(func: Callable) -> Callable:
    """``func`` called with its options gathered into ``data`` (or ``match``: the :class:`Reading`),
    ``options`` and ``spec``."""
    wants = inspect.signature(func).parameters

    @functools.wraps(func)
    def wrapper(**kw):
        click.get_current_context().meta[STRICT] = bool(kw.get("strict"))  # warnings about the request are errors
        if kw.get("max_substitutions") is not None and kw.get("substitutes") is None:
            raise InputError("--max-substitutions needs --substitutes FILE")
        if kw.get("models", 1) > 1 and kw.get("all_optimal"):
            raise click.UsageError("--models and --all-optimal exclude each other")
        if "data" in wants:
            kw["data"] = DataArgs(kw.pop("data_dir", None), tuple(kw.pop("foon", ())), Reading.of(kw))
        elif "match" in wants:
            kw["match"] = Reading.of(kw)
        ctx = click.get_current_context()
        extra = list(ctx.args)
        passes = ctx.command.context_settings.get("ignore_unknown_options", False)
        for param in ctx.command.params:  # a list of files takes the options it does not know: clingo's
            if passes and isinstance(param, click.Argument) and param.nargs == -1 and param.name in kw:
                extra += [v for v in kw[param.name] if v.startswith("--")]
                kw[param.name] = tuple(v for v in kw[param.name] if not v.startswith("--"))
        if extra:
            kw["clingo_args"] = tuple(a for a in extra if a.startswith("-"))
        if "options" in wants:
            try:
                kw["options"] = api.Options.of(**{k: kw.pop(k) for k in KEYWORDS & kw.keys()})
            except InputError as exc:
                key, _, arg = (exc.hint or "").partition("=")
                if key != "unknown-option":
                    raise
                raise click.UsageError(_no_such_option(arg, ctx.command)) from None
        stray = [a for a in extra if not a.startswith("-")]
        if stray or (extra and "options" not in wants):
            raise click.UsageError(f"unexpected argument {(stray or extra)[0]!r}")
        if "spec" in wants:
            kw["spec"] = api.ScheduleSpec.from_files(**{k: kw.pop(k) for k in SPEC_KEYWORDS})
            warn_request(kw["spec"].warnings)
        return func(**kw)

    return wrapper


def _no_such_option(arg: str, command: click.Command) -> str:
    """The message for an option neither this command nor clingo knows (with the closest options of
    the command and of clingo)."""
    name = arg.split("=", 1)[0]
    ours = [o for p in command.params if isinstance(p, click.Option) for o in p.opts if o.startswith("--")]
    known = list(dict.fromkeys([*ours, *api.clingo_option_names()]))
    close = difflib.get_close_matches(name, known, n=2, cutoff=0.8)
    hint = f" Did you mean {' or '.join(repr(c) for c in close)}?" if close else ""
    return f"No such option {name!r} (not foon2asp's, not clingo's).{hint}"


def command(*opts: Callable | list, name: str | None = None, group: click.Group = main, epilog: str | None = None):
    """A command of ``group`` with the options ``opts`` (decorators or lists of them, in the order
    of its help), its function called with the values gathered (:func:`_gather`)."""

    def decorate(func):
        func = _gather(func)
        flat = [o for opt in opts for o in (opt if isinstance(opt, list) else [opt])]
        for option in reversed(flat):
            func = option(func)
        cmd = group.command(name, epilog=epilog)(func)
        if any(o is STRATEGY[-1] for o in flat):
            # clingo's own options, as its application takes them: any option not foon2asp's goes to clingo
            cmd.context_settings.update(ignore_unknown_options=True, allow_extra_args=True)
        return cmd

    return decorate


def choice(flags: str, help: str | None, choices, default: str | None = "text"):
    """An option taking one of ``choices`` (the default shown in the help)."""
    return option(flags, help, type=click.Choice(choices), default=default)


def file_option(flag: str, help: str):
    """An option naming one FILE."""
    return click.option(flag, type=click.Path(), metavar="FILE", help=help)


def output_option(help: str, file: bool = True, **more):
    """``-o/--output``: a FILE (``file``) or a folder."""
    return click.option("-o", "--output", type=click.Path(file_okay=file, dir_okay=not file), help=help, **more)


# ---------------------------------------------------------------- the data

STRICT_HELP = "Treat warnings as errors: units of FOON and tree files skipped, and every warning about the request."
KITCHEN_HELP = (
    "kitchen.json, or 'leaves': every object no unit of the FOON makes (merged generated trees have no kitchen)."
)

#: --motion, --utensils, --utensil-rule and --strict
FILES = [
    option("--motion", "motion.txt (motion TAB success rate)", type=click.Path()),
    option("--utensils", "utensils.txt", type=click.Path()),
    choice(
        "--utensil-rule",
        "When a utensil holding one ingredient is not a required input.",
        api.UTENSIL_RULES,
        default="starter",
    ),
    flag("--strict", STRICT_HELP),
]

#: --level, --normalize, --synonyms FILE, --substitutes FILE and --max-substitutions N
MATCHING = [
    option(
        "--level",
        "FOON's hierarchy level objects are compared at: 1 labels, 2 labels and states (with the container),"
        " 3 also ingredients.",
        type=click.IntRange(1, 3),
        default=3,
        metavar="1|2|3",
    ),
    flag(
        "--normalize",
        "Compare labels, states and ingredients case-folded, white space collapsed, the last word singular.",
    ),
    file_option("--synonyms", "Lines 'name = canonical name': names compared as one."),
    file_option(
        "--substitutes",
        'What may stand in for a missing kitchen item: JSON {"onion": ["red onion"]} or lines'
        " 'onion: red onion, shallot =2'; trees use the fewest (cheapest) substitutions first.",
    ),
    option("--max-substitutions", "At most N substitutions per tree.", type=int32(min=0), metavar="N"),
]

#: --data DIR and --foon FILE
SOURCES = [
    option(
        "--data data_dir",
        "Directory with FOON.txt, kitchen.json, goal_nodes.json, motion.txt, utensils.txt;"
        " 'demo' for the demo data set shipped with foon2asp.",
        type=click.Path(),
    ),
    option(
        "--foon",
        "FOON file(s), several are merged; without --data the other files are read from beside the first.",
        type=click.Path(),
        multiple=True,
    ),
]

#: every data option, as one ``data`` value
DATA = [*SOURCES, option("--kitchen", KITCHEN_HELP, type=click.Path()), *FILES, *MATCHING]


# ---------------------------------------------------------------- goals and methods

GOAL_HELP = (
    "Goal: a label, an object's text as foon2asp prints it ('tomato, diced, in [plate]') or #ID"
    " from 'foon2asp objects'; repeatable."
)


def goal_options(goals_help: str, metavar: str = "FILE|all", goal_help: str = GOAL_HELP) -> list:
    """``--goal TEXT`` (repeatable) and ``--goals`` (``metavar``)."""
    return [
        option("--goal", goal_help, multiple=True, metavar="TEXT"),
        option("--goals", goals_help, metavar=metavar),
    ]


GOALS = goal_options(
    "FILE of goal objects (e.g. 'foon2asp objects --format json' output), 'all' (the goals file) or"
    " 'all-objects' (every made object). Default without --goal: the goals file.",
    "FILE|all|all-objects",
)


def method_option(default: str):
    """``--method``/``--methods`` (the same option): registered names, comma-separated or repeated."""
    return option(
        "--methods --method method_list",
        f"Registered method(s) (see 'foon2asp methods'), comma-separated or repeated (default: {default}).",
        multiple=True,
        metavar="NAME[,NAME]",
    )


# ---------------------------------------------------------------- formats, progress, the request


def format_option(kind: str):
    """``--format`` with the formats of the answers of ``kind`` (:func:`foon2asp.report.names`)."""
    return choice("--format fmt", None, report.names(kind))


PROGRESS = option("--progress/--no-progress", "Progress bar on stderr (default: when it is a terminal).", default=None)


OBJECTIVE_HELP = (
    "ASP objective(s), comma-separated, most important first: units, success, inputs, depth, cost"
    " (with --motion-cost), e.g. cost,units."
)

MOTION_COST = file_option(
    "--motion-cost",
    "Motion costs: a JSON object motion -> cost >= 0, or motion<TAB>cost lines; --objective cost minimises"
    " their sum, and every result then reports its cost. " + api.MOTION_COST_PRECISION + ".",
)


def objective_options(help: str = OBJECTIVE_HELP) -> list:
    """``--objective`` and ``--motion-cost FILE``."""
    return [option("--objective", help, default="units"), MOTION_COST]


def time_limit_option(help: str = "Seconds per goal; the best tree so far is reported as 'feasible'."):
    """``--time-limit SECONDS``."""
    return option("--time-limit", help, type=SECONDS)


GAP_OPTION = option(
    "--gap",
    "Stop a goal once its gap (the tree against the proven lower bound, first objective) is at"
    " most G, e.g. 0.05 or 5%; the answer is then 'feasible' with its bound. Default: prove.",
    type=GAP,
    metavar="G",
)


def _tree_has(name: str, which: str) -> list:
    """``--NAME-motion M`` and ``--NAME-object LABEL``: ``which`` unit of the tree has it."""
    return [
        option(
            f"--{name}-motion {name}_motions",
            f"{which} unit of the tree has motion M; repeatable.",
            multiple=True,
            metavar="M",
        ),
        option(
            f"--{name}-object {name}_objects",
            f"{which} unit of the tree has an input or output labelled LABEL; repeatable.",
            multiple=True,
            metavar="LABEL",
        ),
    ]


#: --constraint FILE.lp, --rule TEXT and the convenience flags
CONSTRAINTS = [
    option(
        "--constraint constraint_files",
        "ASP file with extra rules over the vocabulary (use/1, motion/2, label/2, ...); repeatable.",
        type=click.Path(),
        multiple=True,
    ),
    option("--rule rules", "An extra ASP rule, e.g. ':- use(U), motion(U,\"fry\").'; repeatable.", multiple=True),
    *_tree_has("forbid", "No"),
    *_tree_has("require", "Some"),
    option("--max-units", "The tree has at most N units.", type=int32(min=0)),
]


def _opt_strategy(ctx, param, value):
    if value is not None and value.split(",")[0] not in ("bb", "usc"):
        raise click.BadParameter("expected bb or usc, optionally with clingo's refinements (e.g. usc,oll or bb,hier)")
    return value


#: --opt-strategy and --threads
STRATEGY = [
    option(
        "--opt-strategy",
        "clingo optimisation strategy: bb (branch and bound) or usc (core-guided), e.g. usc,oll;"
        " default usc,oll,succinct,stratify, or with --threads 2+ a portfolio of one bb and one usc solver.",
        callback=_opt_strategy,
    ),
    option(
        "--threads",
        "clingo solver threads (parallel mode; in a batch, per worker). Any other option of clingo's"
        " goes to clingo as it is, e.g. --configuration=crafty.",
        type=int32(min=1, max=64),
        default=1,
    ),
]


def _agents(ctx, param, value):
    try:
        api.parse_agents(value)
    except InputError as exc:
        raise click.BadParameter(str(exc)) from None
    return value


#: --agents, --durations, --capabilities, --resources, as one ``spec``
SCHEDULE = [
    option(
        "--agents",
        "The agents, numbered per kind (arm=2,human=1: arm-1, arm-2, human-1); a 'human' succeeds"
        " for sure. Default: robot=1.",
        callback=_agents,
        metavar="KIND=N[,KIND=N...]",
    ),
    file_option(
        "--durations",
        'JSON {motion: seconds} or {KIND: {motion: seconds}}, "*" a default; exact to 0.001 s.'
        " Default: every unit 1 s.",
    ),
    file_option(
        "--capabilities",
        "JSON {KIND: [motion, ...]}: the motions each kind can do (a kind not listed can do all).",
    ),
    file_option(
        "--resources",
        "JSON {label: capacity}: at most that many units whose inputs hold the label at a time.",
    ),
]


def goal_command(
    kind: str | None, *more, methods: str | None = None, objective_help: str = OBJECTIVE_HELP, epilog: str = EXIT_CODES
):
    """A command on goals: the data options, --goal and --goals, the constraint options, --method
    (default ``methods``; none when None), --objective and --motion-cost, --format (the formats of
    ``kind``; none when None), then the options ``more``."""
    return command(
        DATA,
        GOALS,
        CONSTRAINTS,
        [method_option(methods)] if methods else [],
        objective_options(objective_help),
        [format_option(kind)] if kind else [],
        *more,
        epilog=epilog,
    )
