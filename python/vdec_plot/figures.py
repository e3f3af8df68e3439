"""Whole pictures: the model picture of `vdec plot` (geometry and the chosen layers on equal axes
in metres, titled with the scene and cycle, with the sign conventions and scales stated beneath),
the histories picture, and the set-up picture the verification report places on each problem's
page. Drawn on matplotlib Figure objects (Agg, no display) under a fixed style so that the same
data give the same pixels."""
import math
import textwrap
import tomllib
from pathlib import Path

import matplotlib
import numpy as np
from matplotlib.figure import Figure

from vdec_plot import layers
from vdec_plot.errors import NO_DATA, OUTPUT, PlotError

# Fixed so that pictures do not depend on the user's matplotlibrc: the font matplotlib ships,
# no hash salt in SVG ids, no creation date in PDF and SVG.
STYLE = {"font.family": "DejaVu Sans", "font.size": 8, "svg.hashsalt": "vdec", "path.simplify": False,
         "axes.formatter.useoffset": False, "image.cmap": "viridis"}
FORMATS = {".png": "png", ".svg": "svg", ".pdf": "pdf"}
SIGN_NOTE = "stresses tension positive; joint normal force compression positive"


def style():
    return matplotlib.rc_context(STYLE)


def save(fig, path, dpi):
    """Writes fig to path in the format its suffix names; PlotError(OUTPUT) when it cannot."""
    path = Path(path)
    kind = FORMATS.get(path.suffix.lower())
    if kind is None:
        raise PlotError(OUTPUT, f"--out {path}: give a file ending in .png, .svg or .pdf")
    metadata = {"Software": None} if kind == "png" else {"Creator": None, "Date": None} if kind == "svg" else \
        {"Creator": None, "Producer": None, "CreationDate": None}
    try:
        with style():
            fig.savefig(path, format=kind, dpi=dpi, metadata=metadata)
    except OSError as e:
        raise PlotError(OUTPUT, f"--out {path}: cannot write ({e.strerror or e})") from e


def _model_axes(fig, title):
    ax = fig.add_subplot(1, 1, 1)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title, fontsize=8)
    return ax


def wrapped(text, width=110):
    """text wrapped at width, each of its own lines kept, at most three lines."""
    return "\n".join([part for line in text.split("\n") for part in textwrap.wrap(line, width)][:3])


def read_scene(path):
    """The scene's TOML tables, or None when the file is not there or not TOML."""
    try:
        return tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
        return None


def rigid_forces(scene, snapshot, block_names):
    """[(x, y, fx, fy)]: the `force` of the scene's rigid blocks, at their centroids."""
    centroids = layers.block_centroids(snapshot)
    index = {name: i for i, name in enumerate(block_names)}
    found = []
    for block in (scene or {}).get("block") or []:
        force = block.get("force")
        i = index.get(block.get("name"))
        if isinstance(force, list) and len(force) == 2 and any(force) and i in centroids:
            found.append((*centroids[i], float(force[0]), float(force[1])))
    return found


def model_figure(run, snapshot, chosen, size=(8.0, 6.0), title=None, scene=None, limits=None):
    """The model picture. chosen: {"geometry": True, "joints": None|"state"|"shear", "forces": bool,
    "stress": None|component, "stress_range": None|(low, high), "principal": bool,
    "displacement": bool, "displacement_scale": None|float, "plastic": bool, "boundaries": bool}.
    Returns (Figure, {layer: what its function returned})."""
    time = f", t = {snapshot.time:.6g} s" if snapshot.time is not None else ""
    heading = title or f"{run.title()}\ncycle {snapshot.cycle}{time}"
    with style():
        fig = Figure(figsize=size)
        ax = _model_axes(fig, wrapped(heading, 100) if title is None else title)
        drawn, notes = {}, [SIGN_NOTE]
        # Scaled layers are sized against the region shown, so that a close-up stays readable.
        shown = max(limits[1] - limits[0], limits[3] - limits[2]) if limits is not None else None
        if chosen.get("stress"):
            drawn["stress"] = layers.draw_stress(ax, snapshot, chosen["stress"], chosen.get("stress_range"))
        if chosen.get("plastic"):
            drawn["plastic"] = layers.draw_plastic(ax, run, snapshot)
        drawn["geometry"] = layers.draw_geometry(ax, snapshot, run.simply_deformable(),
                                                 fixed_hatch=chosen.get("boundaries", False),
                                                 stress_drawn=bool(chosen.get("stress")))
        if chosen.get("joints"):
            drawn["joints"] = layers.draw_joints(ax, run, snapshot, chosen["joints"])
        if chosen.get("forces"):
            lines, forces = drawn["forces"] = layers.draw_forces(ax, run, snapshot, extent=shown)
            notes.append(f"force lines along the contact normal, width and length proportional to |Fn|, "
                         f"largest {np.abs(forces).max():.3g} N/m; black compression, red tension")
        if chosen.get("principal"):
            lines, largest = drawn["principal"] = layers.draw_principal(ax, snapshot)
            notes.append(f"principal stress crosses, arms proportional to |sigma|, largest {largest:.3g} Pa; "
                         "black compression, red tension")
        if chosen.get("displacement"):
            arrows, scale, largest = drawn["displacement"] = layers.draw_displacement(
                ax, snapshot, chosen.get("displacement_scale"), extent=shown)
            notes.append(f"displacement vectors drawn {scale:.4g} times their length (largest |u| {largest:.3g} m)")
        if chosen.get("boundaries"):
            boundaries = drawn["boundaries"] = layers.draw_boundaries(
                ax, snapshot, rigid_forces(scene, snapshot, run.block_names()), extent=shown)
            if boundaries["loads"] is not None:
                notes.append(f"load arrows {boundaries['scale']:.4g} m per N/m")
            places = layers.history_locations(scene, snapshot, run.block_names(),
                                              run.results.get("contacts") if run.is_end(snapshot) else ())
            drawn["histories"] = layers.draw_points(ax, places, layers.HISTORY_COLOUR, "*", "history")
        if limits is not None:
            ax.set_xlim(limits[0], limits[1])
            ax.set_ylim(limits[2], limits[3])
        else:
            ax.autoscale_view()
            ax.margins(0.05)
        fig.text(0.01, 0.01, wrapped("; ".join(notes), 150), fontsize=6, va="bottom", ha="left")
        fig.subplots_adjust(bottom=0.14)
    return fig, drawn


