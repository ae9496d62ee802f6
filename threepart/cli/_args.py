"""What the sub-commands share in parsing: the parser, the number options, the option groups.

Building the parser loads no numpy: every numerical import is inside a function.

Names
-----
UsageError          -- a command-line usage error, already formatted as one line
Parser              -- an argument parser whose usage errors raise UsageError
NUMERIC_OPTIONS     -- the options that take a number (``--s -1e-3`` is read as ``--s=-1e-3``)
LIST_OPTIONS        -- the options that take a comma-separated list of numbers
join_negative_numbers -- ``--opt -1e-3`` as ``--opt=-1e-3`` for those options
real_arg            -- the type of every number option: a float, or a one-line refusal
number_list         -- the type of ``--x``: a list of numbers
state_arg           -- the type of ``--state0``/``--state1``: ``P,s,Q,sigma_bulk``
labelled            -- an option's help text with the unit of its quantity
punch_args          -- the option group ``--R1 --R2 --b --R`` (eq. 2)
state_args          -- the options ``--state0 --state1``: a flight cycle's two ends
method_args         -- the option group ``--method --mesh``
method_options      -- the options ``--method`` declares, from the command line (``mesh``, ``n``, ``nu``)
problem_args, problem -- ``--case NAME`` or the punch, loads and material (deck, compare)
given_R             -- ``--R``, or inf (a flat centre) where it is not given
case_arg            -- the option ``--case NAME`` of every command that takes a problem
catalogue_case      -- the resolved catalogue case of ``--case``, every option of the problem refused beside it
need_options        -- refuse a problem given neither by ``--case`` nor whole: the first missing option named
E_HELP, NU_HELP     -- the help of ``--E``/``--nu``: the one material convention (both bodies)
FORCE_HELP          -- the help of the ``--force`` that an output directory no longer needs
"""
from __future__ import annotations

import argparse
import math
import sys
from typing import Any, NoReturn, Sequence

from threepart.errors import InputError, ThreepartError
from threepart.problem.units import E_RANGE, UNITS

__all__ = ["UsageError", "Parser", "NUMERIC_OPTIONS", "LIST_OPTIONS", "join_negative_numbers",
           "real_arg", "number_list", "state_arg", "constant_arg", "labelled", "punch_args", "state_args", "method_args", "method_options",
           "problem_args", "problem", "given_R", "case_arg", "catalogue_case", "need_options", "FORCE_HELP", "E_HELP", "NU_HELP"]

#: options that take a number; ``--s -1e-3`` is read as ``--s=-1e-3`` (argparse alone
#: would take ``-1e-3`` for an option)
NUMERIC_OPTIONS = ("--R1", "--R2", "--b", "--R", "--A", "--E", "--nu", "--P", "--s", "--Q", "--f",
                   "--Q-max", "--sigma-bulk", "--k", "--depth",   # --Q-max, --k, --depth: fatigue
                   "--alpha", "--h", "--penalty", "--stiffening", "--pad-R", "--pad-P",   # deck, compare; match
                   "--stick-slope")   # compare of a partial slip
#: options that take a comma-separated list of numbers (``--x -0.5,0.2`` is read as ``--x=-0.5,0.2``)
LIST_OPTIONS = ("--x",)

FORCE_HELP = ("no longer needed: a rerun replaces threepart's own earlier output in --out (its "
              ".threepart-output.json lists every file with a checksum, and nothing else is there); "
              "a directory holding anything else, or an edited file, is never replaced, with or "
              "without --force")


class UsageError(ThreepartError):
    """A command-line usage error, already formatted as one line."""


#: the help of ``--E``: the one material convention (:mod:`threepart.problem.material`), for every command
E_HELP = ("Young's modulus of BOTH bodies (two similar elastic bodies, A = 4(1 - nu^2)/E), in MPa "
          f"inside [{E_RANGE[0]:g}, {E_RANGE[1]:g}] (steel: 210000)")
#: the help of ``--nu``
NU_HELP = "Poisson's ratio of both bodies"


