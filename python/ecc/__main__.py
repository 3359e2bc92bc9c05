"""``python -m ecc batch ...`` (see :mod:`ecc.batch`)."""

import sys

from .batch import main

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
