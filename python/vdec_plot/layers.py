"""The layers of a model picture, each drawn onto a matplotlib Axes from a snapshot and, for the
states only results.json holds (joint states, contact normals, plastic states), from the run's
results. Each function returns what it drew, so that tests can count and colour-check it.

Sign conventions are vdec's (docs/README.md#conventions): zone stresses tension positive, joint
normal force compression positive."""
import math

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import FuncFormatter

from vdec_plot.errors import NO_DATA, PlotError
from vdec_plot.snapshot import BEAM_ELEMENT, BOLT, CABLE_ELEMENT, RIGID_BLOCK, ZONE

# Joint states, in the order a contact is tested for them.
JOINT_COLOURS = {"open": "tab:red", "slipping": "tab:orange", "closed, bond broken": "tab:purple",
                 "closed": "tab:blue"}
# Plastic states of Mohr-Coulomb zones (results.json zones.plastic_state bits: 1 shear now,
# 2 tension now, 4 yielded before); never-yielded zones are left unfilled.
PLASTIC_COLOURS = {"yielding in shear now": "tab:red", "yielding in tension now": "tab:purple",
                   "yielded before, elastic now": "tab:olive"}
STRESS_COMPONENTS = ("sxx", "syy", "sxy", "szz", "mean", "max", "min")
STRESS_MEANINGS = {"sxx": "sxx", "syy": "syy", "sxy": "sxy", "szz": "szz (out of plane)",
                   "mean": "mean stress (sxx + syy + szz) / 3", "max": "major principal stress (most tensile)",
                   "min": "minor principal stress (most compressive)"}
COMPRESSION_COLOUR, TENSION_COLOUR = "black", "tab:red"
OUTLINE_COLOUR, ZONE_EDGE_COLOUR = "black", "0.6"
RIGID_FACE, SIMPLY_DEFORMABLE_FACE = "0.92", "#dde8f4"
STRUCTURE_COLOURS = {BEAM_ELEMENT: ("darkgreen", "beam"), CABLE_ELEMENT: ("saddlebrown", "cable"),
                     BOLT: ("darkmagenta", "bolt")}


def model_extent(snapshot):
    """The larger side of the box round the zones and blocks (m), the length scales are set against."""
    used = np.unique(np.concatenate([snapshot.cells[i] for i in snapshot_body_cells(snapshot)] or [np.zeros(0, int)]))
    points = snapshot.points[used] if used.size else snapshot.points
    if not points.size:
        return 1.0
    span = points.max(axis=0) - points.min(axis=0)
    return float(max(span.max(), 1e-12))


def add_legend(ax, title, handles):
    """Adds a titled section to the axes' one legend, redrawn with every section so far: layers
    drawn together share it, where separate legends would cover each other (each at loc "best")
    and a later ax.legend() call would drop an earlier layer's."""
    sections = ax.__dict__.setdefault("vdec_legend_sections", [])
    sections.append((title, list(handles)))
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    entries, headings = [], []
    for heading, section in sections:
        headings.append(len(entries))
        entries.append(Patch(visible=False, label=heading))
        entries.extend(section)
    legend = ax.legend(handles=entries, loc="best", fontsize=7)
    for i in headings:
        legend.get_texts()[i].set_fontweight("bold")
    return legend


def snapshot_body_cells(snapshot):
    kinds = snapshot.cell_data["kind"]
    return np.flatnonzero((kinds == ZONE) | (kinds == RIGID_BLOCK))


def block_outline_edges(snapshot):
    """The outline edges of the deformable blocks: zone edges that only one zone of a block has."""
    zones = snapshot.of_kind(ZONE)
    count = {}
    for z in zones:
        a, b, c = (int(p) for p in snapshot.cells[z])
        block = int(snapshot.cell_data["block"][z])
        for edge in ((a, b), (b, c), (c, a)):
            key = (block, min(edge), max(edge))
            count[key] = count.get(key, 0) + 1
    return [(i, j) for (_, i, j), n in count.items() if n == 1]


