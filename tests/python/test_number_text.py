"""Numbers as text do not follow the process's C locale: under a decimal-comma locale (set by
Python's locale.setlocale, as a notebook might) every summary nocdyn writes is byte for byte
the one it writes under "C" (nocdyn/text.hpp: one formatter, in the "C" locale per thread)."""

import locale
import os
import shutil
import subprocess

import pytest

import nocdyn
from conftest import skip_or_fail_in_ci


@pytest.fixture
def decimal_comma(tmp_path):
    """Builds de_DE.UTF-8 into a private folder (Debian's `locales` sources), selects it for
    LC_NUMERIC while the test runs, and restores the locale and LOCPATH after it."""
    localedef = shutil.which("localedef")
    if localedef is None or not os.path.isfile("/usr/share/i18n/locales/de_DE"):
        skip_or_fail_in_ci("localedef or the de_DE locale source is missing (Debian package `locales`)")
    subprocess.run([localedef, "-i", "de_DE", "-f", "UTF-8", str(tmp_path / "de_DE.UTF-8")], check=True,
                   capture_output=True, timeout=120)
    previous_path = os.environ.get("LOCPATH")
    previous = locale.setlocale(locale.LC_NUMERIC)
    os.environ["LOCPATH"] = str(tmp_path)
    try:
        locale.setlocale(locale.LC_NUMERIC, "de_DE.UTF-8")
        assert locale.localeconv()["decimal_point"] == ","
        yield
    finally:
        locale.setlocale(locale.LC_NUMERIC, previous)
        if previous_path is None:
            os.environ.pop("LOCPATH", None)
        else:
            os.environ["LOCPATH"] = previous_path


def summaries():
    plant = nocdyn.frequency_response(pose=[0.002, -0.001, 0.01], min_frequency=1.5, max_frequency=250.0, points=7)
    loop = nocdyn.frequency_response(closed_loop=True, min_frequency=0.5, max_frequency=200.0, points=7)
    return {"plant": plant.text, "closed loop": loop.text}


def test_summaries_keep_a_decimal_point_under_a_decimal_comma_locale(decimal_comma):
    under_comma = summaries()
    locale.setlocale(locale.LC_NUMERIC, "C")
    under_c = summaries()
    for name, text in under_c.items():
        assert "." in text, name
        assert under_comma[name] == text, name
