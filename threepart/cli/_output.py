"""What the sub-commands share in output: printing (text and ``--json``), CSV and VTU files.

Every number is printed with its unit from :data:`threepart.problem.units.UNITS` (the
library is unit-agnostic; the labels are one consistent set: mm, N/mm, MPa).
Every file is written through :func:`threepart.output.write_file`: a new file,
or one threepart wrote there and that is unchanged, never anything else.

Names
-----
UNITS               -- the unit of each printed quantity, by its key (threepart.problem.units)
print_result        -- a result's figures as text, or as strict JSON with a "units" object
print_json          -- a document as strict JSON with the given "units" object
write_points_csv    -- the fields at points (``x``, ``p``, ``q``) as CSV, each column with its unit
write_csv           -- a header and rows of numbers as CSV
write_grid_vtu      -- fields on a grid under the surface as a VTU structured grid of quads
"""
from __future__ import annotations

import sys
from typing import Any, Callable, Sequence

from threepart.problem.units import UNITS

__all__ = ["UNITS", "print_result", "print_json", "write_points_csv", "write_csv", "write_grid_vtu", "say_for"]


def say_for(command: str) -> Callable[[str], None]:
    """A progress line of ``threepart <command>`` on stderr (what :func:`threepart.progress.heartbeat` says with)."""
    def say(msg: str) -> None:
        print(f"threepart {command}: {msg}", file=sys.stderr, flush=True)
    return say


def _quantities(d: dict[str, Any]) -> set[str]:
    """The keys of every number in the nested dict ``d``."""
    keys: set[str] = set()
    for k, v in d.items():
        if isinstance(v, dict):
            keys |= _quantities(v)
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            keys.add(k)
    return keys


def print_json(doc: dict[str, Any], units: dict[str, str]) -> None:
    """``doc`` and its ``"units"`` object as strict JSON (plain numbers; inf and nan as null)."""
    from threepart.output import strict_json

    print(strict_json({**doc, "units": units}, indent=2))


def print_result(out: dict[str, Any], as_json: bool) -> None:
    """The figures of ``solve``/``slip``: ``out`` in print order, its headline (``_describe``) first.

    As text, one line a number with its unit, nested dicts indented, and the
    points as a table; as JSON, the same numbers with a ``"units"`` object of
    the quantities present.
    """
    headline = out.pop("_describe", None)
    points = out.pop("points", None)
    if as_json:
        doc = {**out, **({"points": points} if points is not None else {})}
        print_json(doc, {k: UNITS[k] for k in UNITS if k in _quantities(doc)})
        return
    if headline is not None:
        print(headline)
    _walk({k: v for k, v in out.items() if k != "method"})
    if points is not None:
        cols = list(points)
        print("points:")
        print("  " + "".join(f"{f'{k} [{UNITS[k]}]':>22}" for k in cols))
        for i in range(len(points["x"])):
            print("  " + "".join(f"{points[k][i]:>22.12g}" for k in cols))


def _walk(d: dict[str, Any], indent: str = "") -> None:
    """Print ``d`` as text, one line a key; every number with its unit."""
    for k, v in d.items():
        if isinstance(v, dict):
            print(f"{indent}{k}:")
            _walk(v, indent + "  ")
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            unit = UNITS[k]   # every number has a unit: a missing entry is a bug
            print(f"{indent}{k:<10} {float(v):.10g} {'(dimensionless)' if unit == '1' else unit}")
        elif isinstance(v, list):
            print(f"{indent}{k:<10} {', '.join(map(str, v))}")
        elif k not in ("method_note", "none"):
            print(f"{indent}{k:<10} {v}")
        elif k == "none":
            print(f"{indent}{v}")


def write_csv(path: str, header: Sequence[str], rows: Sequence[Sequence[str]], arg: str) -> None:
    """Write ``header`` and ``rows`` (cells already formatted) to ``path`` as CSV, atomically.

    ``arg`` names the option in a refusal (:func:`threepart.output.write_file`).
    """
    from threepart.output import write_file

    lines = [",".join(header), *(",".join(row) for row in rows)]
    write_file(path, "\n".join(lines) + "\n", arg=arg)


def write_points_csv(path: str, points: dict[str, list[float]]) -> None:
    """Write the points to ``path`` atomically: a new file, or threepart's own unchanged earlier one.

    Anything else is refused (:func:`threepart.output.write_file`).
    """
    cols = list(points)
    write_csv(path, [f"{k} [{UNITS[k]}]" for k in cols],
              [[f"{points[k][i]:.17g}" for k in cols] for i in range(len(points["x"]))], arg="--csv")


def write_grid_vtu(path: str, x: Any, z: Any, data: dict[str, Any], arg: str = "--vtu") -> None:
    """Fields on a grid under the surface as a VTU grid of quads for ParaView.

    ``x`` and ``z`` (depth, >= 0) have the fields' shape ``(nz, nx)``; the
    points are ``(x, -z, 0)``, the surface at y = 0 and depth down, and the
    depth is a field of its own.
    """
    import meshio
    import numpy as np

    from threepart.output import write_file

    x, z = np.broadcast_arrays(x, z)
    nz, nx = x.shape
    pts = np.column_stack([np.ravel(x), -np.ravel(z), np.zeros(nx * nz)])
    i, j = np.meshgrid(np.arange(nz - 1), np.arange(nx - 1), indexing="ij")
    n0 = (i * nx + j).ravel()
    quads = np.column_stack([n0, n0 + 1, n0 + nx + 1, n0 + nx])
    point_data = {k: np.ravel(v).astype(float) for k, v in data.items()}
    point_data["depth"] = np.ravel(z).astype(float)
    mesh = meshio.Mesh(pts, [("quad", quads)], point_data=point_data)
    write_file(path, lambda p: meshio.write(p, mesh, file_format="vtu"), arg=arg)
