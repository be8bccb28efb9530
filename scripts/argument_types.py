"""argparse types shared by the scripts and the benches: a value refused in
one line (argparse's usage error), not a traceback."""
import argparse


def positive_int(text):
    """An argparse type: a whole number of at least 1 (--jobs)."""
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number of at least 1")
    return n


def mesh_size(text):
    """An argparse type: a mesh as PERxTHROUGH (elements per quarter of the
    interface x through the thickness, e.g. 16x8), kept as its text."""
    parts = text.split("x")
    if len(parts) != 2 or not all(p.isdigit() and int(p) > 0 for p in parts):
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a mesh as PERxTHROUGH (elements per quarter x through the "
            "thickness, e.g. 16x8)")
    return text
