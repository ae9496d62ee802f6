"""``python -m threepart.cli``: the command line, as ``python -m threepart`` runs it."""
from __future__ import annotations

import sys

from threepart.cli import main

if __name__ == "__main__":
    sys.exit(main())
