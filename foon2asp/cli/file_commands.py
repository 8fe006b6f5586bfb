"""The commands on files: check, draw, merge, consolidate, export, facts, query, objects, methods."""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from dataclasses import asdict, replace
from functools import partial
from pathlib import Path

import click

from foon2asp import api, report
from foon2asp.cli import flags as opt
from foon2asp.cli.flags import command
from foon2asp.cli.main import EXIT_CODES, emit, exit_code, main, solver_of, warn_all, warn_request
from foon2asp.errors import InputError
from foon2asp.report import draw as draw_mod
from foon2asp.report import pddl


def joined_lines(joined: dict[str, list[str]]) -> list[str]:
    """``joined 'Blueberries', 'blueberries' as 'blueberry'``: one line per text spelled several ways."""
    return [f"joined {', '.join(repr(s) for s in spellings[1:])} as {first!r}" for first, spellings in joined.items()]


# ---------------------------------------------------------------- check


@command(
    click.argument("trees", nargs=-1, required=True, type=click.Path(), metavar="TREE [TREE...]"),
    opt.DATA,
    opt.goal_options(
        "Several goals (a goals file, or 'all' for the goals file): each tree's goal is the one of them it makes.",
        goal_help="The goal (a label, an object's text or #ID; repeat for a meal); default: the goal the file names"
        " (a JSON result, or the '# task tree for ...' line of solve --format foon), else the tree's only sink"
        " (judged on its own: the products of its last unit).",
    ),
    opt.format_option("check"),
    opt.option("--optimum/--no-optimum", "Also solve the ASP optimum to compare with.", default=True),
    opt.SCHEDULE,
)
def check(trees, data, goal, goals, fmt, optimum, spec, options):
    """Check the task tree(s) in each TREE (FOON text with // between units, FOON JSON, foon2asp JSON
    and the JSON lines of 'batch', the unit-list JSON of generated trees, or a plan for 'export pddl':
    '(action-name)' lines as Fast Downward writes them); one report per tree.

    Without --data and --foon a tree is judged on its own: the kitchen is its leaves (or --kitchen
    FILE), the goal the products of its last unit (or --goal), and it is valid when every unit fires
    in the order written; else the report names the first unit that cannot and what it waits for,
    or the cycle.

    A schedule file ('schedule --format json') is judged with the FOON on the schedule options: the
    first violation of validity, durations, capabilities, precedence, one unit per agent at a time
    or resources.

    An answer without units for its goal (solve's answer for an unreachable goal) is 'unreachable:
    no tree to check' when the FOON confirms that the goal is not derivable, counted apart; else it
    is invalid.

    \b
    Exit codes: 0 every tree (schedule) valid or confirmed unreachable;
    1 some tree (schedule) invalid; 2 bad input or usage; 130 interrupted.
    """
    schedules = [p for p in trees if api.is_schedule_file(p)]
    verdicts: list = []
    if schedules:
        if fmt not in ("text", "json"):
            raise InputError(f"schedules are checked in --format text or json, not {fmt}")
        kb = data.load()
        verdicts = [v for p in schedules for v in kb.check_schedules(p, spec, options)]
        out = api.verdicts_json(verdicts) if fmt == "json" else "".join(v.to_text() for v in verdicts)
        click.echo(out, nl=False)
        if len(schedules) == len(trees):
            sys.exit(0 if all(v.valid for v in verdicts) else 1)
        trees = [p for p in trees if p not in schedules]
    reports: list = []
    if data.data_dir is None and not data.foon:
        data.require_foon(options, "a FOON (--data or --foon)")
        if goals:
            raise InputError("--goals needs a FOON (--data or --foon); to judge a tree on its own, use --goal")
        r = data.reading
        files = {"kitchen": r.kitchen, "utensils": r.utensils, "utensil_rule": r.utensil_rule, "strict": r.strict}
        judge: Callable[[str], list] = partial(api.check_tree, goal=list(goal) or None, **files)
        problem = None
    else:
        kb = data.load(goals)
        among = kb.select_goals((), goals) if goals else None
        strict, solver = data.reading.strict, solver_of(kb, options)
        judge = partial(
            kb.check_all, goal=list(goal) or None, optimum=optimum, goals=among, strict=strict, options=solver
        )
        problem = kb.problem
    for path in trees:
        found = judge(path)
        warn_all(dict.fromkeys(w for v in found for w in v.warnings))
        reports += [v.raw for v in found]
    click.echo(report.render("check", fmt, problem, reports), nl=False)
    answered = all(report.verdicts.answered(r) for r in reports)
    proofs = all((getattr(r, "proof", None) or {}).get("verified", True) for r in reports)  # a refused proof: 1
    sys.exit(0 if answered and proofs and all(v.valid for v in verdicts) else 1)


