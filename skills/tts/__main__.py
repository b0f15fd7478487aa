"""``python -m stuart_bt.skills.tts --backend dry --clock SPEC [--options JSON]``"""

import sys

from stuart_bt.skills.runtime import main
from stuart_bt.skills.tts import BACKENDS

if __name__ == "__main__":
    sys.exit(main("tts", BACKENDS))
