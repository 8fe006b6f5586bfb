"""`python -m foon2asp`: the command line.

The ``foon2asp`` script starts here too (:func:`run`).
"""

import signal
import sys

from foon2asp.errors import Terminated, forget_unhandled_interrupt, interrupt_behind


def _terminate(signum, frame) -> None:
    raise Terminated()


def run() -> None:
    """The command line (:func:`foon2asp.cli.main.run`), imported here so that a signal that comes
    while the library is being imported (or before the command line takes it) ends the command as
    one that comes later does: one line on stderr, exit status 130 (SIGINT) or 143 (SIGTERM)."""
    try:
        if signal.getsignal(signal.SIGTERM) is signal.SIG_DFL:
            signal.signal(signal.SIGTERM, _terminate)
        from foon2asp.asp.interrupts import keep_interrupts_until_exit, raise_dropped

        keep_interrupts_until_exit()
        from foon2asp.cli.main import run as command_line

        raise_dropped()  # an interrupt that a finaliser dropped meanwhile
        command_line()
    except (KeyboardInterrupt, RuntimeError) as caught:  # Terminated too
        exc = interrupt_behind(caught)
        if not isinstance(exc, KeyboardInterrupt):
            raise
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        terminated = isinstance(exc, Terminated)
        print(f"foon2asp: {'terminated' if terminated else 'interrupted'}", file=sys.stderr)
        forget_unhandled_interrupt()
        sys.exit(143 if terminated else 130)


if __name__ == "__main__":
    run()
