"""The study's result folder and its self-contained HTML report.

:func:`write_study` writes ``summary.json``, ``histories.nc`` (``histories.csv`` on request), one PNG per
figure, ``scenario.toml`` and ``report.html`` into a folder (the CLI gives it a temporary
folder that :func:`blastscale.io.results.output_folder` renames into place).
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable, Optional

from ..io.histories import write_histories_csv, write_netcdf
from ..io.results import provenance, with_legacy_keys, write_atomic, write_json
from .card import card_of
from .figures import FIGURES, render_figures
from .html import SECTIONS, render_report
from .markup import format_charge
from .motion import motion_section
from .slips import SLIPS, applicable_slips

__all__ = [
    "FIGURES",
    "SECTIONS",
    "SLIPS",
    "applicable_slips",
    "format_charge",
    "render_figures",
    "render_report",
    "summary_dict",
    "write_study",
    "UNITS",
]

#: Units of the summary (keys carry their unit; this says it once for readers of summary.json).
UNITS = {
    "convention": "every key ends with its unit: _m, _kg, _s, _rad, _rad_s, _m_s, _Pa, _Pa_s, _Ns, _kg_m3; "
    "ratios and counts are dimensionless",
    "model results": "up-scaled to prototype units (prototype = model / scaling factor)",
    "design.factors": "model / prototype [-]",
}


def write_study(
    result, folder, progress: Optional[Callable[[str], None]] = None, csv: bool = False, plan_html: Optional[str] = None
) -> list[str]:
    """Write every result file of a study into ``folder`` (which must exist).

    Parameters
    ----------
    result : blastscale.study.StudyResult
    folder : path
    progress : callable, optional
        ``progress(stage)`` before each file group.
    csv : bool
        Also write ``histories.csv``, the histories flat (large: a column's is 135-169 MB and takes
        longer to write than the simulation; ``histories.nc`` holds the same).
    plan_html : str, optional
        The plan's section (``blastscale plan --out``), placed before the test card.

    Returns
    -------
    list of str
        The file names written.
    """

    folder = Path(folder)
    tell = progress or (lambda stage: None)
    meta = provenance()
    tell("histories (NetCDF" + (", CSV)" if csv else ")"))
    tree = result.to_datatree()
    write_netcdf(tree, folder / "histories.nc")
    if csv:
        write_histories_csv(tree, folder / "histories.csv")
    motion = motion_section(result, tree)
    tell("figures")
    figures = render_figures(result)
    for f, png in figures:
        write_atomic(folder / f"{f.name}.png", png)
    write_atomic(folder / "scenario.toml", result.scenario.to_toml(folder))  # a source beside it: relative
    files = (
        ["summary.json", "histories.nc"]
        + (["histories.csv"] if csv else [])
        + ["scenario.toml"]
        + [f"{f.name}.png" for f, _ in figures]
    )
    tell("report")
    write_atomic(
        folder / "report.html", render_report(result, figures, meta, files, plan_html=plan_html, motion=motion)
    )
    write_json(folder / "summary.json", summary_dict(result, meta))
    return ["report.html"] + files


def summary_dict(result, meta: Optional[dict] = None) -> dict:
    """The content of ``summary.json``: provenance (versions, git commit, timestamp), units, the
    study's nested summary (scenario included, and its ``verdict``: :func:`blastscale.study.criterion.judge`),
    its flat ``scalars`` and, with a ``[lab]``
    table, the ``test_card`` (:func:`blastscale.planning.study_test_card`), each renamed key with its
    deprecated name beside it (:func:`blastscale.io.results.with_legacy_keys`)."""

    s = result.summary()
    card = card_of(result)
    extra = {} if card is None else {"test_card": card}
    return with_legacy_keys(
        {
            **(provenance() if meta is None else meta),
            "units": UNITS,
            **s,
            "scalars": result.scalars(),
            **extra,
        }
    )
