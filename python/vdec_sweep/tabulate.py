"""The sweep's table (one row a run, one column an output) and, over seeds, the statistics of
each output for each combination of the other parameters, with their sampling errors."""
import csv
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy import stats

from vdec_sweep.paths import PathNotFound, resolve

CONFIDENCE = 0.95


@dataclass
class RunRecord:
    run: object                 # design.SweepRun
    folder: Path
    exit_code: int = None       # None: the run did not finish
    wall_seconds: float = 0.0
    stderr_tail: str = ""
    reason: str = ""            # why it did not finish (timeout, Slurm task lost)
    results: dict = None        # the run's results.json, None when it wrote none

    @property
    def ok(self):
        return self.exit_code == 0 and self.results is not None


def read_results(folder):
    try:
        results = json.loads((Path(folder) / "results.json").read_text())
    except (OSError, ValueError):
        return None
    return results if isinstance(results, dict) else None


def output_values(records, outputs):
    """{output text: [value or None per record]}, and {output text: why} for each output found in
    no run that wrote results.json (the first run's reason). A run's results.json up to a failure
    counts: its values are tabulated, marked by the run's status."""
    values, unknown = {}, {}
    for path in outputs:
        column, reasons, found = [], [], False
        for record in records:
            value = None
            if record.results is not None:
                try:
                    value = resolve(path, record.results)
                    found = True
                except PathNotFound as e:
                    reasons.append(f"run {record.run.name}: {e}")
            column.append(value)
        values[path.text] = column
        if not found and reasons:
            unknown[path.text] = reasons[0]
    return values, unknown


def _status(record):
    if record.ok:
        return "ok"
    return "failed" if record.exit_code is not None else "did not finish"


def table_rows(records, keys, values, seeds):
    """The table: one dict a run, columns run, the parameters, seed (with seeds), status, exit_code,
    the outputs."""
    rows = []
    for k, record in enumerate(records):
        row = {"run": record.run.name, **{key: record.run.values.get(key) for key in keys}}
        if seeds:
            row["seed"] = record.run.seed
        row.update(status=_status(record), exit_code=record.exit_code)
        row.update({text: column[k] for text, column in values.items()})
        rows.append(row)
    return rows


def _csv_cell(value):
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)   # every digit: the table round-trips
    if isinstance(value, (list, dict)):
        return json.dumps(value)
    return str(value)


def write_csv(path, rows):
    columns = list(rows[0]) if rows else []
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        for row in rows:
            writer.writerow([_csv_cell(row.get(c)) for c in columns])


def quantile_interval(sorted_values, q, confidence=CONFIDENCE):
    """Distribution-free interval [x(l), x(u)] of order statistics holding the q-quantile with
    probability at least `confidence`: the count of samples below the quantile is binomial (n, q).
    An end is None when n is too small for it (the interval is then open on that side)."""
    n = len(sorted_values)
    below = stats.binom.cdf(np.arange(n + 1), n, q)   # below[k] = P(count <= k)
    tail = (1.0 - confidence) / 2.0
    lows = [rank for rank in range(1, n + 1) if below[rank - 1] <= tail]
    highs = [rank for rank in range(1, n + 1) if below[rank - 1] >= 1.0 - tail]
    low, high = (lows[-1] if lows else None), (highs[0] if highs else None)
    coverage = (below[high - 1] if high else 1.0) - (below[low - 1] if low else 0.0)
    return ([float(sorted_values[low - 1]) if low else None, float(sorted_values[high - 1]) if high else None],
            float(coverage))


def describe(values, quantiles, confidence=CONFIDENCE):
    """Mean, its standard error and t interval, standard deviation, and the quantiles with their
    order-statistic intervals, of a sample of numbers."""
    x = np.sort(np.asarray(values, dtype=float))
    n = x.size
    summary = {"n": int(n), "mean": float(x.mean()), "sem": None, "mean_interval": [None, None], "std": None,
               "min": float(x[0]), "max": float(x[-1]), "quantiles": []}
    if n > 1:
        std = float(x.std(ddof=1))
        sem = std / math.sqrt(n)
        half = float(stats.t.ppf(0.5 + confidence / 2.0, n - 1)) * sem
        summary.update(std=std, sem=sem, mean_interval=[summary["mean"] - half, summary["mean"] + half])
    for q in quantiles:
        interval, coverage = quantile_interval(x, q, confidence)
        summary["quantiles"].append({"q": q, "value": float(np.quantile(x, q)), "interval": interval,
                                     "coverage": coverage})
    return summary


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def seed_statistics(records, keys, values, quantiles):
    """One entry a combination of the parameters and a numeric output: the statistics over its
    realisations that ran (failed ones are counted, not used)."""
    groups = {}
    for k, record in enumerate(records):
        groups.setdefault(tuple(record.run.settings.get(key) for key in keys), []).append(k)
    entries = []
    for members in groups.values():
        parameters = {key: records[members[0]].run.values.get(key) for key in keys}
        ran = [k for k in members if records[k].ok]
        for text, column in values.items():
            sample = [column[k] for k in ran if _number(column[k])]
            if not sample:
                continue
            entries.append({"parameters": parameters, "output": text, "realisations": len(members),
                            "failed": len(members) - len(ran), **describe(sample, quantiles)})
    return entries


def statistics_rows(entries, keys):
    """statistics.csv: one row an entry, the intervals as _low and _high columns."""
    rows = []
    for e in entries:
        row = {**e["parameters"], "output": e["output"], "n": e["n"], "failed": e["failed"], "mean": e["mean"],
               "sem": e["sem"], "mean_low": e["mean_interval"][0], "mean_high": e["mean_interval"][1],
               "std": e["std"], "min": e["min"], "max": e["max"]}
        for q in e["quantiles"]:
            name = f"q{q['q']:g}"
            row.update({name: q["value"], f"{name}_low": q["interval"][0], f"{name}_high": q["interval"][1]})
        rows.append(row)
    return rows
