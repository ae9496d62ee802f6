"""Displacement and stress fields of an FE solution, written for ParaView through meshio.

The P2 displacement is written at the mesh vertices and the plane-strain stress
(mean over each triangle's quadrature points) per cell. 2-D vectors and points
are padded to three components, as VTU and XDMF readers expect.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import meshio
import numpy as np
from skfem import Basis
from skfem.models.elasticity import lame_parameters
from threepart.errors import InputError

__all__ = ["Fields", "fields_of", "plane_strain_stress", "to_meshio", "write_fields"]


@dataclass(frozen=True, eq=False)
class Fields:
    """Vertex displacement and cell stress on the substrate triangles.

    Attributes
    ----------
    points
        Vertex coordinates, ``(n, 2)``.
    triangles
        Vertex indices, ``(m, 3)``.
    displacement
        ``(n, 2)`` at the vertices.
    stress
        ``(m, 4)``: ``sigma_xx, sigma_yy, sigma_xy, sigma_zz`` (plane strain).
    """

    points: np.ndarray
    triangles: np.ndarray
    displacement: np.ndarray
    stress: np.ndarray


def plane_strain_stress(grad: np.ndarray, E: float, nu: float) -> tuple[np.ndarray, ...]:
    """``sigma_xx, sigma_yy, sigma_xy, sigma_zz`` (mesh axes, plane strain) from the displacement
    gradient ``grad[i, j] = d u_i / d x_j`` at quadrature points."""
    lam, mu = lame_parameters(E, nu)
    eps = 0.5 * (grad + grad.transpose(1, 0, 2, 3))
    tr = eps[0, 0] + eps[1, 1]
    return (lam * tr + 2 * mu * eps[0, 0], lam * tr + 2 * mu * eps[1, 1], 2 * mu * eps[0, 1],
            lam * tr)


def fields_of(basis: Basis, u: np.ndarray, E: float, nu: float) -> Fields:
    """Vertex displacement and mean cell stress of the P2 field ``u`` on ``basis``."""
    grad = basis.interpolate(u).grad  # (2, 2, cells, quadrature points)
    stress = np.stack([s.mean(axis=1) for s in plane_strain_stress(grad, E, nu)], axis=1)
    disp = u[basis.nodal_dofs].T
    return Fields(points=basis.mesh.p.T.copy(), triangles=basis.mesh.t.T.copy(),
                  displacement=disp, stress=stress)


def _pad3(a: np.ndarray) -> np.ndarray:
    return np.hstack([a, np.zeros((a.shape[0], 3 - a.shape[1]))])


def to_meshio(fields: Fields) -> meshio.Mesh:
    """The fields as a meshio mesh: ``displacement`` (3 components) and ``stress`` (3x3)."""
    sxx, syy, sxy, szz = fields.stress.T
    zero = np.zeros_like(sxx)
    tensor = np.stack([sxx, sxy, zero, sxy, syy, zero, zero, zero, szz], axis=1)
    return meshio.Mesh(
        points=_pad3(fields.points),
        cells=[("triangle", fields.triangles)],
        point_data={"displacement": _pad3(fields.displacement)},
        cell_data={"stress": [tensor], "sigma_yy": [syy],
                   "von_mises": [np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2
                                                + (szz - sxx) ** 2) + 3 * sxy**2)]},
    )


def write_fields(fields: Fields, path: str | Path, overwrite: bool = False) -> Path:
    """Write ``fields`` to ``.vtu`` or ``.xdmf`` (open it in ParaView).

    XDMF is written with XML data, but meshio's XDMF writer imports ``h5py``
    all the same, so ``.xdmf`` needs h5py installed (an ``ImportError`` says so).
    The file is written atomically through :func:`threepart.output.write_file`:
    a new file, or one that threepart wrote there earlier and that is unchanged
    (a rerun replaces it); any other existing file is refused with an
    ``OutputExistsError`` (a ``ValueError``) unless ``overwrite``.
    """
    from threepart.output import check_file, write_file

    path = Path(path)
    if path.suffix not in (".vtu", ".xdmf"):
        raise InputError(f"`path` = {str(path)!r} must end in .vtu or .xdmf")
    how = "choose another name or pass overwrite=True to replace it"
    check_file(path, arg="path", overwrite=overwrite, how=how)
    m = to_meshio(fields)
    if path.suffix == ".xdmf":
        try:
            import h5py  # noqa: F401  (meshio's XDMF writer needs it even for XML data)
        except ImportError as err:
            raise ImportError("writing .xdmf needs h5py (meshio's XDMF writer imports it); "
                              "`pip install h5py` or write .vtu") from err
        return write_file(path, lambda part: meshio.xdmf.write(part, m, data_format="XML"),
                          arg="path", overwrite=overwrite, how=how)
    return write_file(path, lambda part: meshio.write(part, m, file_format="vtu"), arg="path",
                      overwrite=overwrite, how=how)

