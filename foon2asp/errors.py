"""Errors about user input: always reported as one line naming file and line."""

from __future__ import annotations


class InputError(Exception):
    """Bad input. ``str(err)`` is a one-line message ``FILE:LINE: what``."""

    def __init__(self, message: str, path: str | None = None, line: int | None = None):
        super().__init__(message)
        self.message = message
        self.path = path
        self.line = line

    def __str__(self) -> str:
        where = ""
        if self.path is not None:
            where = str(self.path)
            if self.line is not None:
                where += f":{self.line}"
            where += ": "
        return where + self.message.replace("\n", " ")
