"""The command line's arguments: parser errors on one line, negative numbers as values, and the
errors of configuration sections named by the flags that set their keys."""

from __future__ import annotations

import argparse
import contextlib
import re

from ...errors import ConfigError, FricgenError


class UsageError(FricgenError):
    """An argument the parser refuses (missing, not a number, not a choice), from the command ``prog``."""

    def __init__(self, prog: str, message: str):
        self.prog = prog
        super().__init__(f"{message}; see `{prog} --help`")


class Parser(argparse.ArgumentParser):
    """argparse whose errors are one line (a UsageError for main) instead of the usage and an exit."""

    def error(self, message: str):
        raise UsageError(self.prog, message)


def add_command(subparsers, name: str, help: str, examples: str) -> argparse.ArgumentParser:
    """A subcommand whose ``--help`` shows its one-line purpose first and its examples (lines kept) last."""
    return subparsers.add_parser(
        name, help=help, description=help, epilog="examples:\n" + examples, formatter_class=argparse.RawDescriptionHelpFormatter
    )


#: A word that is a negative number (or -inf, -nan): the value of the flag before it, not a flag.
NEGATIVE = re.compile(r"-(\d|\.\d|inf|nan)", re.IGNORECASE)


def join_negative_values(argv: list[str]) -> list[str]:
    """``--flag -1e-3`` as ``--flag=-1e-3`` (argparse would read -1e-3 as an unknown flag)."""
    words: list[str] = []
    for word in argv:
        if words and words[-1].startswith("--") and words[-1] != "--" and "=" not in words[-1] and NEGATIVE.match(word):
            words[-1] += "=" + word
        else:
            words.append(word)
    return words


@contextlib.contextmanager
def named_by_flags(flags: dict[str, str]):
    """Re-raise a ConfigError of a section under the flag that sets its key (``numerics.dt`` -> ``--dt``;
    ``law.parameters.X`` -> ``--param X``); keys without a flag are left as they are."""
    try:
        yield
    except ConfigError as error:
        flag = flags.get(error.key)
        if error.key.startswith("law.parameters."):
            flag = "--param " + error.key.removeprefix("law.parameters.")
        if flag is None:
            raise
        raise ConfigError(flag, error.problem, error.fix) from error
