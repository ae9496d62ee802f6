"""Judge your own contact solver with threepart's pytest plugin (here: the SIE stands in for it).

Run it from the repository root (it is not part of threepart's own test run)::

    pytest examples/test_plugin_sie.py -s -n 0

threepart installs a pytest plugin that gives every test two fixtures:
``threepart_case``, one catalogue case per test run (here chosen by the
``threepart_cases`` marker), and ``threepart_check``, which compares anything
with ``a``, ``c`` and ``pressure(x)`` with the case's reference solution, judges
it by a row group of the tolerance table and prints the margins (listed again
at the end of the run, under "threepart margins"). Replace ``my_solver`` by a
call of your own code; ``examples/test_tamaas_plugin.py`` does so for tamaas.
"""
from __future__ import annotations

from typing import Any

import pytest

from threepart import sie
from threepart.problem.catalogue import Case


def my_solver(case: Case) -> Any:
    """Your code's answer to ``case``: anything with ``a``, ``c`` and ``pressure(x)``.

    The stand-in here is threepart's Gauss-Chebyshev solver, which shares no code
    with the closed form the plugin judges by.
    """
    return sie.solve_normal(case.punch, case.P, case.s, A=case.A, tilt=case.tilt)


@pytest.mark.threepart_cases("caseA_sym", "caseA_moment", "hertz", "suppressed")
def test_my_solver_against_threepart(threepart_case: Case, threepart_check: Any) -> None:
    # the SIE is held to its own rows of the tolerance table; a finite-element code would
    # keep the default, comparison="fem-default"
    threepart_check(my_solver(threepart_case), threepart_case, comparison="sie")
