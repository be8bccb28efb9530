"""What the bench scripts share: running build/pushout on a scene and reading
its outputs (scripts/pushout_runs.py), writing result tables."""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import pushout_runs  # noqa: E402
from pushout_runs import PUSHOUT, ROOT, write_csv  # noqa: E402

# The benches read outputs through these.
curve, summary = pushout_runs.curve, pushout_runs.summary


def run(pushout, scene, out, sets=(), petsc=(), reuse=False, timeout=None, check=True,
        mpirun=None, stop_after=None):
    """Runs a scene (one thread per process, quiet; `mpirun`: on that many
    processes) unless `reuse` and out/ holds a finished run (reused_run).
    Returns the exit code (0 when reused) or None if it ran out of
    `timeout`; `stop_after`: seconds after which the run is stopped as by
    Ctrl-C (its summary.json written, interrupted; pushout_runs.run)."""
    if reuse and reused_run(out, stop_after):
        return 0
    p = pushout_runs.run(pushout, scene, out, sets, petsc, one_thread=True, timeout=timeout,
                         check=check, mpirun=mpirun, stop_after=stop_after)
    return None if p is None else p.returncode


def reused_run(out, stop_after=None):
    """Whether --reuse keeps the run in out/: it has a summary and was not
    interrupted, or was interrupted by the bench's own `stop_after` (it ran
    that long). A run stopped by hand (Ctrl-C, a kill) runs again: its rows
    end wherever it was stopped, not where the bench asked."""
    try:
        s = summary(out)
    except (OSError, ValueError):
        return False
    if not s.get("interrupted", False):
        return True
    return stop_after is not None and s.get("wall_s", 0.0) >= 0.99 * stop_after


def save_figure_and_table(fig, out_dir, name, rows):
    """Writes out_dir/NAME.png (the figure, laid out) and NAME.csv (the rows)."""
    fig.tight_layout()
    os.makedirs(out_dir, exist_ok=True)
    fig.savefig(os.path.join(out_dir, name + ".png"))
    write_csv(os.path.join(out_dir, name + ".csv"), rows)


def ran_utc(out):
    """When the run in out/ was made (its summary.json's time, UTC): with
    --reuse an earlier run, of an earlier build, may stand beside today's."""
    return time.strftime("%Y-%m-%d %H:%M",
                         time.gmtime(os.path.getmtime(os.path.join(out, "summary.json"))))


def markdown_table(header, rows):
    """A markdown table: header names, then one line per row (its values)."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(v) for v in r.values()) + " |" for r in rows]
    return "\n".join(lines) + "\n"


def arguments(doc, out_folder, repeat=False, studies=None, options=()):
    """The options of a bench that runs cases into results/OUT_FOLDER:
    --pushout, --out, --reuse (keep the finished runs: reused_run) and --only
    (the cases to run), with `repeat` --repeat N (rounds of the timed
    cases), with `studies` --study (one of them, the first by default), and
    the bench's own `options` ((flag, argparse keywords) pairs); `doc` is the
    script's docstring (its --help)."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pushout", default=PUSHOUT)
    ap.add_argument("--out", default=os.path.join(ROOT, "results", out_folder),
                    help="the folder of the runs; the tables go to bench/results")
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--only", nargs="*", default=None)
    if repeat:
        ap.add_argument("--repeat", type=int, default=1, metavar="N")
    if studies:
        ap.add_argument("--study", choices=studies, default=studies[0])
    for flag, keywords in options:
        ap.add_argument(flag, **keywords)
    args = ap.parse_args()
    if repeat and args.repeat < 1:
        ap.error(f"--repeat must be at least 1, not {args.repeat}")
    return args


def check_only(args, known):
    """Exits 2 if --only names a case not among `known` (a typo ran nothing
    and wrote an empty table over the committed one)."""
    unknown = [c for c in (args.only or []) if c not in known]
    if unknown:
        print(f"{os.path.basename(sys.argv[0])}: --only {' '.join(unknown)}: no such case "
              f"(the cases: {', '.join(known)})", file=sys.stderr)
        raise SystemExit(2)