# ---------------------------------------------------------------- draw, merge, consolidate


@command(
    click.argument("tree", type=click.Path()),
    opt.option(
        "--data data_dir", "Data directory: marks kitchen items, the goal and a blocking cycle.", type=click.Path()
    ),
    opt.option("--goal", "Goal label (default: the goal a JSON result names, else inferred from the tree)."),
    opt.output_option("FILE.svg, .png, .pdf or .dot", required=True),
    opt.choice("--format fmt", "Drawing format (default: from the extension).", draw_mod.FORMATS, default=None),
    opt.flag("--strict", opt.STRICT_HELP),
    opt.MATCHING,
)
def draw(tree, data, goal, output, fmt, options):
    """Draw a task tree file: FOON text (either dialect), FOON JSON, foon2asp JSON or the unit-list
    JSON of generated trees.

    Objects are ellipses, functional units boxes; with --data the goal is gold,
    kitchen items green, and the cycle that blocks an invalid tree red.
    """
    fmt = fmt or draw_mod.format_of(output)
    if fmt != "dot":
        draw_mod.require_dot()
    kb = None
    if data.data_dir is not None:
        kb = replace(data, reading=replace(data.reading, strict=False)).load()  # --strict is about the tree file
    else:
        data.require_foon(options, "--data DIR")
    warnings: list[str] = []
    count = api.draw_file(
        tree, output, fmt=fmt, kb=kb, goal=goal, strict=data.reading.strict, warnings=warnings, options=options
    )
    warn_all(warnings)
    click.echo(f"drew {count} tree(s) from {tree} -> {output}", err=True)


@command(
    click.argument("files", nargs=-1, required=True, type=click.Path()),
    opt.output_option("The merged FOON file.", required=True),
    opt.flag("--strict", "Treat skipped units (warnings) as errors."),
    opt.choice(
        "--format fmt",
        "foon: official dialect with ids; foon-plain: without ids; foon-json: foon_api's JSON;"
        " units-json: the unit-list JSON of generated trees.",
        api.FOON_FORMATS,
        default="foon",
    ),
    opt.MATCHING,
)
def merge(files, output, fmt, match, options):
    """Merge FOON subgraphs into one universal FOON (duplicate units merged).

    FILES may be FOON text, FOON JSON or the unit-list JSON of generated trees
    ({input_nodes, motion_node, output_nodes} per unit).  With --level 1 or 2, --normalize or
    --synonyms the units are written as that comparison sees them (units equal there merged,
    the first spelling of each text kept); the spellings joined are listed on stderr.
    """
    if options.substitutes is not None:
        raise InputError("merge writes a FOON: --substitutes applies where trees are found (solve, check, ...)")
    foon = api.read_foons(files, match.strict)
    warn_all(foon.warnings)
    foon, joined = api.match_foon(foon, match.level, match.normalize, match.synonyms)
    for line in joined_lines(joined):
        click.echo(line, err=True)
    api.write_foon(foon, output, fmt, header=f"merged by foon2asp from {len(files)} file(s)")
    click.echo(
        f"merged {len(files)} file(s): {len(foon.units)} units, {len(foon.objects)} objects -> {output}", err=True
    )


@command(
    click.argument("trees", nargs=-1, required=True, type=click.Path(), metavar="TREES..."),
    opt.goal_options(
        "A FILE of goal objects, or 'all': every product of a candidate's last unit. Default: the product of"
        " the candidates' last units that most of them share."
    ),
    opt.option("--kitchen", opt.KITCHEN_HELP + " Default: leaves.", type=click.Path()),
    opt.FILES,
    opt.CONSTRAINTS,
    opt.objective_options(),
    opt.format_option("consolidate"),
    opt.output_option("A FILE to write the report to (default: stdout)."),
    opt.time_limit_option(),
    opt.GAP_OPTION,
    opt.flag("--together", "A meal: one tree that makes every goal."),
    opt.STRATEGY,
    opt.MATCHING,
    epilog=EXIT_CODES,
)
def consolidate(trees, goal, fmt, output, options, match, **given):
    """Merge candidate task trees of one recipe (TREES: files in any form 'check' reads, e.g. the
    unit-list JSON of generated trees) into one FOON and find, for each goal, its proven-best tree.

    Each unit of the tree names the files it comes from; each candidate gets a verdict: is it
    executable on its own (its units, in file order, from the kitchen), why not, its measures
    beside the optimum's and which of its units the tree uses.  An unreachable goal comes with
    the fewest objects to add to the kitchen ('missing').
    """
    # given: --goals and --together, as api.consolidate names them
    found = api.consolidate(list(trees), list(goal) or None, options=options, **given, **asdict(match))
    warn_all(found.warnings)
    emit(found.render(fmt), output, f"wrote the {fmt} report of {len(found)} goal(s)")
    sys.exit(exit_code((r.status, None) for r in found))


