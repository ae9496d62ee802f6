"""Judge another code's contact pressure, given as a CSV of points ``x, p``, against threepart.

Run it from anywhere (it writes only into a temporary directory, removed at the end)::

    python examples/judge_a_csv.py

At the command line the same is ``threepart compare --pressure FILE.csv --case hertz
--out DIR`` (``threepart compare --help``: your own punch and loads). Here the
"other code" is Hertz's pressure ``p0 sqrt(1 - x^2/a^2)`` sampled on 81 nodes,
written once as it is and once scaled by 1.05, as a model with a wrong
thickness would give. The first passes every check of the tolerance table's
``referee`` rows; the second fails its load check (``∫p dx`` is 5 % over ``P``)
and shows the ``load`` pitfall, with the number that shows it.
"""
from __future__ import annotations

import math
import tempfile
from pathlib import Path

import numpy as np

from threepart import Punch, similar_pair, solve
from threepart.reports.referee import main as judge_file

A = similar_pair(E=210e3, nu=0.3)          # two steel bodies, eq. (4) [1/MPa]
P, R = 400.0, 10.0                         # load [N/mm], cylinder radius [mm]
reference = solve(Punch(R1=R, R2=R, b=0.0), P=P, s=0.0, A=A)   # what the file is judged against

# the "other code": Hertz's pressure on 81 nodes over [-1.2 a, 1.2 a] (zero outside the contact)
a = math.sqrt(2 * A * R * P / math.pi)
x = np.linspace(-1.2 * a, 1.2 * a, 81)
p = 2 * P / (math.pi * a) * np.sqrt(np.clip(1 - (x / a) ** 2, 0.0, None))

with tempfile.TemporaryDirectory() as tmp:
    for name, scale in (("hertz", 1.0), ("hertz_thick", 1.05)):
        path = Path(tmp) / f"{name}.csv"
        np.savetxt(path, np.column_stack([x, scale * p]), delimiter=",", header="x,p", comments="")
        print(f"{name}.csv (pressure x {scale}), integral of p by the trapezoid rule: "
              f"{np.trapezoid(scale * p, x):.3f} N/mm (P = {P}):")
        status = judge_file(path, reference, out=Path(tmp) / f"{name}_report")
        print(f"exit status {status}")
