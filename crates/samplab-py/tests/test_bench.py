"""The benchmark scripts' own arithmetic, on made-up inputs whose answers are known."""

import importlib.util

import pytest

from conftest import ROOT


def load(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "bench" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


scaling = load("scaling")


def trace(runs):
    """`perf script -F tid,time,ip,sym` lines: for each (tid, start ms, end ms, function),
    one sample a millisecond while the thread runs."""
    lines = []
    for tid, start, end, function in runs:
        for ms in range(start, end):
            lines.append(f"{tid} {ms / 1000 + 0.0005:.6f}: 5555 {function}")
    return "\n".join(sorted(lines, key=lambda line: float(line.split()[1].rstrip(":"))))


def test_a_serial_start_then_both_threads_is_amdahls_fraction():
    # 100 ms on one thread, then 200 ms on two: T1 = 100 + 400, f = 100 / 500
    text = trace([(1, 0, 100, "samplab::grid::build"), (1, 100, 300, "work"), (2, 100, 300, "work")])
    span, lone, serial, where = scaling.windows(text, 2)
    assert span == 75
    assert lone == 25
    assert serial == pytest.approx(0.2)
    assert where == [(1.0, "grid::build")]


def test_a_wait_counts_as_serial_and_a_third_thread_as_no_more_than_two():
    # 40 ms of both threads, 40 ms with no thread on a core (a wait), 40 ms of three
    # threads sharing two cores: T2 = 120 ms, T1 = 80 + 40 + 80 = 200, f = 2 * 120 / 200 - 1
    text = trace([(1, 0, 40, "a"), (2, 0, 40, "a"), (1, 80, 120, "b"), (2, 80, 120, "b"), (3, 80, 120, "b")])
    span, lone, serial, _ = scaling.windows(text, 2)
    assert span == 30
    assert lone == 0
    assert serial == pytest.approx(0.2)


def test_two_threads_busy_throughout_have_no_serial_part():
    _, lone, serial, where = scaling.windows(trace([(7, 0, 400, "x"), (8, 0, 400, "y")]), 2)
    assert (lone, serial, where) == (0, 0.0, [])


def test_a_short_row_gets_the_rounds_that_fill_its_seconds_and_a_long_one_k():
    assert scaling.rounds_for(1.5, 5, 30) == 20
    assert scaling.rounds_for(1.4, 5, 30) == 22
    assert scaling.rounds_for(200.0, 3, 30) == 3
    assert scaling.rounds_for(2.0, 3, 0) == 3


def test_the_spread_is_the_quartiles_of_each_rounds_own_speed_up():
    # speed-ups 1.6, 1.8, 2.0, 2.0, 2.2 (the two columns' medians alone would give 2.0)
    one = [1.6, 3.6, 2.0, 4.0, 2.2]
    two = [1.0, 2.0, 1.0, 2.0, 1.0]
    low, high = scaling.quartiles(one, two)
    assert (low, high) == (pytest.approx(1.8), pytest.approx(2.0))
    assert scaling.quartiles([3.0], [2.0]) == (1.5, 1.5)


def test_names_lose_their_crate_path_and_generic_arguments():
    assert scaling.short("samplab::sampler::blue_noise::poisson::bridson") == "poisson::bridson"
    assert scaling.short("<alloc::vec::Vec<T> as core::ops::Drop>::drop") == "drop"
    assert scaling.short("rayon::iter::plumbing::bridge_producer_consumer::helper::{{closure}}") == \
        "bridge_producer_consumer::helper"
    assert scaling.short("clear_page_erms") == "clear_page_erms"


def test_the_columns_default_to_powers_of_two_up_to_the_cores_and_threads_picks_others():
    assert scaling.thread_counts(None, 2) == [1, 2]
    assert scaling.thread_counts(None, 12) == [1, 2, 4, 8]
    assert scaling.thread_counts("16,1", 2) == [1, 16]
    for bad in ("2,4", "1,1", "1,x", "0,1", ""):
        assert scaling.thread_counts(bad, 16) is None


def test_amdahls_fraction_from_two_times_gives_back_the_law_it_inverts():
    # T_p = T_1 (f + (1 - f) / p) with f = 0.05: on 16 threads 10 s becomes 0.96875 s
    assert scaling.amdahl(10.0, 10.0 * (0.05 + 0.95 / 16), 16) == pytest.approx(0.05)
    assert scaling.amdahl(10.0, 5.0, 2) == pytest.approx(0.0)
    assert scaling.amdahl(10.0, 10.0, 8) == pytest.approx(1.0)


def test_windows_of_any_width_weigh_by_their_width():
    # 0.1 s of one thread, then 0.4 s of two: T1 = 0.1 + 0.8, T2 = 0.5, f = 2 * 0.5 / 0.9 - 1
    assert scaling.windowed_serial([(0.1, 1.0), (0.4, 2.0)], 2) == pytest.approx(1.0 / 9.0)
    # a wait (no thread busy) counts as one thread's time, more than p threads as p
    assert scaling.windowed_serial([(0.1, 0.0), (0.1, 3.0)], 2) == pytest.approx(2 * 0.2 / 0.3 - 1)


def test_cpu_times_between_samples_are_threads_busy():
    # two threads: one busy throughout, one started after the first sample and busy half the time
    samples = [(0.0, {"1": 0}), (0.01, {"1": 10_000_000, "2": 5_000_000}), (0.02, {"1": 20_000_000, "2": 5_000_000})]
    windows = scaling.busy_between(samples)
    assert [w for w, _ in windows] == [pytest.approx(0.01), pytest.approx(0.01)]
    assert [b for _, b in windows] == [pytest.approx(1.5), pytest.approx(1.0)]


def test_cpu_times_of_this_process_grow_with_work():
    import os

    before = scaling.cpu_times(os.getpid())
    sum(i * i for i in range(200_000))
    after = scaling.cpu_times(os.getpid())
    assert before and sum(after.values()) > sum(before.values())


def test_the_strip_spreads_each_windows_work_over_the_stretches_it_overlaps():
    # 1 s of one thread then 1 s of sixteen, in windows that straddle the stretches' edges
    windows = [(0.3, 1.0)] * 3 + [(0.1, 1.0), (0.1, 16.0)] + [(0.3, 16.0)] * 3
    assert scaling.strip(windows, 4) == "11gg"
    assert scaling.strip([(1.0, 4.0)], 3) == "444"