def history_figure(run, names=None, x_axis="time", size=(8.0, 6.0), title=None):
    """One panel per history (results.json histories), against time (s) or cycle (t / dt). names:
    the histories to draw, all when empty. Returns the Figure."""
    histories = run.results.get("histories") or {}
    if not histories:
        raise PlotError(NO_DATA, f"--histories: {run.folder / 'results.json'} has no histories (the scene has no "
                                 "[[history]] tables)")
    names = list(names) or sorted(histories)
    unknown = [n for n in names if n not in histories]
    if unknown:
        raise PlotError(NO_DATA, f"--histories: no history {', '.join(map(repr, unknown))} in "
                                 f"{run.folder / 'results.json'} (it has {', '.join(sorted(histories))})")
    dt = float(run.results["run"].get("dt") or 0.0)
    if x_axis == "cycle" and dt <= 0.0:
        raise PlotError(NO_DATA, "--history-axis cycle: results.json has no run.dt to turn times into cycles")
    with style():
        fig = Figure(figsize=size)
        columns = 1 if len(names) < 4 else 2
        rows = math.ceil(len(names) / columns)
        axes = fig.subplots(rows, columns, squeeze=False, sharex=True)
        for ax, name in zip(axes.flat, names):
            t = np.asarray(histories[name]["t"], dtype=float)
            x = np.round(t / dt) if x_axis == "cycle" else t
            ax.plot(x, np.asarray(histories[name]["value"], dtype=float), lw=1.0, color="tab:blue")
            ax.set_title(name, fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, lw=0.3, alpha=0.5)
        for ax in axes.flat[len(names):]:
            ax.set_visible(False)
        for ax in axes[-1]:
            ax.set_xlabel("cycle" if x_axis == "cycle" else "time (s)")
        fig.suptitle(title or wrapped(f"{run.title()}: histories", 100), fontsize=8)
        fig.tight_layout()
    return fig


def setup_figure(snapshot, scene, block_names, contacts=(), samples=(), title="", size=(5.2, 4.0)):
    """The verification report's set-up picture of a problem: its geometry at cycle 0, the fixed
    and driven boundaries and the loads, where its histories sample (stars) and, given as samples
    [(label, x array, y array)], where its field checks sample (small dots). Returns the Figure."""
    with style():
        fig = Figure(figsize=size)
        ax = _model_axes(fig, title)
        layers.draw_geometry(ax, snapshot, fixed_hatch=True)
        boundaries = layers.draw_boundaries(ax, snapshot, rigid_forces(scene, snapshot, block_names))
        places = layers.history_locations(scene, snapshot, block_names, contacts)
        handles = []
        marked = layers.draw_points(ax, places, layers.HISTORY_COLOUR, "*", "history")
        if marked is not None:
            handles.append(marked)
        for k, (label, xs, ys) in enumerate(samples):
            handles.append(ax.plot(xs, ys, ls="none", marker="o", ms=2.5, color=layers.SAMPLE_COLOUR if k == 0
                                   else f"C{k}", zorder=8, label=label)[0])
        if handles:
            layers.add_legend(ax, "sampled", handles)
        ax.autoscale_view()
        ax.margins(0.05)
        notes = [f"load arrows {boundaries['scale']:.4g} m per N/m, at cycle 0"] if boundaries["loads"] else []
        gravity = ((scene or {}).get("model") or {}).get("gravity")
        if isinstance(gravity, list) and any(gravity):
            notes.append(f"gravity ({gravity[0]:g}, {gravity[1]:g}) m/s^2")
        if notes:
            fig.text(0.01, 0.01, "; ".join(notes), fontsize=6)
        ax.tick_params(labelsize=6)
    return fig


def plastic_result_figure(snapshot, states, source, title="", size=(5.2, 4.0)):
    """The plastic states at the end of a run (states: results.json zones.plastic_state, from the
    file source) on the zones of its cycle-0 model (the undeformed mesh), for the verification
    report. Returns the Figure."""
    with style():
        fig = Figure(figsize=size)
        ax = _model_axes(fig, title)
        layers.fill_plastic_states(ax, snapshot, states, source)
        layers.draw_geometry(ax, snapshot)
        ax.autoscale_view()
        ax.margins(0.05)
        ax.tick_params(labelsize=6)
    return fig
