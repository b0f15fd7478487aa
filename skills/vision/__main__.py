"""``python -m stuart_bt.skills.vision --backend sim --clock SPEC --options JSON``"""

import sys

from stuart_bt.skills.runtime import main
from stuart_bt.skills.vision import BACKENDS

if __name__ == "__main__":
    sys.exit(main("vision", BACKENDS))
