import sys

from netshape.cli import main

sys.exit(main())
