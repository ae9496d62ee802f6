"""The parser of every sub-command, and ``main``: the exit status and the one-line errors.

:func:`build_parser` loops over :data:`SUBCOMMANDS`, one module per sub-command;
:func:`main` runs the one asked for and turns what it raises into one line on
stderr and an exit status (2 an error, 130 interrupted, 141 a closed pipe).
"""
from __future__ import annotations

import argparse
import os
import select
import signal
import sys
import threading
from typing import Any, Iterator, Sequence

from threepart.__main__ import INTERRUPTED, program

from . import cache, cases, compare, cycle, deck, export_refs, fatigue, figures, match, solve, verify
from . import map as map_   # the module, not the builtin
from . import wear
from ._args import Parser, UsageError, join_negative_numbers, real_arg

__all__ = ["build_parser", "main", "SUBCOMMANDS", "HELP"]

#: the sub-command modules, in the order ``threepart --help`` lists them; each has
#: ``add_parser(subparsers)`` (which sets ``func``) and ``run(args) -> int``
SUBCOMMANDS = (solve, cases, verify, figures, map_, export_refs, fatigue, cycle, match, deck, compare, cache, wear)

#: the description ``threepart --help`` prints; ``{commands}`` is each sub-command's line, from the
#: ``help=`` its own module gives (:func:`command_lines`)
HELP = """The ``threepart`` command line.

Sub-commands
------------
{commands}

A problem is a catalogue case, --case NAME (`threepart cases` lists them), or
the punch, material and loads as options; the punch and loads beside --case
are refused (deck and compare take --E, --nu and --tilt beside it to replace
the case's).
An option a command does not know is named before anything else.

--method auto (default) uses the paper's closed form where it holds and the SIE
where it does not (past lift-off, the punch on one corner, a stick zone that
ends on the central segment), and says so on the first line of the output and
as "method" in --json; closedform, sie or fem ask for one method. A contact
that would separate into two zones is refused by every method.

--x X1,X2,... or --grid N add the pressure p(x) (and the shear q(x) for slip)
at those points, or at N points spread evenly over the contact; --csv FILE
writes them to a new file, or over the file an earlier run wrote there if it is
unchanged (never over anything else).

Units: the library works in any consistent set of units. The command line
labels lengths mm, loads per unit length N/mm, pressures and moduli MPa,
compliance 1/MPa and the tilt rad; give the input in a consistent set and read
the labels accordingly. Negative numbers may follow their option (--s -0.1).

--json prints strict JSON: plain numbers, a top-level "units" object, and an
infinite R (flat centre) as null.

Exit status: 0 done (verify: every tolerance holds; map: every point done and
the control within 1e-3), 1 a tolerance or a map point failed, 2 an error (one
line on stderr), 130 interrupted (map: run it again to resume).
"""


def command_lines(sub: Any) -> str:
    """One line per sub-command, its name and the ``help=`` its own module gave ``add_parser``."""
    helps = {a.dest: a.help for a in sub._choices_actions}
    width = max(len(name) for name in helps) + 2
    return "\n".join(f"{name:<{width}}{helps[name]}" for name in sub.choices)


