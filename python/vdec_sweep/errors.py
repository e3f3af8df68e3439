"""The sweep's exit codes and its input error."""

OK = 0
RUNS_FAILED = 1       # every input was good, but some run did not end with exit code 0
USAGE = 2             # the command line: an unknown option, SCENE missing, --out already a sweep, ...
BAD_SET = 3           # a --set that is not KEY=V1,V2,...: no '=', no key, a value not TOML, a key twice
EMPTY_VALUES = 4      # a parameter without values (--set KEY= , or an empty list in a sweep file)
BAD_OUTPUT = 5        # an output path that is malformed, or found in no run's results.json
BAD_SWEEP_FILE = 6    # a sweep file that cannot be read, or has an unknown or ill-typed key
EXECUTOR = 7          # the executor could not run the batch (sbatch refused it, no Slurm)


class SweepError(Exception):
    """Bad input, with the exit code of its kind; the message names the option or file and key."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code
