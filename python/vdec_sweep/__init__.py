"""vdec_sweep: runs a scene over many --set values or seeds, and tabulates and plots the outputs.

    vdec sweep SCENE --set KEY=V1,V2,... [--set ...] [--design product|zip] [--seeds N]
               --output PATH [--output ...] --out DIR [--executor local|slurm ...]
    vdec sweep --file SWEEP.toml --out DIR [--executor ...]

Each run is `vdec run SCENE --out DIR/runs/NNNN --set KEY=V ...` (VDEC_EXECUTABLE, or --vdec,
names the vdec). DIR then holds sweep.json (the sweep and every run's command and exit code),
table.csv and table.json (a row a run: parameters, seed, status, exit code, outputs),
statistics.csv and statistics.json with --seeds (mean, standard error, t interval, standard
deviation, quantiles with order-statistic intervals), and plots/ (each output against each
parameter). Exit codes: vdec_sweep.errors. The user manual: docs/user-manual/sweeps.md.

Modules: design (parameters, designs, seeds), sweepfile (the TOML sweep file), paths (the
output path syntax), runs (one run, as an executor task), tabulate (table and statistics),
plots, sweep (the command).
"""