class Parser(argparse.ArgumentParser):
    """An argument parser whose usage errors are one line (raised, so that main returns 2).

    Every command's ``--E`` is checked here, once, against the moduli of engineering solids in MPa
    (:func:`threepart.problem.material.modulus`): ``--E 210e9`` (Pa) or ``--E 210`` (GPa) is a usage error.
    """

    def error(self, message: str) -> NoReturn:
        msg = " ".join(message.split())
        raise UsageError(f"{self.prog}: error: {msg} (see `{self.prog} --help`)")

    def parse_known_args(self, args: Sequence[str] | None = None,   # type: ignore[override]
                         namespace: argparse.Namespace | None = None) -> tuple[argparse.Namespace, list[str]]:
        ns, rest = super().parse_known_args(args, namespace)
        E = getattr(ns, "E", None)
        if E is not None:
            from threepart.problem.material import modulus

            try:
                modulus(E, "--E")
            except InputError as exc:
                self.error(str(exc))
        return ns, rest


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _is_number_list(token: str) -> bool:
    return all(_is_number(t) for t in token.split(","))


def join_negative_numbers(argv: Sequence[str]) -> list[str]:
    """Rewrite ``--opt -1e-3`` as ``--opt=-1e-3`` for the options in :data:`NUMERIC_OPTIONS`."""
    out: list[str] = []
    i = 0
    while i < len(argv):
        tok = argv[i]
        if tok == "--":
            out.extend(argv[i:])
            break
        nxt = argv[i + 1] if i + 1 < len(argv) else None
        negative = nxt is not None and nxt.startswith("-")
        if negative and ((tok in NUMERIC_OPTIONS and _is_number(nxt))            # type: ignore[arg-type]
                         or (tok in LIST_OPTIONS and _is_number_list(nxt))):   # type: ignore[arg-type]
            out.append(f"{tok}={nxt}")
            i += 2
        else:
            out.append(tok)
            i += 1
    return out


def real_arg(text: str) -> float:
    """The value of a number option (the type of every one): ``float(text)``, or a one-line refusal.

    A number that double precision cannot hold is refused, not rounded: one that
    underflows to 0 (``--b 1e-400`` would be solved as a punch without a flat) or
    overflows to inf (``inf`` itself, where an option takes it, is given as such).
    """
    from decimal import Decimal, InvalidOperation

    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"invalid float value: {text!r}") from None
    try:
        exact = Decimal(text.strip().replace("_", ""))
    except InvalidOperation:   # a form float() reads and Decimal does not: nothing lost
        return v
    if v == 0.0 and exact.is_finite() and exact != 0:
        raise argparse.ArgumentTypeError(f"{text} underflows to 0 in double precision (the smallest "
                                         f"positive number is {math.ulp(0.0):.2g})")
    if math.isinf(v) and exact.is_finite():
        raise argparse.ArgumentTypeError(f"{text} overflows to inf in double precision (the largest "
                                         f"number is {sys.float_info.max:.3g})")
    return v


def constant_arg(text: str) -> tuple[str, float]:
    """``"kappa=0.5"`` as ``("kappa", 0.5)`` (the type of ``--constant``), the value read by :func:`real_arg`."""
    name, sep, value = text.partition("=")
    name = name.strip()
    if not sep or not name.isidentifier():
        raise argparse.ArgumentTypeError(f"invalid constant: {text!r} (write NAME=VALUE, e.g. kappa=0.5)")
    return name, real_arg(value)


def number_list(text: str) -> list[float]:
    """``"1,-2.5,3e-1"`` as a list of floats (the type of ``--x``), each read by :func:`real_arg`."""
    try:
        return [real_arg(t) for t in text.split(",")]
    except argparse.ArgumentTypeError as exc:
        raise argparse.ArgumentTypeError(f"invalid list of numbers: {text!r} ({exc}; write "
                                         "X1,X2,...)") from None


def state_arg(text: str) -> tuple[float, float, float, float]:
    """``"P,s,Q,sigma_bulk"`` as a state (the type of ``--state0``/``--state1``), or a one-line refusal."""
    parts = text.split(",")
    if len(parts) != 4:
        raise argparse.ArgumentTypeError(f"{text!r} must be 4 numbers P,s,Q,sigma_bulk (got {len(parts)})")
    try:
        P, s, Q, sigma = (real_arg(t) for t in parts)
    except argparse.ArgumentTypeError as exc:
        raise argparse.ArgumentTypeError(f"{text!r} must be 4 numbers P,s,Q,sigma_bulk ({exc})") from None
    if not all(math.isfinite(v) for v in (P, s, Q, sigma)):
        raise argparse.ArgumentTypeError(f"{text!r} must hold finite numbers P,s,Q,sigma_bulk")
    if not P > 0:
        raise argparse.ArgumentTypeError(f"{text!r}: P = {P:g} must be > 0 (a compressive normal load)")
    return P, s, Q, sigma


def labelled(help_text: str, quantity: str) -> str:
    """``help_text`` with the unit of ``quantity`` (:data:`threepart.problem.units.UNITS`) in brackets."""
    return f"{help_text} [{UNITS[quantity]}]"


