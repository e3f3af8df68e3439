import sys

from vdec_sweep.sweep import main

sys.exit(main())
