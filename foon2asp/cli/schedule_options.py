"""The schedule options ``schedule``, ``batch`` and ``check`` share: --agents, --durations,
--capabilities and --resources, passed on as one ``spec`` (:class:`foon2asp.api.ScheduleSpec`)."""

from __future__ import annotations

import functools

import click

from foon2asp import api
from foon2asp.cli.options import stacked
from foon2asp.errors import InputError


def _agents(ctx, param, value):
    try:
        api.parse_agents(value)
    except InputError as exc:
        raise click.BadParameter(str(exc)) from None
    return value


def schedule_options(func):
    """--agents, --durations, --capabilities, --resources, passed on as one ``spec`` (:class:`api.ScheduleSpec`)."""
    opts = [
        click.option(
            "--agents",
            callback=_agents,
            metavar="KIND=N[,KIND=N...]",
            help="The agents, numbered per kind (arm=2,human=1: arm-1, arm-2, human-1); a 'human' succeeds"
            " for sure. Default: robot=1.",
        ),
        click.option(
            "--durations",
            type=click.Path(),
            metavar="FILE",
            help='JSON {motion: seconds} or {KIND: {motion: seconds}}, "*" a default; exact to 0.001 s.'
            " Default: every unit 1 s.",
        ),
        click.option(
            "--capabilities",
            type=click.Path(),
            metavar="FILE",
            help="JSON {KIND: [motion, ...]}: the motions each kind can do (a kind not listed can do all).",
        ),
        click.option(
            "--resources",
            type=click.Path(),
            metavar="FILE",
            help="JSON {label: capacity}: at most that many units whose inputs hold the label at a time.",
        ),
    ]

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        files = [kwargs.pop(k) for k in ("agents", "durations", "capabilities", "resources")]
        return func(*args, spec=api.ScheduleSpec.from_files(*files), **kwargs)

    return stacked(wrapper, opts)
