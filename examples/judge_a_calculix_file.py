"""Judge a CalculiX result of a normal contact against the closed form: read, compare, name the pitfalls.

Run it from the repository (it writes only into a temporary directory, removed at the end)::

    python examples/judge_a_calculix_file.py

The file is a coarse CalculiX 2.20 run kept in ``tests/data`` (``calculix_small_slope_h016``:
``threepart deck --R1 200 --R2 200 --b 1 --P 72.115 --E 210000 --nu 0.3 --h 0.16`` and
``ccx -i job``, about 14 elements across the contact; ``tests/data/README.md`` says how it was
made). At the command line the same is ``threepart compare --pressure job.frd --R1 200 --R2 200
--b 1 --P 72.115 --A 8.675333333e-06 --out DIR``. The deck writes the compliance its model
stands for (a punch 1000 x stiffer than the block) in its title: the judge is told that ``A``.

The reader returns the block's surface nodes with their pressure (CalculiX's ``CPRESS``, or
the contact forces over the nodes' share of the face: ``threepart.calculix.force_pressure``);
the judge fits the contact's ends and peaks to them and checks each against the closed form
with the tolerance table's ``referee`` rows. So coarse a mesh misses the ends' targets, and
the judge says why: the ``end_nodes`` pitfall counts the nodes that resolve each end.
"""
from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from threepart import Punch, readers, solve
from threepart.reports.referee import main as judge_file

DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
frd = DATA / "calculix_small_slope_h016.frd"
A = 8.675333333e-06                        # the model's compliance, from the deck's title [1/MPa]
P = 72.115                                 # the deck's load [N/mm]
reference = solve(Punch(R1=200.0, R2=200.0, b=1.0), P=P, s=0.0, A=A)   # the closed form

record = readers.read(frd)                 # x, p of the block's surface nodes (.frd + its .dat)
inside = record.p > 0
print(f"{frd.name}: {record.x.size} surface nodes, {int(inside.sum())} in contact, "
      f"from x = {record.x[inside].min():.4f} to {record.x[inside].max():.4f} mm")
print(f"integral of p by the trapezoid rule: {np.trapezoid(record.p, record.x):.4f} N/mm (P = {P})")
print(f"closed form: contact [{-reference.a:.4f}, {reference.c:.4f}] mm")
with tempfile.TemporaryDirectory() as tmp:
    status = judge_file(frd, reference, out=Path(tmp) / "report")
print(f"exit status {status}")
