"""`python3 -m nocdyn ...` and the `nocdyn` command pip installs: the command line, run in this
process by the compiled package (the same commands as the `nocdyn` executable)."""

import sys

from .commands import main

if __name__ == "__main__":
    sys.exit(main())