def draw_geometry(ax, snapshot, simply_deformable=(), fixed_hatch=False, stress_drawn=False):
    """Zones (thin grey edges), the outlines of deformable blocks, rigid blocks (grey),
    simply-deformable blocks (blue, or unfilled over a stress layer: stress_drawn), and beams,
    cables and bolts as lines (STRUCTURE_COLOURS); with fixed_hatch, a rigid block with every
    degree of freedom driven is hatched. Returns {"zones", "outlines", "rigid", and "beam",
    "cable", "bolt" when present} collections (None when absent)."""
    drawn = {"zones": None, "outlines": None, "rigid": None}
    zones = snapshot.of_kind(ZONE)
    if zones.size:
        drawn["zones"] = ax.add_collection(PolyCollection(snapshot.polygons(zones), facecolors="none",
                                                          edgecolors=ZONE_EDGE_COLOUR, linewidths=0.3, zorder=1))
        edges = block_outline_edges(snapshot)
        drawn["outlines"] = ax.add_collection(LineCollection([snapshot.points[list(e)] for e in edges],
                                                             colors=OUTLINE_COLOUR, linewidths=1.0, zorder=3))
    rigid = snapshot.of_kind(RIGID_BLOCK)
    if rigid.size:
        blocks = snapshot.cell_data["block"][rigid]
        strained = "none" if stress_drawn else SIMPLY_DEFORMABLE_FACE
        faces = [strained if b in simply_deformable else RIGID_FACE for b in blocks]
        collection = PolyCollection(snapshot.polygons(rigid), facecolors=faces, edgecolors=OUTLINE_COLOUR,
                                    linewidths=0.8, zorder=2)
        if fixed_hatch and "driven" in snapshot.point_data:
            driven = snapshot.point_data["driven"]
            fixed = [i for i, cell in enumerate(rigid) if int(driven[snapshot.cells[cell][0]]) & 7 == 7]
            if fixed:
                ax.add_collection(PolyCollection([snapshot.points[snapshot.cells[rigid[i]]] for i in fixed],
                                                 facecolors="none", edgecolors="0.45", linewidths=0.0,
                                                 hatch="////", zorder=2.1))
        drawn["rigid"] = ax.add_collection(collection)
    handles = []
    for kind, (colour, label) in STRUCTURE_COLOURS.items():
        cells = snapshot.of_kind(kind)
        if cells.size:
            drawn[label] = ax.add_collection(LineCollection(snapshot.polygons(cells), colors=colour, linewidths=1.8,
                                                            zorder=4))
            handles.append(Line2D([], [], color=colour, lw=1.8, label=f"{label} elements ({cells.size})"))
    if handles:
        add_legend(ax, "supports", handles)
    ax.autoscale_view()
    return drawn


def _require_end(run, snapshot, layer):
    if run is None or not run.is_end(snapshot):
        cycle = "" if run is None else f" (cycle {run.last_cycle})"
        raise PlotError(NO_DATA, f"--{layer}: the {layer} come from results.json, which holds the end of the run"
                                 f"{cycle} only; draw them with --cycle last")


def joint_state(contact):
    if contact.get("open"):
        return "open"
    if contact.get("slipping"):
        return "slipping"
    if contact.get("law") == "coulomb-fracture" and not contact.get("intact", True):
        return "closed, bond broken"
    return "closed"


def _normal_segments(contacts, half_length_of):
    segments = []
    for c in contacts:
        (px, py), (nx, ny) = c["point"], c["normal"]
        h = half_length_of(c)
        segments.append([(px - h * nx, py - h * ny), (px + h * nx, py + h * ny)])
    return segments


def block_points(snapshot):
    """{block index: (k, 2) array}: a rigid block's vertices, a deformable block's gridpoints."""
    kinds, blocks = snapshot.cell_data["kind"], snapshot.cell_data["block"]
    indices = {}
    for cell in np.flatnonzero((kinds == ZONE) | (kinds == RIGID_BLOCK)):
        indices.setdefault(int(blocks[cell]), []).append(snapshot.cells[cell])
    return {block: snapshot.points[np.unique(np.concatenate(cells))] for block, cells in indices.items()}


