"""`python -m vdec_plot` (what `vdec plot` runs)."""
import sys

from vdec_plot.cli import main

sys.exit(main())
