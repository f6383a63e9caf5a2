"""``python -m judder`` runs the ``judder`` command line."""

import sys

from .cli import main

if __name__ == "__main__":   # Dask's worker processes import this module
    sys.exit(main())
