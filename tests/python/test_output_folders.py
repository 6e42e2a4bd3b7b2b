"""An output into a folder that does not exist (or under a file) is refused before the work, in
Python as on the command line (the one check, app/outputs.hpp), naming the argument and the path."""

import re

import pytest

import nocdyn


def test_an_output_into_a_missing_folder_is_refused_before_the_work(tmp_path):
    missing = tmp_path / "no-such-folder"
    calls = []
    refused = re.escape(f"output '{missing}/id.csv': the folder '{missing}' does not exist")
    with pytest.raises(ValueError, match=refused):
        # 20 s of trajectory at 10 kHz: refused before any sample (no progress reported)
        nocdyn.inverse_dynamics("paper1", duration=20.0, output=missing / "id.csv",
                                progress=lambda done, total: calls.append(done))
    assert calls == [] and not missing.exists()
    refused = re.escape(f"figure '{missing}/envelope.png': the folder '{missing}' does not exist")
    with pytest.raises(ValueError, match=refused):
        nocdyn.envelope(points=30, figure=missing / "envelope")
    assert not missing.exists()


def test_an_output_under_a_file_is_refused_naming_it(tmp_path):
    plain = tmp_path / "plain.txt"
    plain.write_text("a file\n")
    with pytest.raises(ValueError, match=re.escape(f"output '{plain}/loads.csv': '{plain}' is a file, not a folder")):
        nocdyn.loads("paper1", duration=0.005, rate=2000.0, output=plain / "loads.csv")
    assert plain.read_text() == "a file\n"

