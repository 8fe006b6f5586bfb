"""The ``explore`` command: the explorer page, served on this machine."""

from __future__ import annotations

from dataclasses import asdict

import click

from foon2asp import explore
from foon2asp.cli import flags as opt
from foon2asp.cli.flags import command
from foon2asp.cli.main import warn_all


@command(
    opt.DATA,
    opt.MOTION_COST,
    opt.time_limit_option(
        "The most seconds one answer may take (default 30); the page's time limit is at most this,"
        " and its own default 10 s."
    ),
    opt.SCHEDULE,
    opt.option(
        "--host", "Listen on this address; anything but this machine's loopback is warned about.", default="127.0.0.1"
    ),
    opt.option("--port", "Listen on this port (default: a free one).", type=click.IntRange(0, 65535)),
    opt.flag("--open open_browser", "Open the page in the browser."),
    name="explore",
)
def explore_page(data, agents, durations, capabilities, resources, host, port, open_browser, options):
    """Ask a FOON in the browser: a goal's proven tree beside the search baselines, the question
    as controls (objective, motions, kitchen items, objects, human steps, a rule), its schedule
    and exports; the address holds the whole question.

    The page is served on 127.0.0.1 at a free port (printed) until Ctrl+C; each answer runs in
    a worker process of its own, at most --time-limit seconds. Needs the 'explore' extra:
    pip install 'foon2asp[explore]'.
    """
    explore.require_extra()
    from foon2asp.explore.server import serve
    from foon2asp.explore.settings import Setup

    kb = data.load()
    setup = Setup.of(
        data.data_dir,
        foon=data.foon,
        **asdict(data.reading),
        motion_cost=options.motion_cost,
        substitutes=options.substitutes,
        max_substitutions=options.max_substitutions,
        agents=agents,
        durations=durations,
        capabilities=capabilities,
        resources=resources,
        **({} if options.time_limit is None else {"time_limit": options.time_limit}),
    )
    serve(setup, kb, host=host, port=port, open_browser=open_browser, say=click.echo, warn=lambda w: warn_all([w]))
