"""``python -m fricgen`` and the ``fricgen`` command: the command line of :mod:`fricgen.app.cli`.

Its imports compile the engines on a first start (Numba: up to minutes); Ctrl-C then ends as it does
later, on one line with exit status 130, not in a traceback.
"""

import sys


def main() -> int:
    """Run the command line on ``sys.argv``; the exit status."""
    try:
        from .app.cli.commands import main as command_line
    except KeyboardInterrupt:
        print("fricgen: interrupted", file=sys.stderr)
        return 130
    return command_line()


if __name__ == "__main__":
    sys.exit(main())
