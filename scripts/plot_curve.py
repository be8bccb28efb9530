#!/usr/bin/python3
"""Draw curve.csv of a pushout run as a PNG.

push-out: nominal bond stress tau [MPa] against tube displacement delta [um]
(paper eq. 1); single joint: shear force F_s [N] against shear displacement
u_s [mm]; corrosion (corrosion.csv): interface pressure p [MPa] and crack
widths [um] against the corrosion depth x [um]; crack pattern
(crack_pattern.csv, with [cracking]): the slice seen along the tube axis,
each column of the concrete coloured by its thickness-mean crack opening,
and the crack planes (crack_planes.csv beside it) by their mouth opening.
Usage: plot_curve.py CSV OUT.png --kind pushout|single_joint|corrosion|crack_pattern
       plot_curve.py --serve   (plots named on stdin: what pushout runs)
"""
import argparse
import csv
import json
import os
import signal
import sys

if "--serve" in sys.argv:
    # The run's signals are the run's, from the start (the import below
    # takes most of a second): this process ends when its stdin does.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)

# The figure API without pyplot: a fifth less to import, and nothing of
# pyplot's global state (each figure is drawn and dropped).
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402


# The columns each kind draws from (a file of another kind lacks them).
NEEDS = {"pushout": ("delta_mm", "tau_MPa"), "single_joint": ("u_s_mm", "F_s_N"),
         "corrosion": ("penetration_mm", "p_MPa"),
         "crack_pattern": ("x_mm", "opening_mm") + tuple(f"corner_{k}_{c}_mm" for k in range(4)
                                                       for c in "xy")}


class PlotError(Exception):
    """A file that cannot be drawn as asked, said in one line."""


def read(path):
    """Each column of the CSV file at `path` (its header's, also where it has
    no row: a run that failed before its first step)."""
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            names = reader.fieldnames or []
        return {k: [float(r[k]) for r in rows] for k in names}
    except OSError as e:
        raise PlotError(f"cannot read {path}: {e.strerror}") from None
    except (ValueError, TypeError, UnicodeDecodeError, csv.Error):
        raise PlotError(f"{path} is not a CSV table of numbers (a file of pushout's?)") from None


def read_kind(path, kind):
    """read(path), which must hold the columns `kind` draws (NEEDS)."""
    data = read(path)
    missing = [k for k in NEEDS[kind] if k not in data]
    if missing:
        raise PlotError(f"{path} has no column {', '.join(missing)}: not a {kind} file "
                        f"(--kind {kind} draws {', '.join(NEEDS[kind])})")
    return data


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("csv", nargs="?")
    ap.add_argument("png", nargs="?")
    ap.add_argument("--kind", default="pushout", choices=["pushout", "single_joint", "corrosion", "crack_pattern"])
    ap.add_argument("--title", default=None)
    ap.add_argument("--serve", action="store_true",
                    help="draw the plots named on stdin, one JSON list [csv, png, kind] per line, "
                         "until its end (pushout starts this when a run starts, so that importing "
                         "matplotlib overlaps the run)")
    args = ap.parse_args()
    if args.serve:
        # While the run computes: draw a figure like the ones to come, to
        # nowhere, so that fonts, mathtext and the renderer are ready when
        # the first plot is asked for.
        try:
            draw_example()
        except Exception as e:  # noqa: BLE001  (the plots asked for may still work)
            print(f"plot_curve.py: warming up: {e}", file=sys.stderr)
        failed = False
        for line in sys.stdin:
            if not line.strip():
                continue
            csv_path, png, kind = json.loads(line)
            try:
                draw(csv_path, png, kind, None)
            except Exception as e:  # noqa: BLE001  (reported, the next plot still drawn)
                print(f"plot_curve.py: {png}: {e}", file=sys.stderr)
                failed = True
        # pushout waits for this process to end: skip the interpreter's
        # teardown of matplotlib (a fifth of a second); the files are closed.
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(1 if failed else 0)
    if not args.csv or not args.png:
        ap.error("CSV and OUT.png are needed (or --serve)")
    if os.path.isdir(args.png):
        ap.error(f"{args.png} is a folder: name the PNG file to write")
    try:
        draw(args.csv, args.png, args.kind, args.title)
    except PlotError as e:
        sys.exit(f"plot_curve.py: error: {e}")


