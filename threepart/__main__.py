"""``python -m threepart`` and the ``threepart`` console script: the command line (:mod:`threepart.cli`).

Both enter here, not in :mod:`threepart.cli`: this module imports nothing but
``sys``, so that a Ctrl-C while the command line still loads (argparse, the
parser, numpy), before :func:`threepart.cli.main` watches SIGINT, is one line
and exit status 130 too, never a traceback.

Names
-----
main         -- run the command line; an interrupt at any moment after this module loads is one line
COMMANDS     -- the sub-commands' names, read before anything loads (tests/test_cli.py keeps them in step
                with the modules of :data:`threepart.cli._main.SUBCOMMANDS`)
INTERRUPTED  -- the exit status of an interrupted command, 128 + SIGINT
"""
from __future__ import annotations

import sys
from collections.abc import Sequence   # loaded with the interpreter: no import cost

__all__ = ["main", "COMMANDS", "INTERRUPTED", "program"]

#: the sub-commands (kept in step with :func:`threepart.cli.build_parser` by tests/test_cli.py;
#: one module each in threepart/cli/, ``solve`` and ``slip`` both in solve.py)
COMMANDS = ("solve", "slip", "cases", "verify", "figures", "map", "export-refs", "fatigue", "cycle", "match", "deck",
            "compare", "cache", "wear")
#: the exit status of an interrupted command: 128 + SIGINT, as a shell reports a process it ended
INTERRUPTED = 130


def program(argv: Sequence[str]) -> str:
    """The name an error or an interrupt is reported under: ``threepart <command>``, or ``threepart``."""
    return f"threepart {argv[0]}" if argv and argv[0] in COMMANDS else "threepart"


def main(argv: Sequence[str] | None = None) -> int:
    """Run :func:`threepart.cli.main` (entry point of the console script); 130 on a Ctrl-C it did not see.

    A KeyboardInterrupt raised while :mod:`threepart.cli` is imported, or before
    its ``main`` installs its own handler, ends here.
    """
    try:
        from threepart.cli import main as cli_main

        return cli_main(argv)
    except KeyboardInterrupt:
        print(f"{program(list(sys.argv[1:] if argv is None else argv))}: interrupted", file=sys.stderr)
        return INTERRUPTED


if __name__ == "__main__":
    sys.exit(main())
