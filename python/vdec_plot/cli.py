"""`vdec plot DIR [options]`: the command line (docs/user-manual/plot.md)."""
import argparse
import re
import sys
from pathlib import Path

from vdec_plot import __doc__ as PACKAGE_DOC
from vdec_plot.errors import EXIT_CODES, NO_DATA, USAGE, PlotError
from vdec_plot.figures import history_figure, model_figure, read_scene, save
from vdec_plot.layers import STRESS_COMPONENTS
from vdec_plot.run_output import load_run, parse_cycle

MAP_LAYERS = ("geometry", "joints", "forces", "stress", "principal", "displacement", "plastic", "boundaries")


class Parser(argparse.ArgumentParser):
    """argparse, with its usage errors raised as PlotError so that they share the exit-code table,
    and negative numbers in exponent notation (a stress range of -7e7 -1e7) taken as values: the
    stock matcher knows only -7 and -0.5, and takes -7e7 for an option."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

    def error(self, message):
        raise PlotError(USAGE, message)


def positive(kind):
    def convert(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
        if not value > 0:
            raise argparse.ArgumentTypeError(f"{text} is not above 0")
        return value
    return convert


def build_parser():
    codes = "\n".join(f"  {code}  {meaning}" for code, meaning in EXIT_CODES.items())
    parser = Parser(prog="vdec plot", formatter_class=argparse.RawDescriptionHelpFormatter,
                    description=PACKAGE_DOC.split("\n\n")[0],
                    epilog=f"exit codes:\n{codes}\n\nexamples:\n"
                           "  vdec plot out                                   geometry at the last snapshot\n"
                           "  vdec plot out --joints --forces --out forces.png\n"
                           "  vdec plot out --stress syy --principal --cycle 2000 --out syy.pdf\n"
                           "  vdec plot out --plastic --displacement --displacement-scale 50\n"
                           "  vdec plot out --histories ratio settlement --history-axis cycle\n"
                           "See docs/user-manual/plot.md.")
    parser.add_argument("folder", metavar="DIR", help="the --out DIR of a `vdec run`: DIR/results.json and DIR/vtk/")
    what = parser.add_argument_group("layers (any together; the geometry is always drawn under them)")
    what.add_argument("--joints", nargs="?", const="state", choices=("state", "shear"),
                      help="contacts as segments along the joint, coloured by state (open, slipping, closed with a "
                           "broken bond, closed), or with `shear` by |shear displacement| (m); end of run only")
    what.add_argument("--forces", action="store_true",
                      help="contact normal forces: lines along the normal, width and length proportional to |Fn|; "
                           "end of run only")
    what.add_argument("--stress", choices=STRESS_COMPONENTS, metavar="COMPONENT",
                      help="fill zones and simply-deformable blocks with a stress (Pa, tension positive): "
                           + ", ".join(STRESS_COMPONENTS) + " (max/min: major/minor principal)")
    what.add_argument("--stress-range", nargs=2, type=float, metavar=("LOW", "HIGH"),
                      help="colour range of --stress in Pa (default: the data's)")
    what.add_argument("--principal", action="store_true", help="principal stress crosses at zone centroids")
    what.add_argument("--displacement", action="store_true", help="displacement vectors")
    what.add_argument("--displacement-scale", type=positive(float), metavar="S",
                      help="draw displacements S times their length (default: the largest 8%% of the model's size)")
    what.add_argument("--plastic", action="store_true",
                      help="plastic state of Mohr-Coulomb zones; end of run only")
    what.add_argument("--boundaries", action="store_true",
                      help="driven (fixed) gridpoints and blocks, loads, and where the histories sample")
    what.add_argument("--histories", nargs="*", metavar="NAME",
                      help="a picture of the histories instead (all, or those named), against --history-axis")
    what.add_argument("--history-axis", choices=("time", "cycle"), default="time", help="abscissa of --histories")
    where = parser.add_argument_group("snapshot, view and output")
    where.add_argument("--cycle", default="last", type=str, metavar="N|first|last",
                       help="the snapshot to draw, by cycle (default last, the end of the run)")
    where.add_argument("--window", nargs=4, type=float, metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
                       help="the region to show (m); default: the whole model")
    where.add_argument("--scene", metavar="FILE",
                       help="the scene file, for history places and blocks' applied forces with --boundaries "
                            "(default: results.json scene.path, if it is there)")
    where.add_argument("--title", help="title (default: the scene's title, cycle and time)")
    where.add_argument("--out", metavar="FILE",
                       help="picture file; .png, .svg or .pdf (default DIR/plot-cycleN.png, DIR/histories.png)")
    where.add_argument("--size", nargs=2, type=positive(float), default=(8.0, 6.0), metavar=("W", "H"),
                       help="figure size in inches (default 8 6)")
    where.add_argument("--dpi", type=positive(int), default=150, help="resolution of a PNG (default 150)")
    return parser


def scene_of(run, given):
    """The scene's tables for --boundaries: --scene, else results.json's scene.path as run from the
    current folder or beside DIR; None (with a note) when it cannot be read."""
    if given:
        scene = read_scene(given)
        if scene is None:
            raise PlotError(USAGE, f"--scene {given}: not a readable TOML file")
        return scene
    recorded = (run.results.get("scene") or {}).get("path") or ""
    for candidate in (Path(recorded), run.folder.parent / recorded):
        if recorded and candidate.is_file():
            return read_scene(candidate)
    print(f"vdec plot: note: scene {recorded!r} not found: history places and blocks' applied forces are not drawn "
          "(give --scene FILE)", file=sys.stderr)
    return None


def plot(args):
    run = load_run(args.folder)
    chosen_layers = [name for name in MAP_LAYERS if getattr(args, name, None)]
    if args.histories is not None:
        if chosen_layers:
            raise PlotError(USAGE, f"--histories draws its own picture: give it without --{chosen_layers[0]}")
        fig = history_figure(run, args.histories, args.history_axis, tuple(args.size), args.title)
        out = Path(args.out) if args.out else run.folder / "histories.png"
    else:
        parse_cycle(args.cycle)
        snapshot = run.snapshot(args.cycle)
        chosen = {name: getattr(args, name) for name in MAP_LAYERS if name != "geometry"}
        chosen.update(stress_range=args.stress_range, displacement_scale=args.displacement_scale)
        if args.stress_range and not args.stress:
            raise PlotError(USAGE, "--stress-range is the colour range of --stress: give --stress COMPONENT too")
        if args.stress_range and args.stress_range[0] >= args.stress_range[1]:
            raise PlotError(USAGE, f"--stress-range {args.stress_range[0]:g} {args.stress_range[1]:g}: LOW must be "
                                   "below HIGH")
        if args.window and (args.window[0] >= args.window[1] or args.window[2] >= args.window[3]):
            raise PlotError(USAGE, "--window XMIN XMAX YMIN YMAX: each minimum must be below its maximum")
        scene = scene_of(run, args.scene) if args.boundaries else None
        fig, _ = model_figure(run, snapshot, chosen, tuple(args.size), args.title, scene, args.window)
        out = Path(args.out) if args.out else run.folder / f"plot-cycle{snapshot.cycle}.png"
    save(fig, out, args.dpi)
    print(out)
    return 0


def main(argv=None):
    try:
        args = build_parser().parse_args(argv)
        return plot(args)
    except PlotError as e:
        print(f"vdec plot: error: {e}", file=sys.stderr)
        return e.code
