"""What the half-plane methods share: bulk stress, steady cycles, load histories, Coulomb."""
