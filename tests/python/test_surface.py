"""The Python functions stand on the typed application layer, not on the command line: two
threads run two commands at once, another thread's prints are its own, a progress callback may
call nocdyn, Ctrl-C (a KeyboardInterrupt) stops a call, and the process's signal handlers and
locale are as they were after every call."""

import io
import locale
import signal
import threading
import time
import contextlib

import numpy as np
import pytest

import nocdyn


def test_two_threads_run_two_commands_at_once():
    # each call reports its progress from its own thread; with nothing shared and the GIL
    # released, the two calls' reports interleave: the second runs while the first is running
    # (a lock around commands would put all of one call's reports before the other's). Bit for
    # bit the answer of one call alone.
    reference = nocdyn.inverse_dynamics("paper1", duration=2.0, rate=100000.0, progress=False)
    reports = []
    results = [None, None]

    def run(k):
        def progress(done, total):
            reports.append(k)
            time.sleep(0.002)  # let the other thread's command run

        results[k] = nocdyn.inverse_dynamics("paper1", duration=2.0, rate=100000.0, progress=progress)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        np.testing.assert_array_equal(r.data, reference.data)
    first = [i for i, k in enumerate(reports) if k == 0]
    second = [i for i, k in enumerate(reports) if k == 1]
    assert first and second
    assert any(first[0] < i < first[-1] for i in second) or any(second[0] < i < second[-1] for i in first), reports


def test_another_threads_prints_are_neither_captured_nor_breaking(capsys):
    stop = threading.Event()

    def chatter():
        while not stop.is_set():
            print("chatter", flush=True)
            time.sleep(0.001)

    thread = threading.Thread(target=chatter)
    thread.start()
    try:
        report = nocdyn.pose(0.001, -0.002, 0.01)
        table = nocdyn.inverse_dynamics("paper1", duration=0.05, rate=2000.0, progress=False)
    finally:
        stop.set()
        thread.join()
    assert report.cond_A > 1.0 and len(table) == 100
    assert not hasattr(report, "text") or "chatter" not in report.text
    assert "chatter" not in table.text
    assert "chatter" in capsys.readouterr().out  # printed where the thread printed it


def test_a_progress_callback_may_call_nocdyn():
    seen = []

    def progress(done, total):
        seen.append(nocdyn.pose(0.0, 0.0, 0.0).cond_A)  # reentrant: no lock held

    nocdyn.inverse_dynamics("paper1", duration=0.2, rate=50000.0, progress=progress)
    assert seen and all(c > 1.0 for c in seen)


def test_a_keyboard_interrupt_from_progress_stops_the_call():
    calls = []

    def progress(done, total):
        calls.append(done)
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        nocdyn.inverse_dynamics("paper1", duration=10.0, rate=100000.0, progress=progress)
    assert len(calls) == 1  # stopped at the first report, not after 1e6 samples


def test_signal_handlers_and_locale_are_as_before_after_every_call():
    handlers = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    numeric = locale.setlocale(locale.LC_NUMERIC)
    nocdyn.pose(0.0, 0.0, 0.0)
    nocdyn.inverse_dynamics("paper1", duration=0.01, progress=False)
    with contextlib.redirect_stdout(io.StringIO()):
        assert nocdyn.commands.main(["nocdyn", "pose", "0", "0", "0", "--json"]) == 0
    assert {s: signal.getsignal(s) for s in handlers} == handlers
    assert locale.setlocale(locale.LC_NUMERIC) == numeric


def test_a_value_that_starts_with_two_dashes_stays_a_value():
    # on a command line "--robot" would be an option; here it is the trajectory's file name
    with pytest.raises(nocdyn.Error, match="--robot"):
        nocdyn.inverse_dynamics("--robot", duration=0.01)


def test_a_bad_value_names_the_python_argument():
    with pytest.raises(ValueError, match="^rate: "):
        nocdyn.inverse_dynamics("paper1", rate=0.5)
    with pytest.raises(ValueError, match="^duration: "):
        nocdyn.inverse_dynamics("paper1", duration=float("nan"))
    with pytest.raises(ValueError, match="allow_limits"):
        nocdyn.inverse_dynamics("paper1", allow_limits="yes")
    with pytest.raises(TypeError):
        nocdyn.inverse_dynamics("paper1", rates=1000.0)  # a typo is named by Python