# ---------------------------------------------------------------- export


@main.group()
def export():
    """Write a FOON problem in another planning language."""


@command(
    opt.DATA,
    opt.goal_options(
        "FILE of goal objects or 'all' (the goals file): all of them in one :goal.",
        "TEXT",
        "Goal label; repeat for a meal (every goal in :goal).",
    ),
    opt.choice(
        "--objective pddl_objective",
        "units: plan length; success: integer action costs round(-1000 ln p) (:action-costs); inputs: input"
        " nodes; cost: the motion costs of --motion-cost in hundredths.",
        pddl.PDDL_OBJECTIVES,
        default="units",
    ),
    opt.MOTION_COST,
    opt.output_option("Directory for domain.pddl and problem.pddl.", file=False, required=True),
    opt.option("--name", "Domain name (problem: NAME-task).", default="foon"),
    opt.CONSTRAINTS,
    name="pddl",
    group=export,
)
def export_pddl(data, goal, goals, pddl_objective, output, name, options):
    """The goal's relevant part as a delete-free STRIPS domain and problem (DIR/domain.pddl, DIR/problem.pddl).

    One action per functional unit, named u<id>-<motion> (a plan maps back to the units:
    'foon2asp check PLAN --goal ...'); preconditions are the required inputs, effects the
    products; kitchen items in :init, the goal(s) in :goal.  --forbid-motion and
    --forbid-object remove actions; general --rule/--constraint programs, --require-* and
    --max-units cannot be exported.
    """
    if goals == "all-objects":
        raise InputError("--goals all-objects cannot be one PDDL goal; name goals with --goal or a goals FILE")
    if options.substitutes is not None:
        raise InputError("export pddl cannot express --substitutes (a plan cannot count its substitutions)")
    kb, goal_ids = data.load_goals(goal, goals)
    problem = kb.solving_problem(solver_of(kb, options))  # with the motion costs, for --objective cost
    if not all(c.isalnum() or c in "-_" for c in name) or not name[:1].isalpha():
        raise InputError(f"--name must be a PDDL name (a letter, then letters, digits, - or _), not {name!r}")
    task = pddl.export(problem, goal_ids, pddl_objective, options.constraints, name)
    out = Path(output)
    out.mkdir(parents=True, exist_ok=True)
    (out / "domain.pddl").write_text(task.domain, encoding="utf-8")
    (out / "problem.pddl").write_text(task.problem, encoding="utf-8")
    click.echo(
        f"wrote {out / 'domain.pddl'} ({len(task.actions)} actions, {len(task.objects)} objects) "
        f"and {out / 'problem.pddl'} ({len(task.goals)} goal(s))",
        err=True,
    )


# ---------------------------------------------------------------- facts and queries

FACT_GOALS = opt.option(
    "--goals", "Goals for goal_node/2 facts (default: the goals file).", metavar="FILE|all|all-objects"
)


@command(
    opt.DATA,
    FACT_GOALS,
    opt.option("--goal", "Also fix goal(O) for this goal. " + opt.GOAL_HELP, multiple=True, metavar="TEXT"),
    opt.output_option("A FILE to write the facts to (default: stdout)."),
)
def facts(data, goals, goal, output, options):
    """Write the FOON, kitchen and goals as ASP facts."""
    kb = data.load(goals)
    nodes = kb.select_goals((), goals) if goals else None
    text = kb.facts(nodes, kb.select_goals(goal, None) if goal else [], options=options)
    emit(text, output, f"wrote {len(text.splitlines())} lines")


