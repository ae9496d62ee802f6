"""``python -m threepart``: the ``threepart`` command line (see :mod:`threepart.cli`)."""
from __future__ import annotations

import sys

from threepart.cli import main

if __name__ == "__main__":
    sys.exit(main())
