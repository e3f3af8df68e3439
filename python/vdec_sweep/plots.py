"""Summary plots of a sweep (matplotlib, Agg): each numeric output against each swept parameter,
one line for each combination of the other parameters, at the mean over the seeds with its
standard error as bars; a sweep over seeds alone gets a histogram of each output."""
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
import numpy as np  # noqa: E402

# More lines than this and a legend no longer helps.
LEGEND_LINES = 8


def _file_name(*parts):
    return "__".join(re.sub(r"[^A-Za-z0-9_.-]+", "_", p) for p in parts) + ".png"


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and np.isfinite(value)


def _positions(values):
    """x of each parameter value: the value itself when all are numbers, else its place in order
    of appearance, with the values as tick labels."""
    if all(_number(v) for v in values):
        return [float(v) for v in values], None
    labels = list(dict.fromkeys(str(v) for v in values))
    return [labels.index(str(v)) for v in values], labels


def _against_parameter(ax, records, column, key, others):
    """Lines of the output against parameter key; a line for each value of the other parameters.
    A run of a listed design that does not set the key is not drawn."""
    pairs = [(r, v) for r, v in zip(records, column) if key in r.run.settings]
    lines = {}
    for record, value in pairs:
        if record.ok and _number(value):
            other = tuple(record.run.settings.get(o) for o in others)
            lines.setdefault(other, {}).setdefault(record.run.settings[key], (record.run.values[key], []))[1].append(value)
    all_values = [record.run.values[key] for record, _ in pairs]
    _, labels = _positions(all_values)
    for other, points in lines.items():
        xs, labels_here = _positions([v for v, _ in points.values()])
        if labels is not None:
            xs = [labels.index(str(v)) for v, _ in points.values()]
        means = [float(np.mean(ys)) for _, ys in points.values()]
        sems = [float(np.std(ys, ddof=1) / np.sqrt(len(ys))) if len(ys) > 1 else 0.0 for _, ys in points.values()]
        order = np.argsort(xs)
        label = ", ".join(f"{o}={t}" for o, t in zip(others, other)) or None
        ax.errorbar(np.asarray(xs)[order], np.asarray(means)[order], yerr=np.asarray(sems)[order], marker="o",
                    capsize=3, label=label)
    failed = [(record.run.values[key], value) for record, value in pairs if not record.ok and _number(value)]
    if failed:
        xs = [labels.index(str(v)) if labels is not None else float(v) for v, _ in failed]
        ax.plot(xs, [y for _, y in failed], "rx", label="failed runs")
    if labels is not None:
        ax.set_xticks(range(len(labels)), labels, rotation=30)
    if 1 < len(lines) <= LEGEND_LINES or failed:
        ax.legend(fontsize="small")


def write_plots(folder, records, keys, values):
    """One PNG a (numeric output, parameter) in folder; a histogram an output without parameters.
    Returns the files written."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for text, column in values.items():
        if not any(_number(v) for r, v in zip(records, column) if r.ok):
            continue
        targets = [(key, [o for o in keys if o != key]) for key in keys] or [(None, [])]
        for key, others in targets:
            figure, ax = plt.subplots(figsize=(6.4, 4.4))
            if key is None:
                ax.hist([v for r, v in zip(records, column) if r.ok and _number(v)], bins="auto")
                ax.set_xlabel(text)
                ax.set_ylabel("realisations")
                name = _file_name(text)
            else:
                _against_parameter(ax, records, column, key, others)
                ax.set_xlabel(key)
                ax.set_ylabel(text)
                name = _file_name(text, key)
            ax.grid(alpha=0.3)
            figure.tight_layout()
            figure.savefig(folder / name, dpi=100)
            plt.close(figure)
            written.append(folder / name)
    return written
