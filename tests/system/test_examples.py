"""The example gallery (examples/*.py) runs and writes its figures.

Each script runs as a subprocess (the interpreter of this test run, cwd a temporary folder,
output to ``tmp_path``), with ``--quick`` where it has one; measured ~12 s for the whole file
on 2 cores. Figures are checked to exist and to be non-trivial PNG files (> 10 kB).
"""

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

CASES = {
    "paper_table_blast_loading.py": ([], ["table_blast_loading.png"], ["0.2332 mg", "14.2656 mg"]),
    "paper_figure_5_8_scaling_factors.py": (
        [],
        ["figure_5_scaling_factors_vs_lambda.png", "figure_8_scaling_factors_vs_gamma.png"],
        ["pressure 5.846 %", "gamma = 0.05: 0.189 %"],
    ),
    "paper_figures_6_7_rocking.py": (
        ["--quick"],
        [
            "figure_6_prototype_response.png",
            "figure_7_model_response.png",
            "figure_9_upscaled_gamma_1.png",
            "figure_10_upscaled_gamma_0p07.png",
        ],
        ["critical charge (Friedlander pulse): 79.87 kg", "outcomes agree: True"],
    ),
    "paper_fe_blocks_3d.py": (
        ["--quick"],
        ["figure_fe_slender_blocks.png", "figure_fe_non_slender_block.png"],
        ["2b = 3.50 m", "alpha = 19.3 deg"],
    ),
    "pi_diagram.py": (["--quick"], ["pi_diagram.png"], ["79.870 kg", "79.864 kg", "79.844 kg"]),
    "paper_columns_method_a.py": (  # --quick: a 3-drum column for 0.5 s (full length: docs/columns.md)
        ["--quick"],
        [
            "figure_column_square_250kg.png",
            "figure_column_circular_200kg.png",
            "figure_column_ensemble_circular_200kg.png",
        ],
        ["square 250 kg: prototype collapsed False", "ensemble circular 200 kg (2 runs, 1e-6)"],
    ),
}


def _run(script: str, args: list[str], cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, str(EXAMPLES / script), *args], cwd=cwd, capture_output=True, text=True, timeout=120
    )


@pytest.mark.parametrize("script", sorted(CASES))
def test_example_runs_and_writes_its_pngs(script, tmp_path):
    args, pngs, printed = CASES[script]
    out = tmp_path / "out"
    work = tmp_path / "cwd"
    work.mkdir()
    r = _run(script, [str(out), *args], work)
    assert r.returncode == 0, r.stderr[-3000:]
    for name in pngs:
        f = out / name
        assert f.is_file(), f"{script} did not write {name}: {sorted(p.name for p in out.iterdir())}"
        assert f.read_bytes()[:8] == PNG_MAGIC and f.stat().st_size > 10_000
    for text in printed:  # key numbers of docs/examples.md
        assert text in r.stdout, r.stdout
    assert not list(work.iterdir()), "an example wrote into the working folder although given an output folder"


def test_default_output_folder_is_results_examples(tmp_path):
    r = _run("paper_table_blast_loading.py", [], tmp_path)
    assert r.returncode == 0, r.stderr[-3000:]
    assert (tmp_path / "results" / "examples" / "table_blast_loading.png").is_file()
    assert (tmp_path / "results" / "examples" / "table_blast_loading.csv").is_file()


def test_every_example_is_tested_and_documented():
    scripts = {p.name for p in EXAMPLES.glob("*.py") if not p.name.startswith("_")}
    assert scripts == set(CASES)
    gallery = (EXAMPLES.parent / "docs" / "examples.md").read_text()
    for s in scripts:
        doc = (EXAMPLES / s).read_text().split('"""')[1]
        assert "Run time" in doc and "What to look for" in doc and "Usage" in doc, s
        assert f"examples/{s}" in gallery, s


def test_help_documents_quick():
    r = _run("paper_fe_blocks_3d.py", ["--help"], EXAMPLES)
    assert r.returncode == 0 and "--quick" in r.stdout and "--alpha35" in r.stdout


@pytest.mark.parametrize("script", ["paper_fe_blocks_3d.py", "paper_columns_method_a.py"])
def test_3d_examples_go_through_the_study(script):
    """The 3D examples build scenarios and run the Study (one way in): no engine or comparison
    function is called directly."""
    text = (EXAMPLES / script).read_text()
    assert "from blastscale.study import Study" in text and "Scenario.from_dict(" in text
    for name in ("compare_structure3d(", "ensemble_compare(", "run_system(", "design_model(", "simulate_structure("):
        assert name not in text, (script, name)