def build_parser() -> argparse.ArgumentParser:
    """The parser of every sub-command; its usage errors raise :class:`UsageError`."""
    parser = Parser(prog="threepart", formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for module in SUBCOMMANDS:
        module.add_parser(sub)
    parser.description = HELP.format(commands=command_lines(sub))
    for action in _actions(parser):   # one reader of numbers: every `type=float` option's
        if action.type is float:
            action.type = real_arg
    return parser


def _actions(parser: argparse.ArgumentParser) -> Iterator[argparse.Action]:
    """Every option of ``parser`` and of its sub-commands."""
    for action in parser._actions:
        yield action
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                yield from _actions(sub)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


#: the exit status when the reader of standard output went away (``threepart slip | head``):
#: 128 + SIGPIPE, what a program killed by the signal reports, and silent, as ``git`` and coreutils are
PIPE_CLOSED = 141


def _stdout_closed() -> bool:
    """Whether standard output is a pipe whose reader has gone (then nothing more can be printed).

    Its buffer is pointed at ``os.devnull`` so that the interpreter's flush at exit
    does not fail a second time.
    """
    try:
        fd = sys.stdout.fileno()
        poll = select.poll()
        poll.register(fd, select.POLLOUT)
        closed = any(ev & select.POLLERR for _, ev in poll.poll(0))
    except (OSError, ValueError, AttributeError):   # no file descriptor (a test's capture)
        return False
    if closed:
        os.dup2(os.open(os.devnull, os.O_WRONLY), fd)
    return closed


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``threepart`` console script.

    Parameters
    ----------
    argv
        The arguments after the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 done, 1 a verification tolerance failed, 2 an error (one line on
        stderr, no traceback), 130 interrupted (Ctrl-C), 141 (silently) when
        the reader of standard output has gone.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    # named before parsing, so that Ctrl-C while the parser is built names the command too
    prog = program(argv)
    interrupted, previous = _watch_interrupts()
    args = None
    try:
        try:
            args, extra = build_parser().parse_known_args(join_negative_numbers(argv))
        except SystemExit as exc:  # --help
            return exc.code if isinstance(exc.code, int) else 0
        except UsageError:
            _unknown_first(argv)
            raise
        prog = f"threepart {args.command}"
        if extra:   # named here, so that the message names the sub-command
            raise _unrecognized(prog, extra)
        return int(args.func(args))
    except BaseException as exc:
        # Ctrl-C inside a C extension's import (numpy's) comes out as an ImportError, or any
        # other error, with the KeyboardInterrupt lost: the flag, not the class, tells
        if not (isinstance(exc, KeyboardInterrupt) or interrupted.is_set()):
            return _error_status(exc, prog)
        resume = "; run it again to resume" if prog == "threepart map" else ""
        print(f"{prog}: interrupted{resume}", file=sys.stderr)
        return INTERRUPTED
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)


def _unrecognized(prog: str, extra: Sequence[str]) -> UsageError:
    """The one-line usage error that names the arguments ``prog`` does not know."""
    return UsageError(f"{prog}: error: unrecognized arguments: {' '.join(extra)} (see `{prog} --help`)")


def _unknown_first(argv: Sequence[str]) -> None:
    """Raise the error naming an unknown option, if ``argv`` has one, before any other usage error.

    argparse reports a missing required option before an unknown one, so ``--load 400``
    (for ``--P 400``) would be told "--P is required" and never hear of ``--load``: the
    arguments are parsed again with nothing required, and what is left over is named.
    """
    parser = build_parser()
    for action in _actions(parser):
        if not isinstance(action, argparse._SubParsersAction):
            action.required = False
    try:
        args, extra = parser.parse_known_args(join_negative_numbers(argv))
    except (UsageError, SystemExit):   # another error, which the first parse reports
        return
    if extra:
        raise _unrecognized(f"threepart {args.command}", extra)


def _watch_interrupts() -> tuple[threading.Event, Any]:
    """An event that SIGINT sets, and the handler it replaced (None: none replaced).

    The new handler still raises KeyboardInterrupt, as Python's default does. It
    is installed only where Python's own handler is (not where SIGINT is ignored,
    nor off the main thread).
    """
    event = threading.Event()
    if (threading.current_thread() is not threading.main_thread()
            or signal.getsignal(signal.SIGINT) is not signal.default_int_handler):
        return event, None

    def on_sigint(signum: int, frame: Any) -> None:
        event.set()
        raise KeyboardInterrupt

    return event, signal.signal(signal.SIGINT, on_sigint)


def _error_status(exc: BaseException, prog: str) -> int:
    """The exit status of an error that ended a command (its one line on stderr), or re-raise it."""
    from threepart.errors import ThreepartError

    try:
        raise exc
    except UsageError as exc:
        print(exc, file=sys.stderr)
        return 2
    except BrokenPipeError as exc:
        if not _stdout_closed():
            print(f"{prog}: error: {_one_line(exc)}", file=sys.stderr)
            return 2
        return PIPE_CLOSED
    except (ThreepartError, ValueError, OSError) as exc:   # any refusal of threepart's, bad input, a file
        print(f"{prog}: error: {_one_line(exc)}", file=sys.stderr)
        return 2