def draw_example():
    """A push-out figure drawn in memory and thrown away (serve mode)."""
    fig = Figure(figsize=(6, 4), dpi=120)
    FigureCanvasAgg(fig)
    plot(fig, {"delta_mm": [0.0, 0.001], "tau_MPa": [0.0, 1.0]}, "pushout", "example")
    fig.canvas.draw()


def draw(csv_path, png, kind, title):
    fig = Figure(figsize=(6, 4), dpi=120)
    FigureCanvasAgg(fig)
    title = title or os.path.basename(os.path.dirname(os.path.abspath(csv_path)))
    if kind == "crack_pattern":
        # The crack planes of the run and its resolved scene (the slice's
        # outline), beside its crack_pattern.csv.
        folder = os.path.dirname(os.path.abspath(csv_path))
        planes = os.path.join(folder, "crack_planes.csv")
        plot_crack_pattern(fig, read_kind(csv_path, kind), title,
                           read(planes) if os.path.exists(planes) else None,
                           read_scene(os.path.join(folder, "scene.toml")))
    else:
        plot(fig, read_kind(csv_path, kind), kind, title)
    try:
        fig.savefig(png)
    except OSError as e:
        raise PlotError(f"cannot write {png}: {e.strerror}") from None
    except ValueError as e:  # a format matplotlib does not write (".txt")
        raise PlotError(f"cannot write {png}: {e}") from None


def read_scene(path):
    """The slice of a run's resolved scene.toml that the crack pattern draws:
    {"shape", "width", "center", "tube_outer", "tube_inner", "radius"} [mm];
    None without the file (or a scene of another model)."""
    if not os.path.exists(path):
        return None
    import tomllib
    try:
        with open(path, "rb") as f:
            scene = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise PlotError(f"cannot read the scene beside the crack pattern, {path}: {e}") from None
    g, c = scene.get("geometry", {}), scene.get("cracking", {})
    if "width" not in g or "tube_outer_diameter" not in g:
        return None
    shape = g.get("outer_shape", "square")
    # A circle slice is centred on the tube (the scene refuses another centre).
    center = g.get("tube_center", [g["width"] / 2] * 2) if shape == "square" else [g["width"] / 2] * 2
    return {"shape": shape, "width": g["width"], "center": center,
            "tube_outer": g["tube_outer_diameter"], "tube_inner": g.get("tube_inner_diameter", 0.0),
            "radius": c.get("radius", 0.0)}


def cell_outlines(data):
    """Each column's cell of crack_pattern.csv as its four corners [mm]."""
    return [[(data[f"corner_{k}_x_mm"][i], data[f"corner_{k}_y_mm"][i]) for k in range(4)]
            for i in range(len(data.get("x_mm", [])))]


def slice_notes(data, slice_):
    """What the crack pattern's figure says under it of a part model's
    mirror images and of cracking.radius ("" for neither)."""
    if not slice_:
        return ""
    notes = []
    planes = mirrors(cell_outlines(data), slice_)
    if planes:
        notes.append(f"mirrored about the dashed symmetry plane{'s' if len(planes) > 1 else ''} "
                     "(the model is a part of the slice)")
    if slice_["radius"] > 0:
        notes.append(f"pale: linear beyond cracking.radius = {slice_['radius']:g} mm")
    return "; ".join(notes)


def mirrors(outlines, slice_):
    """The symmetry planes a part model's cells lie on one side of: "x"
    (x = xc, cells at x >= xc) and/or "y", where the slice spans both sides
    (a half or quarter model: its cells are drawn with their mirror images,
    as the readings count the specimen's cracks)."""
    if not outlines or not slice_:
        return []
    tol = 1e-6 * slice_["width"]
    xc, yc = slice_["center"]
    found = []
    for axis, c in ((0, xc), (1, yc)):
        if 0 < c < slice_["width"] and all(p[axis] >= c - tol for o in outlines for p in o):
            found.append("xy"[axis])
    return found


