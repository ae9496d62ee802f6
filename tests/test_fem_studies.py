"""FE studies: the block-size study converges to the half-plane (closed form) as the block grows."""
from __future__ import annotations

import numpy as np

from threepart import Punch, closedform, fem, rigid_punch

E, NU, P, S = 210e3, 0.3, 28846.0, 0.2
PUNCH = Punch(10.0, 5.0, 1.0)
#: the tilt's change at least halves as the block doubles (its far-field error falls as 1/L or faster)
HALVING = 0.5
#: the tilt of the L = 50 block (n = 40) against the half-plane's, relative
DOMAIN_TILT = 1e-3


def test_domain_study_approaches_the_half_plane():
    """The tilt is the most far-field sensitive figure: its change shrinks as L doubles."""
    st = fem.domain_study(PUNCH, P, S, E=E, nu=NU, Ls=(12.5, 25, 50, 100), n=40)
    assert st.param == "1/L" and np.allclose(st.sizes, 1 / np.array([12.5, 25, 50, 100]))
    change = np.array(st.errors["alpha"][:3])      # relative to the largest block
    assert np.all(change[1:] < HALVING * change[:-1]), change
    # the half-plane limit is the closed form (an independent solution)
    ref = closedform.solve_normal(PUNCH, P, S, A=rigid_punch(E, NU))
    alpha = np.array(st.values["alpha"])
    assert abs(alpha[0] - ref.alpha) > abs(alpha[2] - ref.alpha)
    assert abs(alpha[2] - ref.alpha) < DOMAIN_TILT * abs(ref.alpha)