@command(
    click.argument("program", type=click.Path()),
    opt.DATA,
    FACT_GOALS,
    opt.option("--goal", "Also add goal(O) for this goal. " + opt.GOAL_HELP, metavar="TEXT"),
    opt.option(
        "--encoding encoding_names",
        "Also load a part of encodings/parts/ by name (tree, units, success, inputs, cost, reachable,"
        " missing, ...), over tree.lp when it reads a tree; repeatable.",
        multiple=True,
    ),
    opt.option("--models", "Models to print (0 = all); with an objective, the optimum.", type=opt.int32(), default=1),
    opt.format_option("query"),
    opt.time_limit_option("Seconds for the solve."),
)
def query(program, data, goals, goal, encoding_names, fmt, options):
    """Run your ASP PROGRAM with the FOON facts; print its shown atoms with ids as readable objects.

    With a #show statement in PROGRAM only what it shows is printed. Atoms that
    no rule or fact defines (a misspelt predicate) are warned about.

    \b
    Exit codes: 0 a model (with an objective, the proven optimum); 1 no such
    answer: proven unsatisfiable, or the time limit stopped the search (no model
    yet, or the optimum not proven; the status printed says which); 2 bad input
    or usage; 130 interrupted.
    """
    text = api.read_program(program)
    kb = data.load(goals)
    nodes = kb.select_goals((), goals) if goals else None
    result = kb.query(
        text, goal=goal or None, encodings=encoding_names, name=program, goal_nodes=nodes, options=options
    )
    warn_request(result.warnings)
    click.echo(report.render("query", fmt, kb.problem, result), nl=False)
    sys.exit(0 if result.status in ("satisfiable", "optimal") else 1)


# ---------------------------------------------------------------- objects and methods


@command(
    click.argument("query", required=False, metavar="[LABEL]"),
    opt.SOURCES,
    opt.FILES,
    opt.MATCHING,
    opt.option(
        "--produced only", "Only objects some unit makes (without needing it as an input).", flag_value="produced"
    ),
    opt.option("--kitchen only", "Only kitchen items.", flag_value="kitchen"),
    opt.option("--derivable only", "Only objects that can be made from the kitchen.", flag_value="derivable"),
    opt.option(
        "--kitchen-file kitchen", opt.KITCHEN_HELP.replace("kitchen.json", "A kitchen.json", 1), metavar="FILE|leaves"
    ),
    opt.choice("--format fmt", None, ("text", "json")),
)
def objects(query, data, only, fmt, options):
    """List the objects LABEL names (all objects without it), each with its #ID and text.

    LABEL is a label ('scrambled egg'), an object's text, #ID, or words of labels ('egg').
    Any #ID or text listed can be given as --goal; the JSON list is a goals file
    (--goals FILE).

    'made by N units' counts the units that make the object: a unit that outputs it but also
    needs it as an input does not make it ('output by N units that need it').
    """
    try:
        kb = data.load()
    except InputError as exc:
        key, _, looked_for = (exc.hint or "").partition("=")
        if key == "kitchen-data":
            raise InputError(
                "kitchen file not found in the data folder; give --kitchen-file FILE, or --kitchen-file leaves"
                " (every object no unit makes)",
                exc.path,
            ) from None
        if key != "kitchen":
            raise
        raise InputError(
            f"no kitchen.json beside the FOON file (looked for {looked_for}); give --kitchen-file FILE,"
            " --kitchen-file leaves (every object no unit makes) or --data DIR"
        ) from None
    ids = kb.find_objects(query, only, options=options)
    # per object: the units that make it, and those that output it but also need it (the heated stove stays on)
    needing = {i: sum(1 for u in kb.problem.producers.get(i, ()) if i in kb.problem.inputs[u]) for i in ids}
    made = {i: len(kb.problem.producers.get(i, ())) - needing[i] for i in ids}
    if only == "produced":
        ids = [i for i in ids if made[i]]
    infos = [{**kb.object_info(i), "producers": made[i]} for i in ids]
    if fmt == "json":
        click.echo("[\n" + ",\n".join(json.dumps(i, ensure_ascii=False) for i in infos) + "\n]" if infos else "[]")
        return
    width = len(f"#{max(ids)}") if ids else 2
    for info in infos:
        where = ["kitchen"] if info["in_kitchen"] else []
        if info["producers"]:
            where.append(f"made by {info['producers']} unit{'s' if info['producers'] != 1 else ''}")
        if n := needing[info["id"]]:
            also = "also " if info["producers"] else "only "
            where.append(f"{also}output by {n} unit{'s' if n != 1 else ''} that need{'s' if n == 1 else ''} it")
        if "joined" in info:
            where.append("joins " + " | ".join(info["joined"]))
        click.echo(f"{'#' + str(info['id']):<{width}}  {info['text']}" + (f"   ({', '.join(where)})" if where else ""))
    what = {None: "", "produced": " made by some unit", "kitchen": " in the kitchen", "derivable": " derivable"}[only]
    click.echo(f"{len(infos)} object{'s' if len(infos) != 1 else ''}{what}", err=True)
    for line in joined_lines(kb.joined):
        click.echo(line, err=True)


@command(name="methods")
def list_methods():
    """List the registered methods."""
    for m in api.methods():
        click.echo(f"{m.name:16} {m.kind:7} {m.description}")