def draw_crack_pattern(ax, data, top=None, planes=None, slice_=None):
    """The slice seen along the tube axis on `ax`: each column its cell's
    outline, coloured by its opening on a log scale from 1 um (below: the
    lightest colour) to `top` [mm] (default: the widest); `planes`
    (crack_planes.csv's columns): each crack plane a line from the tube to
    the outer face, coloured by its mouth opening on the same scale and
    labelled with it. With `slice_` (read_scene): the slice's outline, the
    concrete that may not crack (cracking.radius) in its own colour, the
    tube, and a half or quarter model's cells with their mirror images
    (the symmetry planes dashed). Returns the coloured collection (for a
    colour bar)."""
    from matplotlib.collections import PatchCollection
    from matplotlib.colors import LogNorm
    from matplotlib.patches import Circle, Polygon, Rectangle
    floor = 1e-3  # mm
    xs = data.get("x_mm", [])
    opening = data.get("opening_mm", [])
    mouths = (planes or {}).get("mouth_mm", [])
    top = top or max([floor * 10] + opening + mouths)
    outlines = cell_outlines(data)
    values = [max(w, floor) for w in opening]
    planes_of_symmetry = mirrors(outlines, slice_)
    for axis in planes_of_symmetry:
        c = slice_["center"]["xy".index(axis)]
        images = [[(2 * c - x, y) if axis == "x" else (x, 2 * c - y) for x, y in o] for o in outlines]
        outlines, values = outlines + images, values + values
    cells = PatchCollection([Polygon(o) for o in outlines], cmap="inferno_r",
                            norm=LogNorm(floor, top), linewidths=0, zorder=2)
    cells.set_array(values)
    if slice_:
        w, (xc, yc) = slice_["width"], slice_["center"]
        linear = {"fc": "#dce6f0", "ec": "none", "zorder": 1}  # concrete that stays linear
        edge = {"fc": "none", "ec": "black", "lw": 0.8, "zorder": 4}
        if slice_["shape"] == "circle":
            ax.add_patch(Circle((xc, yc), w / 2, **linear))
            ax.add_patch(Circle((xc, yc), w / 2, **edge))
        else:
            ax.add_patch(Rectangle((0, 0), w, w, **linear))
            ax.add_patch(Rectangle((0, 0), w, w, **edge))
        ax.add_patch(Circle((xc, yc), slice_["tube_outer"] / 2, fc="0.6", ec="black", lw=0.6,
                            zorder=3))
        ax.add_patch(Circle((xc, yc), slice_["tube_inner"] / 2, fc="white", ec="black", lw=0.6,
                            zorder=3))
        for axis in planes_of_symmetry:
            if axis == "x":
                ax.plot([xc, xc], [0, w], color="0.3", lw=0.7, ls="--", zorder=2.5)
            else:
                ax.plot([0, w], [yc, yc], color="0.3", lw=0.7, ls="--", zorder=2.5)
        ax.set_xlim(-0.02 * w, 1.02 * w)
        ax.set_ylim(-0.02 * w, 1.02 * w)
        ax.set_facecolor("white")
    else:
        if xs:
            ax.set_xlim(min(p[0] for o in outlines for p in o), max(p[0] for o in outlines for p in o))
            ax.set_ylim(min(p[1] for o in outlines for p in o), max(p[1] for o in outlines for p in o))
        ax.set_facecolor("0.85")  # where the concrete may not crack, and the tube
    ax.add_collection(cells)
    ax.set_aspect("equal")
    for i, w in enumerate(mouths):
        x = [planes["x_inner_mm"][i], planes["x_outer_mm"][i]]
        y = [planes["y_inner_mm"][i], planes["y_outer_mm"][i]]
        ax.plot(x, y, color=cells.cmap(cells.norm(max(w, floor))), lw=2.5, solid_capstyle="butt",
                zorder=5)
        ax.plot(x, y, color="C0", lw=0.6, ls="--", zorder=5)  # marks it a plane, however narrow
        at = (x[0] + 0.8 * (x[1] - x[0]), y[0] + 0.8 * (y[1] - y[0]))  # inside the slice
        ax.annotate(f"plane {int(planes['plane'][i])}: {w * 1e3:.3g} µm", at,
                    fontsize=7, color="C0", ha="center", va="center", zorder=6,
                    bbox={"boxstyle": "round,pad=0.2", "fc": "white", "alpha": 0.8, "lw": 0})
    return cells


