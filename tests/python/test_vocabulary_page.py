"""docs/vocabulary.md is what scripts/docs/vocabulary.py generates from the command line's
options and the Python signatures: the table cannot drift from the two sides."""

import os
import pathlib
import subprocess
import sys

from conftest import SOURCE_DIR, skip_or_fail_in_ci


def test_the_vocabulary_page_is_generated_from_both_sides():
    cli = os.environ.get("NOCDYN_CLI")
    if not cli or not os.path.exists(cli):
        skip_or_fail_in_ci("NOCDYN_CLI does not name the built nocdyn binary (ctest sets it)")
    script = pathlib.Path(SOURCE_DIR) / "scripts" / "docs" / "vocabulary.py"
    generated = subprocess.run([sys.executable, str(script), cli], check=True, capture_output=True, text=True,
                               timeout=120).stdout
    committed = (pathlib.Path(SOURCE_DIR) / "docs" / "vocabulary.md").read_text(encoding="utf-8")
    assert "| `--rate` | `rate` | 10000 |" in generated
    assert generated == committed, (
        "docs/vocabulary.md is stale: PYTHONPATH=build/python python3 scripts/docs/vocabulary.py build/nocdyn "
        "> docs/vocabulary.md")
