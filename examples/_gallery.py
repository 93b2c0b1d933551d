"""Shared plumbing of the example gallery (not an example itself).

Every example takes an optional output folder (default ``./results/examples``) and, where it
has one, a ``--quick`` flag (fewer points / shorter runs, used by ``tests/test_examples.py``).
Figures are written as PNG with matplotlib's Agg backend (no display needed).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # before pyplot: files only, no window

import matplotlib.pyplot as plt  # noqa: E402

DEFAULT_OUT = Path("results") / "examples"


def parse_args(doc: str, quick_help: str | None = None, flags: dict[str, str] | None = None) -> argparse.Namespace:
    """``out`` (folder, created), ``quick`` when ``quick_help`` is given, and one boolean
    option per entry of ``flags`` (name -> help, e.g. ``{"alpha35": "..."}`` gives ``--alpha35``)."""
    p = argparse.ArgumentParser(
        description=doc.strip().splitlines()[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument(
        "out",
        nargs="?",
        type=Path,
        default=DEFAULT_OUT,
        help=f"output folder for the PNG files (default ./{DEFAULT_OUT})",
    )
    if quick_help:
        p.add_argument("--quick", action="store_true", help=quick_help)
    for name, text in (flags or {}).items():
        p.add_argument(f"--{name}", action="store_true", help=text)
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    args.started = time.perf_counter()
    return args


def save(fig, out: Path, name: str) -> Path:
    """Write ``fig`` to ``out/name`` (PNG, 130 dpi), close it and say where it went."""
    path = out / name
    fig.savefig(path, dpi=130)
    plt.close(fig)
    print(f"wrote {path}")
    return path


def done(args: argparse.Namespace) -> None:
    """Print the wall time of the example."""
    print(f"done in {time.perf_counter() - args.started:.1f} s")