def plot_crack_pattern(fig, data, title, planes=None, slice_=None):
    """The crack pattern of one run (draw_crack_pattern) with its colour bar."""
    ax = fig.add_subplot()
    cells = draw_crack_pattern(ax, data, planes=planes, slice_=slice_)
    notes = slice_notes(data, slice_)
    ax.set_xlabel("x [mm]" + (f"\n{notes}" if notes else ""), fontsize=None if not notes else 8)
    ax.set_ylabel("y [mm]")
    fig.colorbar(cells, ax=ax, label="crack opening, mean through the thickness [mm]"
                 + ("\n(planes: mouth opening)" if planes else ""))
    ax.set_title(f"crack pattern at the start of the push\n{title}", fontsize=10)
    fig.tight_layout()


def plot(fig, data, kind, title):
    """A curve of `kind` (the crack pattern: plot_crack_pattern)."""
    ax = fig.add_subplot()
    if kind == "pushout":
        ax.plot([d * 1e3 for d in data.get("delta_mm", [])], data.get("tau_MPa", []), "o-", ms=3)
        ax.set_xlabel("tube displacement $\\delta$ [µm]")
        ax.set_ylabel("nominal bond stress $\\tau$ [MPa]")
    elif kind == "corrosion":
        x_um = [x * 1e3 for x in data.get("penetration_mm", [])]
        ax.plot(x_um, data.get("p_MPa", []), "o-", ms=3, color="C0")
        ax.set_xlabel("corrosion depth $x$ [µm]")
        ax.set_ylabel("interface pressure $p$ [MPa]", color="C0")
        # The crack planes' mouths, and with cracks anywhere the widest
        # surface crack as a gauge reads it (of the planes' mouths too).
        widths = sorted(k for k in data if k.startswith("w_crack_"))
        concrete = "cracks_at_surface" in data
        if widths or concrete:
            ax2 = ax.twinx()
            for i, k in enumerate(widths):
                ax2.plot(x_um, [w * 1e3 for w in data[k]], "s-", ms=2, color=f"C{i + 1}",
                         label=f"crack plane {k[len('w_crack_'):-3]}")
            if concrete:
                ax2.plot(x_um, [w * 1e3 for w in data.get("crack_width_mm", [])],
                         "--" if widths else "s-", ms=2, color="0.2" if widths else "C1",
                         label="widest surface crack")
            ax2.set_ylabel("crack-mouth opening [µm]" if not concrete
                           else "surface crack width [µm]" if not widths else "crack width [µm]")
            ax2.legend(loc="upper left", fontsize=8)
    else:
        ax.plot(data.get("u_s_mm", []), data.get("F_s_N", []), "o-", ms=3)
        ax.set_xlabel("shear displacement $u_s$ [mm]")
        ax.set_ylabel("shear force $F_s$ [N]")
    if not any(data.get(k) for k in ("delta_mm", "penetration_mm", "u_s_mm")):
        # A run that failed before its first row: say so, not blank axes.
        ax.text(0.5, 0.65, "no converged step\n(summary.json: message)", ha="center",
                va="center", transform=ax.transAxes, color="0.3")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.grid(alpha=0.3)
    ax.set_title(title)
    fig.tight_layout()


if __name__ == "__main__":
    main()