def joint_segments(contacts, snapshot, block_names, shortest):
    """Each contact's segment along its joint: as long as its contact length (at least shortest),
    centred on its point, but moved along the joint where that would take it beyond either block,
    as at a joint's end, and shortened where the blocks share less than that length. A block's
    extent along the joint is that of its vertices or gridpoints on the joint's line."""
    points = block_points(snapshot)
    index = {name: i for i, name in enumerate(block_names)}
    on_line = 1e-3 * model_extent(snapshot)
    segments = []
    for c in contacts:
        p, n = np.asarray(c["point"], dtype=float), np.asarray(c["normal"], dtype=float)
        along = np.array([n[1], -n[0]])
        length = max(c.get("length", 0.0), shortest)
        low, high = -math.inf, math.inf
        for name in (c.get("block_a"), c.get("block_b")):
            vertices = points.get(index.get(name))
            if vertices is None:
                continue
            offsets = vertices - p
            shared = np.abs(offsets @ n) <= on_line
            if shared.any():
                positions = offsets[shared] @ along
                low, high = max(low, float(positions.min())), min(high, float(positions.max()))
        start = -0.5 * length
        if low < high:
            length = min(length, high - low)
            start = min(max(start, low), high - length)
        segments.append([p + start * along, p + (start + length) * along])
    return segments


def draw_joints(ax, run, snapshot, colour_by="state"):
    """Each contact as a segment of its length along the joint at its point, kept on its two
    blocks (joint_segments). colour_by "state":
    open, slipping, closed with a broken bond (model 5), closed (JOINT_COLOURS); "shear": the
    magnitude of its accumulated shear displacement (m), on a colour bar. Returns the
    LineCollection (its colours per segment, in results.json's contact order)."""
    _require_end(run, snapshot, "joints")
    contacts = run.results.get("contacts") or []
    if not contacts:
        raise PlotError(NO_DATA, f"--joints: {run.folder / 'results.json'} lists no contacts")
    shortest = 0.005 * model_extent(snapshot)
    segments = joint_segments(contacts, snapshot, run.block_names(), shortest)
    if colour_by == "state":
        states = [joint_state(c) for c in contacts]
        lines = LineCollection(segments, colors=[JOINT_COLOURS[s] for s in states], linewidths=2.0, zorder=5)
        ax.add_collection(lines)
        present = [s for s in JOINT_COLOURS if s in states]
        add_legend(ax, "joints", [Line2D([], [], color=JOINT_COLOURS[s], lw=2, label=f"{s} ({states.count(s)})")
                                  for s in present])
        return lines
    shear = np.abs([c.get("shear_displacement", 0.0) for c in contacts])
    lines = LineCollection(segments, cmap="plasma", linewidths=2.0, zorder=5)
    lines.set_array(shear)
    lines.set_clim(0.0, max(float(shear.max()), 1e-300))
    ax.add_collection(lines)
    ax.figure.colorbar(lines, ax=ax, shrink=0.8, label="|joint shear displacement| (m)")
    return lines


def draw_forces(ax, run, snapshot, largest_width=4.0, extent=None):
    """The contacts' normal forces as segments along the contact normal through the contact point,
    their widths proportional to |Fn| (the largest largest_width points) and their lengths too (the
    largest 6 % of extent, the size of the region shown, by default the model's): black in compression,
    red in tension. Open contacts, with no
    force, are not drawn. Returns (LineCollection, forces drawn in N/m)."""
    _require_end(run, snapshot, "forces")
    contacts = [c for c in run.results.get("contacts") or [] if c.get("normal_force", 0.0) != 0.0]
    if not contacts:
        raise PlotError(NO_DATA, f"--forces: {run.folder / 'results.json'} has no contact carrying a normal force")
    forces = np.array([c["normal_force"] for c in contacts])
    largest = float(np.abs(forces).max())
    half = 0.03 * (extent or model_extent(snapshot))
    segments = _normal_segments(contacts, lambda c: half * abs(c["normal_force"]) / largest)
    lines = LineCollection(segments, colors=[COMPRESSION_COLOUR if f > 0 else TENSION_COLOUR for f in forces],
                           linewidths=np.maximum(largest_width * np.abs(forces) / largest, 0.2), zorder=6,
                           capstyle="butt")
    ax.add_collection(lines)
    return lines, forces


