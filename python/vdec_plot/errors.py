"""The errors of `vdec plot`, each with its own exit code (docs/user-manual/plot.md#errors-and-exit-codes)."""

OK = 0
USAGE = 2          # a bad option or option value (argparse's own code for the same kind of error)
NO_RESULTS = 3     # DIR has no readable results.json of schema vdec.results/1
NO_SNAPSHOT = 4    # no VTK snapshot, or not the one asked for
NO_DATA = 5        # a layer asked for has nothing to draw in this run or snapshot
OUTPUT = 6         # the picture cannot be written

EXIT_CODES = {
    OK: "the picture was written",
    USAGE: "bad option or option value",
    NO_RESULTS: "no readable results.json in the run folder",
    NO_SNAPSHOT: "no VTK snapshot, or not the one asked for",
    NO_DATA: "a layer asked for has no data in this run or snapshot",
    OUTPUT: "the output file cannot be written",
}


class PlotError(Exception):
    """A message the user can act on, and the exit code it ends `vdec plot` with."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code
