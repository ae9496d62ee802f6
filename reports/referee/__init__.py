"""``threepart compare --pressure FILE``: a pressure from another code, judged against threepart.

A user's finite-element (or any) contact pressure, given as points ``x, p``
(any file :mod:`threepart.readers` reads: a CSV, CalculiX's ``.frd`` or ``.dat``,
a VTU, XDMF, MED or Exodus mesh with a pressure field), becomes a result of the
shared shape (:class:`PointsResult`, a :class:`~threepart.results.NormalResult`)
and is compared with the reference of the same case -- the closed form where
it holds, the SIE past lift-off (``threepart.methods.solve(method="auto")``)
-- by the verification run's own comparison (:func:`reports.compare.compare`)
and the tolerance table's ``"referee"`` rows. :func:`diagnose` then looks for
the known pitfalls of contact FE results, each with the number that shows it (the limits:
the tolerance table's ``"referee-pitfall"`` rows):

``negative-pressure``
    Tension outside (or inside) the contact: CalculiX writes CPRESS = -K COPEN
    at open nodes, so a penalty contact shows negative "pressures" beyond its ends.
``load``
    ``∫p dx`` differs from ``P`` (a second increment re-paired on the deformed
    geometry, a wrong thickness, a half model).
``end-resolution``
    An end of the contact resolved by fewer than :data:`END_NODES` nodes
    within ``EDGE_FRACTION * W`` of it.
``mesh-peak``
    A peak set by the mesh: the largest pressure at a node next to an end, or
    an element-scale (node-to-node) oscillation larger than :data:`OSCILLATION`
    of the peak.
``increments``
    A CalculiX run whose step took more than one increment (its ``.sta``):
    the deck's model is one increment of the whole load.
``shear-sign``, ``no-slip``, ``coupling``, ``stick-slope`` (a partial slip, ``--Q --f``)
    The shear's sign flipped (``∫q = -Q``); the reference's slip zones not
    slipping; the stick zone shifted with its width right (a rigid punch or
    dissimilar bodies couple normal and shear); a stick slope so soft that the
    stick zone creeps (:mod:`.friction`, limits in the same rows).
``penalty``
    The penalty's overclosure ``p_max / K`` (a length; ``K`` read where the
    contact is closed) against the profile's rise over the contact: the peak
    error falls as ``1/K``.

Modules
-------
points   -- PointsResult, from_points, square_root_end, check_points, read_pressure (by threepart.readers)
pitfalls -- Pitfall, diagnose, oscillation and the pitfalls' limits
friction -- SlipPointsResult, slip_from_points, friction_pitfalls (a partial slip's shear)
verdict  -- judge, document, write_report, main (``threepart compare``), COMPARISON
studies  -- the CalculiX column of the verification run: calculix_result, calculix_studies

Names
-----
PointsResult    -- a NormalResult whose pressure interpolates given points
from_points     -- build one: the ends from the data (square-root fit), P and s its moments
square_root_end -- a square-root end from the last loaded points
check_points    -- refuse points that overflow, and a tilt that is no small slope
read_pressure   -- the points ``(x, p, info)`` of a file, by the reader its suffix picks
SlipPointsResult -- a SlipResult whose shear interpolates given points (its normal a PointsResult)
slip_from_points -- build one: the stick zone by threepart.results.fields.stick_ends
friction_pitfalls -- the friction pitfalls a partial slip's points show
Pitfall         -- one diagnosed pitfall: its name, the number and what to do
diagnose        -- every pitfall a pressure shows
oscillation     -- the node-to-node (odd-even) amplitude of nodal values
NEGATIVE, LOAD, END_NODES, OSCILLATION, PENETRATION -- the pitfalls' limits (tolerance table)
judge           -- compare and diagnose: the document of the report
document        -- that document as the report's sections
write_report    -- the report directory (md, html, json) through threepart.output
main            -- read, judge, report: ``threepart compare``
COMPARISON      -- the tolerance table's rows a pressure from outside is judged by
calculix_result  -- one CalculiX run of a case (threepart.calculix) as a PointsResult
calculix_studies -- its convergence in h and in the penalty K against the closed form
CALCULIX_CASE, SLOPE_SCALE, CALCULIX_N, CALCULIX_K, CALCULIX_K_MESH, CALCULIX_QUANTITIES -- its settings
"""
from __future__ import annotations

from .friction import SlipPointsResult, friction_pitfalls, slip_from_points
from .pitfalls import END_NODES, LOAD, NEGATIVE, OSCILLATION, PENETRATION, Pitfall, diagnose, oscillation
from .points import PointsResult, check_points, from_points, read_pressure, square_root_end
from .studies import (CALCULIX_CASE, CALCULIX_K, CALCULIX_K_MESH, CALCULIX_N, CALCULIX_QUANTITIES, SLOPE_SCALE,
                      calculix_result, calculix_studies)
from .verdict import COMPARISON, document, judge, main, write_report

__all__ = ["SlipPointsResult", "slip_from_points", "friction_pitfalls",
           "PointsResult", "from_points", "square_root_end", "check_points", "read_pressure", "Pitfall",
           "diagnose", "oscillation", "judge", "document", "write_report", "main", "calculix_result",
           "calculix_studies", "CALCULIX_CASE", "SLOPE_SCALE", "CALCULIX_N", "CALCULIX_K", "CALCULIX_K_MESH",
           "CALCULIX_QUANTITIES", "END_NODES", "OSCILLATION", "NEGATIVE", "LOAD", "PENETRATION", "COMPARISON"]
