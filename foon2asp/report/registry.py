"""The one registry of output formats, by kind of answer.

A format renders one kind of answer -- ``trees`` (solve), ``compare``,
``check``, ``reachable``, ``missing``, ``query``, ``summary`` (batch) -- to
text.  Every command and the library look formats up here, so a new format
is one registration.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from foon2asp.errors import InputError

Renderer = Callable[..., str]


@dataclass(frozen=True)
class Format:
    kind: str
    name: str
    render: Renderer
    #: file name extension when written to a folder
    extension: str
    description: str


FORMATS: dict[tuple[str, str], Format] = {}


def register(kind: str, name: str, extension: str, description: str) -> Callable[[Renderer], Renderer]:
    """Decorator: ``render`` is format ``name`` of answers of ``kind``."""

    def deco(render: Renderer) -> Renderer:
        FORMATS[(kind, name)] = Format(kind, name, render, extension, description)
        return render

    return deco


def names(kind: str) -> list[str]:
    """The format names of ``kind``, in registration order."""
    return [name for (k, name) in FORMATS if k == kind]


def get(kind: str, name: str) -> Format:
    try:
        return FORMATS[(kind, name)]
    except KeyError:
        raise InputError(f"unknown {kind} format {name!r} (have {', '.join(names(kind))})") from None


def render(kind: str, name: str, *args: object) -> str:
    """Render an answer of ``kind`` in format ``name``."""
    return get(kind, name).render(*args)
