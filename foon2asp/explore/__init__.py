"""The explorer: a local web page to ask a FOON for a goal's proven tree, beside the search baselines.

``foon2asp explore --data DIR`` (or :func:`serve`) starts it on 127.0.0.1; :func:`app` is the
ASGI application itself.  It needs the ``explore`` extra (Starlette and uvicorn): ``pip install
'foon2asp[explore]'``.  docs/explore.md shows the page.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from foon2asp.errors import InputError

#: the one line said when the extra is not installed
NEEDS_EXTRA = "the explorer needs the 'explore' extra (Starlette and uvicorn): pip install 'foon2asp[explore]'"


def require_extra() -> None:
    """Raise an :class:`InputError` saying how to install the extra when Starlette or uvicorn is missing."""
    try:
        import starlette  # noqa: F401
        import uvicorn  # noqa: F401
    except ImportError:
        raise InputError(NEEDS_EXTRA) from None


def app(path: str | Path | None = None, **keywords: Any) -> Any:
    """The explorer's ASGI application (Starlette) for ``foon2asp.load(path, ...)``'s data; the
    keywords are :class:`foon2asp.explore.settings.Setup`'s (``time_limit``, ``workers``,
    ``agents``, ``motion_cost``, ...) and :func:`foon2asp.load`'s.  Its worker processes start
    with the application's lifespan (e.g. ``with TestClient(app(...))``)."""
    require_extra()
    from foon2asp.explore.app import make_app
    from foon2asp.explore.settings import Setup

    return make_app(Setup.of(path, **keywords))


def serve(
    path: str | Path | None = None,
    *,
    host: str = "127.0.0.1",
    port: int | None = None,
    open_browser: bool = False,
    **keywords: Any,
) -> None:
    """Serve the explorer for ``foon2asp.load(path, ...)``'s data until interrupted (the keywords
    as :func:`app`'s): on ``host`` (default this machine only) at ``port`` (default a free one),
    its address printed; ``open_browser`` opens it."""
    require_extra()
    from foon2asp.explore.server import serve as run
    from foon2asp.explore.settings import Setup

    run(Setup.of(path, **keywords), host=host, port=port, open_browser=open_browser)


__all__ = ["app", "serve", "require_extra", "NEEDS_EXTRA"]
