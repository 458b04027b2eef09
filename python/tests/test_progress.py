"""Long work: progress callbacks, stopping from the callback, timeouts, Ctrl-C, and
the GIL released while the library works."""

from __future__ import annotations

import _thread
import signal
import threading
import time

import pytest

import apart
from conftest import EXAMPLES, solution_set


@pytest.fixture(scope="module")
def tray():
    return apart.load(EXAMPLES / "tray-of-cubes")


def test_progress_callback_is_called_with_monotone_counts(tray):
    seen = []
    plan = tray.sequence(base="tray", progress=lambda *r: seen.append(r))
    assert plan.complete
    phases = [p for p, _, _ in seen]
    # The plan makes its pair regions as its steps need them, within its steps' phase.
    assert "sequence steps" in phases
    tray.partition(progress=lambda *r: seen.append(r))
    phases = [p for p, _, _ in seen]
    assert "pair regions" in phases
    last = {}
    for phase, done, total in seen:
        assert 0 <= done <= total
        assert done >= last.get(phase, 0)
        last[phase] = done
    # A phase that ran to its end reports done == total last.
    assert last["sequence steps"] == len(tray.parts) - 1


def test_loading_reports_progress():
    seen = set()
    apart.load(EXAMPLES / "ring-and-cone", progress=lambda p, d, t: seen.add(p))
    assert any(p.startswith("loading") for p in seen)


def test_stop_from_the_callback_gives_the_partial_plan(tray):
    full = tray.sequence(base="tray")

    def stop_after_two_steps(phase, done, total):
        if phase == "sequence steps" and done >= 2:
            raise apart.Stop

    part = tray.sequence(base="tray", progress=stop_after_two_steps)
    assert not part.complete and part.status == "stopped"
    assert part.stopped["by"] == "callback" and part.stopped["phase"] == "sequence steps"
    assert 2 <= len(part) < len(full) and part.not_yet_split
    # The steps found are the full plan's first steps.
    assert [(s.moving, s.exact_direction) for s in part] == [
        (s.moving, s.exact_direction) for s in full.steps[:len(part)]]


def test_stop_before_any_solution_gives_an_empty_partial_partition(tray):
    def stop(phase, done, total):
        raise apart.Stop

    p = tray.partition(progress=stop)
    assert not p.complete and p.status == "stopped" and not p.interlocked and len(p) == 0
    with pytest.raises(apart.StoppedError):
        tray.separate("tray", "lid", progress=stop)


def test_stop_during_the_solutions_keeps_valid_ones():
    asm = apart.load(EXAMPLES / "split-star")
    full = solution_set(asm.partition())

    def stop(phase, done, total):
        if phase in ("edges and vertices", "solution directions", "free regions") and done > 0:
            raise apart.Stop

    p = asm.partition(progress=stop)
    assert solution_set(p) <= full
    assert p.complete == (p.status == "done")


def test_other_exceptions_from_the_callback_propagate(tray):
    def broken(phase, done, total):
        raise ZeroDivisionError("in the callback")

    with pytest.raises(ZeroDivisionError):
        tray.partition(progress=broken)


def test_timeout_ends_with_the_partial_answer(tray):
    p = tray.partition(timeout=1e-6)
    assert p.status in ("timeout", "done")
    if p.status == "timeout":
        assert not p.complete and p.stopped["by"] == "timeout"
    with pytest.raises(apart.InputError):
        tray.partition(timeout=0)


@pytest.fixture
def python_handles_sigint():
    # A process started in the background by a shell (as CI may start the tests)
    # inherits SIGINT ignored, and then Python installs no handler and ignores a Ctrl-C:
    # the test installs Python's own handler, what an interactive session has.
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, old)


def test_ctrl_c_interrupts(tray, python_handles_sigint):
    # interrupt_main() is what a Ctrl-C does: it sets the signal the waiting thread checks.
    def ctrl_c(phase, done, total):
        _thread.interrupt_main()

    t = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        tray.partition(progress=ctrl_c)
    assert time.perf_counter() - t < 60
    # The assembly is still usable afterwards.
    assert not tray.partition(first=True).interlocked


def test_the_gil_is_released():
    asm = apart.load(EXAMPLES / "ring-and-cone")  # its partition takes a few tenths of a second
    ticks = []
    span = []
    done = threading.Event()

    def work():
        # The first report comes from inside the library's run, the answer at its end.
        first = []
        asm.partition(progress=lambda *r: first or first.append(time.perf_counter()))
        span.extend([first[0], time.perf_counter()])
        done.set()

    th = threading.Thread(target=work)
    th.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    th.join()
    start, end = span
    inside = [t for t in ticks if start < t < end]
    # The main thread kept running Python code while the library worked: ticks all
    # along the run (with the GIL held there would be none between the reports).
    assert end - start > 0.05
    assert len(inside) >= (end - start) / 0.01


def test_tqdm_bar(tray, capsys):
    pytest.importorskip("tqdm", reason="tqdm is not installed")
    plan = tray.sequence(base="tray", progress=True)
    assert plan.complete
    assert "sequence steps" in capsys.readouterr().err
