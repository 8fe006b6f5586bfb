"""Checked option types for the command line (click parameter types).

* :data:`SECONDS` -- a time limit: a finite number of seconds > 0 (``0``, ``nan``, ``inf``, ``-1``
  refused, in the words the library uses for ``time_limit=``);
* :data:`GAP` -- a relative gap: a number >= 0 (``0.05``) or a percentage (``5%``);
* :func:`int32` -- an integer within what the solver takes (clingo numbers are 32-bit), so an
  overflow can never turn into a wrong answer;
* :data:`SCHEDULER` -- a Dask scheduler address ``[tcp://|tls://|ucx://|ws://|wss://]HOST:PORT``
  (a port is required, except for ``inproc://``).
"""

from __future__ import annotations

import math
import re

import click

from foon2asp.api.options import NOT_A_TIME_LIMIT
from foon2asp.errors import escape

INT32_MAX = 2**31 - 1


class Seconds(click.ParamType):
    """A time limit: a finite number of seconds > 0 (no limit: leave the option out)."""

    name = "seconds"

    def convert(self, value, param, ctx):
        if isinstance(value, int | float) and not isinstance(value, bool):
            number = float(value)
        else:
            try:
                number = float(str(value).strip())
            except ValueError:
                self.fail(f"{escape(str(value))!r} is not a number of seconds", param, ctx)
        if not math.isfinite(number) or number <= 0:
            self.fail(f"{escape(str(value))!r} {NOT_A_TIME_LIMIT} (leave the option out for no limit)", param, ctx)
        return number


SECONDS = Seconds()


class Gap(click.ParamType):
    """A relative gap: a number >= 0 (0.05) or a percentage (5%)."""

    name = "G"

    def convert(self, value, param, ctx):
        if isinstance(value, float):
            return value
        text = str(value).strip()
        try:
            number = float(text[:-1]) / 100 if text.endswith("%") else float(text)
        except ValueError:
            number = -1.0
        if not 0 <= number < float("inf"):
            self.fail(f"expected a number >= 0 (0.05) or a percentage (5%), not {value!r}", param, ctx)
        return number


GAP = Gap()


def int32(min: int = 0, max: int = INT32_MAX) -> click.IntRange:
    """An integer in ``[min, max]``, at most 2^31 - 1 (the solver's integers are 32-bit)."""
    return click.IntRange(min=min, max=max)


class Workers(click.ParamType):
    """A number of worker processes (1..1024), or ``"auto"`` (one process, then every core)."""

    name = "N|auto"

    def convert(self, value, param, ctx):
        if isinstance(value, int):
            number = value
        elif str(value).strip().lower() == "auto":
            return "auto"
        else:
            try:
                number = int(str(value).strip())
            except ValueError:
                self.fail(f"{escape(str(value))!r} is not a number of workers or 'auto'", param, ctx)
        if not 1 <= number <= 1024:
            self.fail(f"{number} is not in 1..1024 (or 'auto')", param, ctx)
        return number


WORKERS = Workers()

_ADDRESS = re.compile(r"^(?:(tcp|tls|inproc|ucx|ws|wss)://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.\-]+)(?::(\d{1,5}))?/?$")


class SchedulerAddress(click.ParamType):
    """``[PROTOCOL://]HOST[:PORT]`` of a Dask scheduler (the port 1..65535)."""

    name = "address"

    def convert(self, value, param, ctx):
        text = str(value).strip()
        m = _ADDRESS.match(text)
        if m is None:
            self.fail(
                f"{escape(text)!r} is not a scheduler address (expected [tcp://]HOST:PORT, e.g. tcp://127.0.0.1:8786)",
                param,
                ctx,
            )
        port = m.group(3)
        if port is None and m.group(1) != "inproc":
            self.fail(
                f"{escape(text)!r} has no port (expected [tcp://]HOST:PORT, e.g. tcp://127.0.0.1:8786)", param, ctx
            )
        if port is not None and not 0 < int(port) < 65536:
            self.fail(f"port {port} of {escape(text)!r} is not in 1..65535", param, ctx)
        return text


SCHEDULER = SchedulerAddress()
