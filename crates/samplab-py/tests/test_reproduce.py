"""samplab.reproduce from Python: no terminal bar, progress through a callback, and a
callback's exception stops the run and is raised."""

import os

import pytest

import samplab


def test_progress_reaches_the_callback_and_nothing_the_terminal(tmp_path, capfd):
    seen = []
    claims = samplab.reproduce(str(tmp_path / "r"), only="sbert2006", progress=lambda *a: seen.append(a))
    out, err = capfd.readouterr()
    assert out == "" and err == ""
    assert claims and all(c["paper"] == "sbert2006" for c in claims)
    experiments = list(dict.fromkeys((p, e) for p, e, _, _ in seen))
    assert len(experiments) >= 2 and all(p == "sbert2006" for p, _ in experiments)
    for p, e in experiments:
        calls = [(done, total) for q, f, done, total in seen if (q, f) == (p, e)]
        assert calls[0] == (0, 0), (e, calls[0])
        # done never goes back, and the last call is the finish, done == total
        assert all(a[0] <= b[0] for a, b in zip(calls, calls[1:])), e
        assert calls[-1][0] == calls[-1][1], (e, calls[-1])
    assert os.path.isfile(tmp_path / "r" / "index.html")


def test_an_exception_in_the_callback_stops_the_run(tmp_path):
    def boom(paper, experiment, done, total):
        if done > 0:
            raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        samplab.reproduce(str(tmp_path / "r"), only="sbert2006", progress=boom)
    assert not os.path.exists(tmp_path / "r")
    with pytest.raises(samplab.Error, match="not callable"):
        samplab.reproduce(str(tmp_path / "r"), only="sbert2006", progress=3)
