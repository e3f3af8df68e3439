import sys

from vdec_verify.cli import main

sys.exit(main())
