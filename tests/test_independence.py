"""The independent solvers never load the closed form, at run time.

Importing ``threepart.sie`` or ``threepart.fem`` (and solving with them) must
leave ``threepart.closedform`` out of ``sys.modules``: a solver that used the
formulas it is meant to check would check nothing. A fresh interpreter is
used for each package, so that nothing imported by other tests is seen.
"""
from __future__ import annotations

import subprocess
import sys

import pytest

SOLVE = {
    "threepart.sie": "import threepart.sie as m; m.solve_normal(Punch(1.0, 2.0, 0.4), 0.1, 0.1, A=1.0, n=16)",
    "threepart.fem": "import threepart.fem as m",
    "threepart.meshes": "import threepart.meshes as m",
}


def _loaded(code: str) -> set[str]:
    prog = f"import sys\nfrom threepart import Punch\n{code}\nprint(' '.join(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", prog], capture_output=True, text=True, check=True)
    return set(out.stdout.split())


@pytest.mark.parametrize("package", sorted(SOLVE))
def test_independent_solvers_never_load_the_closed_form(package):
    loaded = _loaded(SOLVE[package])
    assert package in loaded
    assert not {m for m in loaded if m.startswith("threepart.closedform")}, \
        f"{package} loads the closed form"


def test_the_check_sees_a_closed_form_import():
    loaded = _loaded("import threepart.reports.solvers, threepart.registry as r; r.names()")
    assert "threepart.closedform" not in loaded  # the registry imports a solver on first use
    assert "threepart.closedform.normal" in _loaded("from threepart.closedform import solve_normal")