def _stressed_cells(snapshot):
    """Zones and simply-deformable blocks: the cells that carry a stress."""
    kinds = snapshot.cell_data["kind"]
    stressed = np.zeros(kinds.shape, dtype=bool)
    stressed[kinds == ZONE] = True
    rigid = kinds == RIGID_BLOCK
    for name in ("sxx", "syy", "sxy", "szz"):
        stressed |= rigid & (snapshot.cell_data[name] != 0.0)
    return np.flatnonzero(stressed)


def principal_stresses(sxx, syy, sxy):
    """(major, minor, angle of the major from x in radians); tension positive, so major is the
    most tensile."""
    centre, radius = 0.5 * (sxx + syy), np.hypot(0.5 * (sxx - syy), sxy)
    return centre + radius, centre - radius, 0.5 * np.arctan2(2.0 * sxy, sxx - syy)


def stress_values(snapshot, cells, component):
    d = {k: snapshot.cell_data[k][cells] for k in ("sxx", "syy", "sxy", "szz")}
    if component in ("sxx", "syy", "sxy", "szz"):
        return d[component]
    if component == "mean":
        return (d["sxx"] + d["syy"] + d["szz"]) / 3.0
    major, minor, _ = principal_stresses(d["sxx"], d["syy"], d["sxy"])
    return major if component == "max" else minor


def draw_stress(ax, snapshot, component, limits=None):
    """Zones and simply-deformable blocks filled with one stress component (tension positive),
    constant over each zone as the constant-strain triangle's stress is; the colour range is the
    data's unless limits (low, high, Pa) are given; the colour bar reads in MPa, kPa or Pa
    (stress_unit). Returns the PolyCollection."""
    cells = _stressed_cells(snapshot)
    if not cells.size:
        raise PlotError(NO_DATA, f"--stress: {snapshot.path} has no zones or simply-deformable blocks, whose stress it "
                                 "draws (rigid blocks carry none; their contact forces: --forces)")
    values = stress_values(snapshot, cells, component)
    low, high = limits if limits is not None else (float(values.min()), float(values.max()))
    if low == high:
        low, high = low - 0.5 * max(abs(low), 1.0), high + 0.5 * max(abs(high), 1.0)
    filled = PolyCollection(snapshot.polygons(cells), cmap="viridis", edgecolors="face", linewidths=0.2, zorder=1.5)
    filled.set_array(values)
    filled.set_clim(low, high)
    ax.add_collection(filled)
    unit, pascals = stress_unit(max(abs(low), abs(high)))
    # Ticks read in the unit named, without the "1e7" offset above the bar that is easily missed.
    bar = ax.figure.colorbar(filled, ax=ax, shrink=0.8, label=f"{STRESS_MEANINGS[component]} ({unit}, tension positive)",
                             format=FuncFormatter(lambda value, _: f"{value / pascals:g}"))
    bar.ax.yaxis.get_offset_text().set_visible(False)
    return filled


def stress_unit(largest):
    """(unit, Pa per unit) in which stresses up to `largest` Pa read best: MPa, kPa or Pa."""
    for unit, pascals in (("MPa", 1e6), ("kPa", 1e3)):
        if largest >= pascals:
            return unit, pascals
    return "Pa", 1.0


