"""The one registry of output formats, by kind of answer.

A format renders one kind of answer (``trees``, ``compare``, ``check``, ``schedule``, ...) to
text, or to bytes for a ``binary`` format; commands and the library look formats up here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from foon2asp.errors import InputError

Renderer = Callable[..., str | bytes]


@dataclass(frozen=True)
class Format:
    render: Renderer
    #: file name extension when written to a folder
    extension: str
    #: renders bytes (write them to a file or to stdout.buffer), not text
    binary: bool = False


FORMATS: dict[tuple[str, str], Format] = {}


def register(kind: str, name: str, extension: str, binary: bool = False) -> Callable[[Renderer], Renderer]:
    """Decorator: ``render`` is format ``name`` of answers of ``kind`` (``binary``: it returns bytes)."""

    def deco(render: Renderer) -> Renderer:
        FORMATS[(kind, name)] = Format(render, extension, binary)
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
    """Render an answer of ``kind`` in the text format ``name``."""
    fmt = get(kind, name)
    if fmt.binary:
        raise InputError(f"{kind} format {name!r} is binary: write it to a file (--output)")
    out = fmt.render(*args)
    assert isinstance(out, str)
    return out


def render_bytes(kind: str, name: str, *args: object) -> bytes:
    """Render an answer of ``kind`` in format ``name`` as bytes (text formats as UTF-8)."""
    out = get(kind, name).render(*args)
    return out.encode("utf-8") if isinstance(out, str) else out