def punch_args(p: argparse.ArgumentParser) -> None:
    """``--R1 --R2 --b --R``: the punch of eq. (2), for every command that takes one (required
    unless ``--case`` gives it: :func:`need_options`)."""
    g = p.add_argument_group("punch geometry (eq. 2), unless --case")
    g.add_argument("--R1", type=float, help=labelled("left edge radius, > 0", "R1"))
    g.add_argument("--R2", type=float, help=labelled("right edge radius, > 0", "R2"))
    g.add_argument("--b", type=float, help=labelled("half-width of the central segment, >= 0", "b"))
    g.add_argument("--R", type=float,   # None: inf, the default (given_R reads it)
                   help=labelled("central radius: inf (flat, case A, default), negative for "
                                 "concave (case B)", "R"))


def given_R(args: argparse.Namespace) -> float:
    """``--R``, or inf (a flat centre) where it is not given."""
    return math.inf if args.R is None else float(args.R)


def state_args(group: Any, instead: str = "--P, --s, --Q-max and --sigma-bulk",
               then: str = "the fatigue of its periodic steady state at its two ends (docs/STEADY_STATE.md, "
                           "docs/FATIGUE.md)") -> None:
    """``--state0 --state1``: a flight cycle's two ends, ``instead`` of one load; ``then`` what the command
    does with them (the defaults are ``fatigue``'s)."""
    for k in (0, 1):
        group.add_argument(f"--state{k}", type=state_arg, metavar="P,s,Q,SIGMA",
                           help=f"end {k} of an in-phase flight cycle (N/mm, mm, N/mm, MPa), instead of "
                                f"{instead}: {then}")


def method_args(p: argparse.ArgumentParser) -> Any:
    """``--method`` (from the registry) and ``--mesh``, for every command that solves; the group."""
    from threepart import registry

    mt = p.add_argument_group("method")
    mt.add_argument("--method", choices=("auto", *registry.names()), default="auto",
                    help="auto (default): the closed form where it holds, else the SIE; or one method")
    mt.add_argument("--mesh", choices=("quick", "default", "fine"), default="default",
                    help="FE mesh preset for --method fem (default: default)")
    return mt


def method_options(args: argparse.Namespace, nu: float | None) -> dict[str, Any]:
    """The options that ``--method`` declares (:attr:`threepart.registry.Method.options`), from the
    command line: ``mesh`` (``--mesh``), ``n`` (``--n``, where the command has it and it is given),
    and ``nu`` for a method of finite bodies. With ``auto`` they are the fallback's, the SIE's
    (:data:`threepart.methods.AUTO`), as the library passes them."""
    from threepart import registry
    from threepart.methods import AUTO

    m = registry.get(AUTO[1] if args.method == "auto" else args.method)
    options: dict[str, Any] = {"mesh": args.mesh} if "mesh" in m.options else {}
    if "n" in m.options and getattr(args, "n", None) is not None:
        options["n"] = args.n
    if m.default_nu is not None:     # a finite body needs Poisson's ratio besides A
        options["nu"] = nu
    return options


#: what every ``--case`` says of the options beside it (one rule for every command)
CASE_RULE = "`threepart cases` lists them; the punch and the loads beside it are refused"


def case_arg(group: Any, what: str = "a case of the catalogue (threepart/problem/cases.json)", rule: str = CASE_RULE) -> None:
    """``--case NAME`` in ``group``: the problem of a catalogue case (:func:`catalogue_case`)."""
    group.add_argument("--case", metavar="NAME", help=f"{what}; {rule}")


def catalogue_case(args: argparse.Namespace, own: Sequence[str],
                   what: str = "the punch, material and loads") -> Any:
    """The resolved :class:`threepart.problem.catalogue.Case` of ``--case``, before any numerics.

    ``own`` are the command's options of the problem (``dest`` names): beside ``--case``
    the first one given is refused, as is a name the catalogue does not hold (its names
    listed). A ``store_true`` option counts as given when set. ``what`` names ``own`` in the refusal.
    """
    from threepart.problem.catalogue import get_case, load_cases

    given = [o for o in own if getattr(args, o, None) not in (None, False)]
    if given:
        raise InputError(f"give `--case` or {what}, not both (also got "
                         f"`--{given[0].replace('_', '-')}`)")
    names = [c.name for c in load_cases(None)]
    if args.case not in names:
        raise InputError(f"`--case` = {args.case!r} is not in the catalogue ({', '.join(names)}; "
                         "`threepart cases` describes them)")
    return get_case(args.case).resolved()