def draw_principal(ax, snapshot):
    """A cross at the centroid of each zone and simply-deformable block along its principal
    directions, each arm as long as its principal stress is large (the largest |sigma| across
    the median zone's size): black compression, red tension. Returns (LineCollection, largest |sigma|)."""
    cells = _stressed_cells(snapshot)
    if not cells.size:
        raise PlotError(NO_DATA, f"--principal: {snapshot.path} has no zones or simply-deformable blocks")
    polygons = snapshot.polygons(cells)
    centres = np.array([p.mean(axis=0) for p in polygons])
    sizes = np.array([math.sqrt(abs(_area(p))) for p in polygons])
    major, minor, angle = principal_stresses(*(snapshot.cell_data[k][cells] for k in ("sxx", "syy", "sxy")))
    largest = float(max(np.abs(major).max(), np.abs(minor).max()))
    if largest == 0.0:
        raise PlotError(NO_DATA, f"--principal: every stress in {snapshot.path} is zero")
    arm = 0.5 * float(np.median(sizes)) / largest
    segments, colours = [], []
    for (x, y), s1, s2, a in zip(centres, major, minor, angle):
        for value, theta in ((s1, a), (s2, a + 0.5 * math.pi)):
            h = arm * abs(value)
            dx, dy = h * math.cos(theta), h * math.sin(theta)
            segments.append([(x - dx, y - dy), (x + dx, y + dy)])
            colours.append(TENSION_COLOUR if value > 0 else COMPRESSION_COLOUR)
    lines = LineCollection(segments, colors=colours, linewidths=0.8, zorder=6)
    ax.add_collection(lines)
    return lines, largest


