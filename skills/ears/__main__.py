"""``python -m stuart_bt.skills.ears --backend dry --clock SPEC [--options JSON]``"""

import sys

from stuart_bt.skills.ears import BACKENDS
from stuart_bt.skills.runtime import main

if __name__ == "__main__":
    sys.exit(main("ears", BACKENDS))
