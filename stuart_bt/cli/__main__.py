"""``python -m stuart_bt.cli``: the same as ``stuart-bt``."""

import sys

from .main import main

sys.exit(main())