def _area(polygon):
    x, y = polygon[:, 0], polygon[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def displacement_points(snapshot):
    """(points, displacements): every gridpoint of a zone, and each rigid block at the mean of its
    vertices (where its rigid motion's displacement is the mean of theirs)."""
    u = snapshot.point_data.get("displacement")
    if u is None:
        return np.zeros((0, 2)), np.zeros((0, 2))
    zones = snapshot.of_kind(ZONE)
    gridpoints = np.unique(np.concatenate([snapshot.cells[z] for z in zones])) if zones.size else np.zeros(0, int)
    at, values = [snapshot.points[gridpoints]], [u[gridpoints]]
    for cell in snapshot.of_kind(RIGID_BLOCK):
        vertices = snapshot.cells[cell]
        at.append(snapshot.points[vertices].mean(axis=0, keepdims=True))
        values.append(u[vertices].mean(axis=0, keepdims=True))
    return np.concatenate(at), np.concatenate(values)


def draw_displacement(ax, snapshot, scale=None, extent=None):
    """Displacement vectors drawn `scale` times their length (default: the largest as long as 8 %
    of extent, the size of the region shown, by default the model's), at the gridpoints and the rigid blocks' vertex means. Returns
    (Quiver, scale used, largest |u| in m)."""
    at, u = displacement_points(snapshot)
    magnitude = np.hypot(u[:, 0], u[:, 1]) if u.size else np.zeros(0)
    if not magnitude.size or magnitude.max() == 0.0:
        raise PlotError(NO_DATA, f"--displacement: nothing has moved in {snapshot.path} (every displacement is zero)")
    largest = float(magnitude.max())
    scale = scale if scale is not None else 0.08 * (extent or model_extent(snapshot)) / largest
    arrows = ax.quiver(at[:, 0], at[:, 1], u[:, 0], u[:, 1], angles="xy", scale_units="xy", scale=1.0 / scale,
                       color="tab:green", width=0.003, zorder=7)
    return arrows, scale, largest


def draw_plastic(ax, run, snapshot):
    """Zones of Mohr-Coulomb material filled by plastic state at the end of the run (results.json
    zones.plastic_state): PLASTIC_COLOURS; zones that never yielded are not filled. Returns
    (PolyCollection, state label per zone, None where not filled)."""
    _require_end(run, snapshot, "plastic")
    return fill_plastic_states(ax, snapshot, (run.results.get("zones") or {}).get("plastic_state"),
                               run.folder / "results.json")


def fill_plastic_states(ax, snapshot, states, source):
    """Fills the snapshot's zones by the plastic states `states` (one per zone, from the results
    file `source`), as draw_plastic does."""
    zones = snapshot.of_kind(ZONE)
    if not states:
        raise PlotError(NO_DATA, f"--plastic: {source} has no zones, whose plastic states it draws")
    if len(states) != zones.size:
        raise PlotError(NO_DATA, f"--plastic: {snapshot.path} has {zones.size} zones and {source} "
                                 f"{len(states)}: they are not of the same run")
    labels = []
    for s in states:
        s = int(s)
        labels.append("yielding in shear now" if s & 1 else "yielding in tension now" if s & 2
                      else "yielded before, elastic now" if s & 4 else None)
    filled = [i for i, label in enumerate(labels) if label]
    collection = PolyCollection(snapshot.polygons(zones[filled]) if filled else [],
                                facecolors=[PLASTIC_COLOURS[labels[i]] for i in filled], edgecolors="none", zorder=1.6)
    ax.add_collection(collection)
    present = [s for s in PLASTIC_COLOURS if s in labels]
    add_legend(ax, "plastic state",
               [Patch(color=PLASTIC_COLOURS[s], label=f"{s} ({labels.count(s)})") for s in present]
               + [Patch(facecolor="none", edgecolor=ZONE_EDGE_COLOUR, label=f"never yielded ({labels.count(None)})")])
    return collection, labels


DRIVEN_MARKERS = {1: (">", "x driven"), 2: ("^", "y driven"), 3: ("s", "x and y driven")}
LOAD_COLOUR, HISTORY_COLOUR, SAMPLE_COLOUR = "tab:red", "tab:cyan", "tab:pink"


def draw_boundaries(ax, snapshot, rigid_forces=(), scale=None, extent=None):
    """The boundary conditions the snapshot records (its `driven` and `boundary_load` point
    arrays): gridpoints with a driven velocity component (zero when fixed) marked by component
    (DRIVEN_MARKERS), rigid blocks with every degree of freedom driven hatched (by draw_geometry)
    and partly driven ones marked with a diamond, and the loads as red arrows: the loaded edges'
    forces on their gridpoints at the snapshot's time, and rigid_forces [(x, y, fx, fy)] (a block's
    applied force at its centroid), the largest as long as 8 % of extent (the size of the region
    shown, by default the model's) unless scale (m per N/m) is given. Returns {"driven": {bits: count}, "loads": Quiver or None, "scale": scale}."""
    if not snapshot.has_boundary_conditions():
        raise PlotError(NO_DATA, f"--boundaries: {snapshot.path} has no `driven` and `boundary_load` arrays (written by "
                                 "vdec builds after 0.1.0's boundary-condition output); run the scene again with this vdec")
    driven, load = snapshot.point_data["driven"].astype(int), snapshot.point_data["boundary_load"]
    zones = snapshot.of_kind(ZONE)
    gridpoints = np.unique(np.concatenate([snapshot.cells[z] for z in zones])) if zones.size else np.zeros(0, int)
    counts, handles = {}, []
    for bits, (marker, label) in DRIVEN_MARKERS.items():
        chosen = gridpoints[(driven[gridpoints] & 3) == bits]
        if chosen.size:
            counts[bits] = int(chosen.size)
            ax.plot(*snapshot.points[chosen].T, ls="none", marker=marker, ms=4, mfc="tab:blue", mec="navy", mew=0.4,
                    zorder=8)
            handles.append(Line2D([], [], ls="none", marker=marker, mfc="tab:blue", mec="navy", label=label))
    partly = [c for c in snapshot.of_kind(RIGID_BLOCK) if 0 < int(driven[snapshot.cells[c][0]]) & 7 < 7]
    if partly:
        at = np.array([snapshot.points[snapshot.cells[c]].mean(axis=0) for c in partly])
        ax.plot(at[:, 0], at[:, 1], ls="none", marker="D", ms=5, mfc="tab:blue", mec="navy", zorder=8)
        handles.append(Line2D([], [], ls="none", marker="D", mfc="tab:blue", mec="navy", label="block partly driven"))
    if any(int(driven[snapshot.cells[c][0]]) & 7 == 7 for c in snapshot.of_kind(RIGID_BLOCK)):
        handles.append(Patch(facecolor=RIGID_FACE, edgecolor="0.45", hatch="////", label="block fixed"))
    loaded = np.flatnonzero(np.hypot(load[:, 0], load[:, 1]) > 0.0)
    vectors = np.concatenate([np.column_stack([snapshot.points[loaded], load[loaded]]),
                              np.array(list(rigid_forces), dtype=float).reshape(-1, 4)])
    arrows = None
    if vectors.size:
        largest = float(np.hypot(vectors[:, 2], vectors[:, 3]).max())
        scale = scale if scale is not None else 0.08 * (extent or model_extent(snapshot)) / largest
        arrows = ax.quiver(vectors[:, 0], vectors[:, 1], vectors[:, 2], vectors[:, 3], angles="xy", scale_units="xy",
                           scale=1.0 / scale, color=LOAD_COLOUR, width=0.004, zorder=8)
        handles.append(Line2D([], [], color=LOAD_COLOUR, marker=">", label=f"load (largest {largest:.3g} N/m)"))
    if handles:
        add_legend(ax, "boundaries", handles)
    return {"driven": counts, "loads": arrows, "scale": scale}


def block_centroids(snapshot):
    """{block index: centroid (m)}: a rigid block's polygon's vertex mean, a deformable block's
    zone-area-weighted centroid."""
    centroids = {}
    for cell in snapshot.of_kind(RIGID_BLOCK):
        centroids[int(snapshot.cell_data["block"][cell])] = snapshot.points[snapshot.cells[cell]].mean(axis=0)
    sums = {}
    for z in snapshot.of_kind(ZONE):
        p = snapshot.points[snapshot.cells[z]]
        a = abs(_area(p))
        block = int(snapshot.cell_data["block"][z])
        total = sums.setdefault(block, [0.0, np.zeros(2)])
        total[0] += a
        total[1] += a * p.mean(axis=0)
    centroids.update({b: s / a for b, (a, s) in sums.items() if a > 0})
    return centroids


def history_locations(scene, snapshot, block_names, contacts=()):
    """[(name, x, y)] of the scene's [[history]] tables that sample at a place: a `point`; a block's
    centroid for a block quantity; the mean of the contact points between a joint's two blocks
    (from results.json contacts, when given). Model-wide quantities have no place."""
    centroids = block_centroids(snapshot)
    index = {name: i for i, name in enumerate(block_names)}
    found = []
    for h in (scene or {}).get("history") or []:
        name = h.get("name", "?")
        if isinstance(h.get("point"), list) and len(h["point"]) == 2:
            found.append((name, float(h["point"][0]), float(h["point"][1])))
        elif isinstance(h.get("block"), str) and index.get(h["block"]) in centroids:
            x, y = centroids[index[h["block"]]]
            found.append((name, float(x), float(y)))
        elif isinstance(h.get("blocks"), list):
            pair = set(h["blocks"])
            points = [c["point"] for c in contacts if {c.get("block_a"), c.get("block_b")} == pair]
            if points:
                x, y = np.mean(points, axis=0)
                found.append((name, float(x), float(y)))
    return found


def draw_points(ax, places, colour, marker, label):
    """Named places [(name, x, y)] as markers with their names beside them."""
    if not places:
        return None
    xy = np.array([(x, y) for _, x, y in places])
    drawn = ax.plot(xy[:, 0], xy[:, 1], ls="none", marker=marker, ms=7, mfc=colour, mec="black", mew=0.5, zorder=9,
                    label=label)[0]
    # Histories sampled at one place (a block's displacement and rotation) share one label, where
    # separate labels would be printed over each other.
    names_at = {}
    for name, x, y in places:
        names_at.setdefault((x, y), []).append(name)
    for (x, y), names in names_at.items():
        ax.annotate(", ".join(names), (x, y), textcoords="offset points", xytext=(4, 4), fontsize=6, zorder=9)
    return drawn