def need_options(args: argparse.Namespace, needs: Sequence[str]) -> None:
    """Refuse a problem given neither by ``--case`` nor whole: the first of ``needs`` missing is named."""
    missing = [o for o in needs if getattr(args, o, None) is None]
    if missing:
        raise InputError(f"give `--case NAME`, or the punch, material and loads: "
                         f"`--{missing[0].replace('_', '-')}` is missing")


def problem_args(p: argparse.ArgumentParser, *, compliance_option: bool) -> None:
    """``--case NAME``, or the punch, the loads and the material on the command line."""
    g = p.add_argument_group("the problem: --case NAME, or the punch and the loads (eq. 2)")
    case_arg(g)
    for name, text in (("--R1", "left edge radius"), ("--R2", "right edge radius"),
                       ("--b", "half-width of the central segment")):
        g.add_argument(name, type=float, help=labelled(text, name[2:]))
    g.add_argument("--R", type=float, default=None,
                   help=labelled("central radius (default inf: flat)", "R"))
    g.add_argument("--P", type=float, help=labelled("normal load per unit length", "P"))
    g.add_argument("--s", type=float, default=None, help=labelled("lever arm of P (default 0)", "s"))
    g.add_argument("--E", type=float, help=E_HELP + "; with --case, replaces the case's")
    g.add_argument("--nu", type=float, help=NU_HELP + "; with --case, replaces the case's")
    if compliance_option:
        g.add_argument("--A", type=float,
                       help=labelled("compliance of the model judged (eq. 4); default: the case's, "
                                     "or 4(1 - nu^2)/E (two similar bodies)", "A"))
    g.add_argument("--tilt", choices=("free", "suppressed"), default=None,
                   help="free (default, or the case's) or suppressed")


def given_punch_and_material(args: argparse.Namespace, needs: Sequence[str]) -> tuple[Any, float | None]:
    """The punch of ``--R1 --R2 --b [--R]`` and the checked ``--A`` or ``--E``/``--nu`` choice.

    ``needs`` are the options the command requires besides the material (its first missing one is
    named). Returns ``(punch, nu)``, ``nu`` None where not given (the caller's default applies).
    """
    import math

    from threepart.problem.punch import Punch
    from threepart.problem.checks import poisson

    need_options(args, needs)
    if args.A is not None and args.E is not None:
        raise InputError("give either `--A` or `--E`/`--nu`, not both")
    if args.A is None and (args.E is None or args.nu is None):
        raise InputError("the material needs `--A`, or both `--E` and `--nu`")
    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=math.inf if args.R is None else args.R)
    return punch, None if args.nu is None else poisson(args.nu)


def problem(args: argparse.Namespace) -> dict[str, Any]:
    """The punch, loads and material of ``--case`` or of the command line's options.

    ``A`` is the problem's compliance: the case's, or that of ``--E``/``--nu`` as two similar bodies
    (:func:`threepart.problem.material.material_compliance`; a case's ``bodies`` kept when it is a rigid punch).
    """
    from threepart.problem.material import material_compliance
    from threepart.problem.punch import Punch

    if args.case is not None:
        case = catalogue_case(args, ("R1", "R2", "b", "R", "P", "s"), "the punch and loads")
        if case.material is None and (args.E is None or args.nu is None):
            raise InputError(f"case {case.name!r} gives only A; add `--E` and `--nu`")
        E, nu = case.material if case.material is not None else (args.E, args.nu)
        E = E if args.E is None else args.E
        nu = nu if args.nu is None else args.nu
        A = case.A if args.E is None and args.nu is None else material_compliance(E, nu, case.bodies)
        return {"name": case.name, "punch": case.punch, "P": case.P, "s": float(case.s or 0.0),
                "E": E, "nu": nu, "bodies": case.bodies, "A": A, "tilt": args.tilt or case.tilt}
    missing = [o for o in ("R1", "R2", "b", "P", "E", "nu") if getattr(args, o) is None]
    if missing:
        raise InputError(f"give `--case NAME`, or the punch and the loads: `--{missing[0]}` is missing")
    punch = Punch(R1=args.R1, R2=args.R2, b=args.b, R=float("inf") if args.R is None else args.R)
    return {"name": "", "punch": punch, "P": args.P, "s": 0.0 if args.s is None else args.s,
            "E": args.E, "nu": args.nu, "bodies": "similar pair", "A": material_compliance(args.E, args.nu),
            "tilt": args.tilt or "free"}
