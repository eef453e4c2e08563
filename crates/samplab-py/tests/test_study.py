"""Studies on a Dask cluster: the same bytes as a local run and as the CLI, whatever the
chunking; a killed worker changes nothing; a stopped study resumes from its checkpoint and
computes only what is missing; bad checkpoint files are refused."""

import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import samplab
from samplab import Study

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    """Two worker processes, one thread each (rayon uses one thread per worker too); the
    scheduler's and the workers' scratch space in pytest's temporary folders, not
    /tmp/dask-scratch-space."""
    import dask

    scratch = str(tmp_path_factory.mktemp("dask"))
    with dask.config.set({"temporary-directory": scratch}):
        cluster = distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            env={"RAYON_NUM_THREADS": "1"},
        )
        with distributed.Client(cluster) as c:
            yield c
        cluster.close()


def test_integration_study_local_dask_and_cli_agree(client, cli):
    args = dict(sets=6, instances=3, seed=2)
    study = Study.integrate(["random", "jitter"], "quad", [16, 64], units_per_chunk=1, **args)
    local = study.run(progress=False)
    on_dask = study.run(client, progress=False)
    coarse = Study.integrate(["random", "jitter"], "quad", [16, 64], units_per_chunk=5, **args).run(client, progress=False)
    theirs = json.loads(
        cli("integrate", "--sampler", "random", "--sampler", "jitter", "--integrand", "quad", "-n", "16,64",
            "--sets", 6, "--instances", 3, "--seed", 2, "--json")
    )
    assert local.data == theirs
    assert on_dask.to_json() == local.to_json() == coarse.to_json()
    assert (local.computed, on_dask.computed, coarse.computed) == (12, 12, 3)


def test_spectrum_study_local_dask_and_cli_agree(client, cli, tmp_path):
    # 83 sets: 6 blocks of 16, a merge tree with a lone node on its right edge
    kw = dict(sets=83, res=16, seed=8)
    local = Study.spectrum("jitter.gaussian:sigma=0.25", 64, sets_per_chunk=16, **kw).run(progress=False)
    on_dask = Study.spectrum("jitter.gaussian:sigma=0.25", 64, sets_per_chunk=32, **kw).run(client, progress=False)
    cli("spectrum", "--sampler", "jitter.gaussian:sigma=0.25", "-n", 64, "--sets", 83, "--res", 16, "--seed", 8,
        "-o", tmp_path / "s")
    theirs = json.loads((tmp_path / "s" / "spectrum.json").read_text())["statistics"]
    assert json.loads(local.to_json()) == theirs
    assert local.to_csv() == (tmp_path / "s" / "radial.csv").read_text()
    assert on_dask.to_json() == local.to_json()
    in_memory = samplab.spectrum(samplab.generate("jitter.gaussian:sigma=0.25", n=64, sets=83, seed=8), res=16)
    for name, values in in_memory.items():
        assert np.array_equal(values, local.data[name], equal_nan=True), name


def test_discrepancy_study_local_dask_and_cli_agree(client, cli):
    kw = dict(sets=250, seed=3)
    local = Study.discrepancy(["star", "l2-star", "centered"], "nrooks", 16, sets_per_chunk=100, **kw).run(progress=False)
    on_dask = Study.discrepancy(["star", "l2-star", "centered"], "nrooks", 16, sets_per_chunk=7, **kw).run(client, progress=False)
    theirs = json.loads(cli("discrepancy", "star", "l2-star", "centered", "--sampler", "nrooks", "-n", 16,
                            "--sets", 250, "--seed", 3, "--json"))
    assert local.data == theirs
    assert on_dask.to_json() == local.to_json()
    # a sampler named by an alias is written as the CLI writes it (its canonical spec)
    alias = Study.discrepancy("star", "LHCube", 16, sets=20, seed=3).run(progress=False)
    theirs = json.loads(cli("discrepancy", "star", "--sampler", "LHCube", "-n", 16, "--sets", 20, "--seed", 3, "--json"))
    assert alias.data == theirs and alias.data["source"].startswith("nrooks ")
    # and checking the arguments generates nothing: a CCVT of 10^6 points is not optimized here
    Study.discrepancy("star", "ccvt", 10**6, sets=1)


def test_render_study_local_dask_and_cli_agree(client, cli, tmp_path):
    settings = dict(sampler="jitter", n=4, res=(32, 24))
    study = Study.render("spheres", [5, 6, 7], reference_samples=64, seeds_per_chunk=2, **settings)
    local = study.run(progress=False)
    on_dask = study.run(client, progress=False)
    assert on_dask.to_json() == local.to_json()
    # the study's reference is rendered for its settings (the default seed), as the CLI's
    # first run writes one; the later runs compare with that file
    cli("render", "spheres", "--sampler", "jitter", "-n", 4, "--res", "32x24", "--reference", tmp_path / "ref.exr",
        "--reference-samples", 64, "-o", tmp_path / "first.exr")
    for seed, errors in zip([5, 6, 7], local.data["errors"]):
        out = json.loads(cli("render", "spheres", "--sampler", "jitter", "-n", 4, "--res", "32x24", "--seed", seed,
                             "--reference", tmp_path / "ref.exr", "--reference-samples", 64, "--json",
                             "-o", tmp_path / "img.exr"))
        assert out["errors"] == errors


def first_chunk_kept(box, running):
    """Wait until the checkpoint folder ``box`` holds a finished chunk, while ``running()``
    says the study goes on; the chunks kept by then (most are still to compute)."""
    while True:
        kept = [f for f in box.iterdir() if f.suffix == ".chunk"] if box.is_dir() else []
        if kept:
            return len(kept)
        assert running(), "the study ended before a chunk was kept"
        time.sleep(0.005)


# About 2 s of work in 24 chunks: the interruptions below land once the first chunk is
# kept, with 23 left to compute however fast the machine (they waited 1-1.5 s of a 5 s
# study before).
SHORT = "Study.integrate(['random', 'jitter'], 'disk', [1024, 4096], sets=8000, instances=6, seed={})"


def test_a_killed_worker_does_not_change_the_result(client, tmp_path):
    study = eval(SHORT.format(5))
    assert len(study.chunks) == 24
    expected = study.run(progress=False)
    pids = client.run(os.getpid)
    box = tmp_path / "checkpoint"
    finished = threading.Event()
    killed = []

    def kill_one():
        kept = first_chunk_kept(box, lambda: not finished.is_set())
        os.kill(next(iter(pids.values())), signal.SIGKILL)
        killed.append(kept)

    killer = threading.Thread(target=kill_one, daemon=True)
    killer.start()
    try:
        result = study.run(client, checkpoint=str(box), progress=False)
    finally:
        finished.set()
    killer.join()
    # the kill landed with chunks still to compute: work done, not seconds
    assert killed and killed[0] < len(study.chunks), f"killed after {killed} of {len(study.chunks)} chunks"
    assert result.to_json() == expected.to_json()
    client.wait_for_workers(2, timeout=60)


def test_a_stopped_study_resumes_computing_only_the_missing_chunks(tmp_path):
    box = tmp_path / "checkpoint"
    make = SHORT.format(9)
    script = textwrap.dedent(
        f"""
        import signal, samplab
        from samplab import Study
        # KeyboardInterrupt on SIGINT even if it was ignored when the tests began (as in
        # test_interrupt.py)
        signal.signal(signal.SIGINT, signal.default_int_handler)
        try:
            {make}.run(checkpoint={str(box)!r}, progress=False)
        except KeyboardInterrupt:
            print("stopped")
        """
    )
    run = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first_chunk_kept(box, lambda: run.poll() is None)
        run.send_signal(signal.SIGINT)
        out, err = run.communicate(timeout=120)
    finally:
        run.kill()
    assert out.strip() == "stopped", out + err
    study = eval(make)
    kept = [f for f in os.listdir(box) if f.endswith(".chunk")]
    assert 0 < len(kept) < len(study.chunks), f"{len(kept)} chunks kept: stop earlier or make the study longer"
    resumed = study.run(checkpoint=str(box), progress=False)
    assert (resumed.reused, resumed.computed) == (len(kept), len(study.chunks) - len(kept))
    assert resumed.to_json() == study.run(progress=False).to_json()
    # a third run computes nothing
    again = study.run(checkpoint=str(box), progress=False)
    assert (again.reused, again.computed) == (len(study.chunks), 0)
    assert again.to_json() == resumed.to_json()


def test_corrupted_and_foreign_checkpoint_files_are_refused(tmp_path):
    study = Study.discrepancy(["star"], "jitter", 16, sets=40, seed=1, sets_per_chunk=10)
    box = tmp_path / "a"
    study.run(checkpoint=str(box), progress=False)
    files = sorted(f for f in os.listdir(box) if f.endswith(".chunk"))
    assert len(files) == 4
    # one flipped byte
    path = box / files[1]
    raw = bytearray(path.read_bytes())
    raw[len(raw) // 2] ^= 1
    path.write_bytes(bytes(raw))
    with pytest.raises(samplab.Error, match="corrupted"):
        study.run(checkpoint=str(box), progress=False)
    # a chunk of another study under this study's name
    other = Study.discrepancy(["star"], "jitter", 16, sets=40, seed=2, sets_per_chunk=10)
    other_box = tmp_path / "b"
    other.run(checkpoint=str(other_box), progress=False)
    theirs = sorted(f for f in os.listdir(other_box) if f.endswith(".chunk"))[1]
    path.write_bytes((other_box / theirs).read_bytes())
    with pytest.raises(samplab.Error, match="another study"):
        study.run(checkpoint=str(box), progress=False)
    # another study's directory
    with pytest.raises(samplab.Error, match="holds another study"):
        other.run(checkpoint=str(box), progress=False)
    # truncated to nothing useful
    path.write_bytes(b"samplab")
    with pytest.raises(samplab.Error, match="not a samplab chunk"):
        study.run(checkpoint=str(box), progress=False)


def test_ranges_and_numpy_arrays_are_read_as_lists():
    # the guide's example gives a render study's seeds as range(64)
    plain = Study.render("spheres", [5, 6, 7], sampler="jitter", n=4)
    for seeds in (range(5, 8), np.arange(5, 8)):
        study = Study.render("spheres", seeds, sampler="jitter", n=4)
        assert (study.params, study.chunks, study.fingerprint) == (plain.params, plain.chunks, plain.fingerprint)
    with pytest.raises(samplab.Error, match="not a number, a name or a list"):
        Study.render("spheres", {5, 6, 7}, sampler="jitter", n=4)


def test_bad_studies_are_refused_before_any_work():
    with pytest.raises(samplab.Error, match="16 times a power of two"):
        Study.spectrum("jitter", 64, sets=100, res=16, sets_per_chunk=48)
    with pytest.raises(samplab.Error, match="9 and 16"):
        Study.spectrum("jitter", 15, sets=100, res=16)
    with pytest.raises(samplab.Error, match="res = 15: must be even and positive"):
        Study.spectrum("jitter", 16, sets=100, res=15)
    with pytest.raises(samplab.Error, match="sets"):
        Study.integrate(["random"], "quad", [16], sets=1)
    with pytest.raises(samplab.Error, match="did you mean"):
        Study.integrate(["randm"], "quad", [16])
    with pytest.raises(samplab.Error, match="unknown metric"):
        Study.discrepancy(["strr"], "jitter", 16, sets=4)
    with pytest.raises(samplab.Error, match="units_per_chunk"):
        Study.integrate(["random"], "quad", [16], units_per_chunk=0)


def test_the_readme_example_runs(tmp_path):
    example = os.path.join(os.path.dirname(__file__), "..", "examples", "study.py")
    out = tmp_path / "out"
    # its LocalCluster's scratch space in pytest's folder too (Dask's default is /tmp)
    env = dict(os.environ, DASK_TEMPORARY_DIRECTORY=str(tmp_path / "dask"))
    run = subprocess.run([sys.executable, example, str(out), "--quick"], capture_output=True, text=True, timeout=300,
                         env=env)
    assert run.returncode == 0, run.stderr[-2000:]
    assert sorted(os.listdir(out)) == ["fig6.ckpt", "fig6.csv", "fig6.png"]


def test_constructors_are_generated_from_the_library_kinds():
    """Each Study constructor's parameters, defaults and documentation are the library's
    declaration (samplab_render::study::KINDS): a signature for help(), Python's own
    TypeError for a missing or unknown argument."""
    import inspect

    kinds = samplab._samplab.study_kinds()
    assert [k["kind"] for k in kinds] == ["integrate", "spectrum", "discrepancy", "render"]
    for k in kinds:
        make = getattr(Study, k["kind"])
        names = list(inspect.signature(make).parameters)
        declared = [p["name"] for p in k["parameters"]] + [k["per_chunk"][0]] + ([k["rest"]] if k["rest"] else [])
        assert names == declared, k["kind"]
        assert make.__doc__ and make.__doc__.startswith(k["doc"].split("`")[0])
    with pytest.raises(TypeError):
        Study.spectrum("jitter", 64, res=16)  # sets is required
    with pytest.raises(TypeError):
        Study.integrate("random", "quad", 16, bogus=1)
    # defaults come from the declaration: 50 sets, 10 instances
    study = Study.integrate("random", "quad", 16, seed=1)
    assert (study.params["sets"], study.params["instances"]) == (50, 10)


def _gauss(x):
    return np.exp(-(x * x).sum(axis=1))


def test_an_integration_study_of_your_function_runs_on_dask(client, tmp_path):
    # exp(-|x|^2) over [0,1]^2, a module-level function (workers unpickle it by value or by
    # reference; a lambda works too, through cloudpickle)
    exact = 0.5577462853510336
    kw = dict(sets=6, seed=4, d=2, exact=exact)
    study = Study.integrate(["random", "sobol.owen"], _gauss, [16, 64], **kw)
    assert study.params["integrand"] == "_gauss" and study.params["instances"] == 1
    local = study.run(progress=False)
    on_dask = study.run(client, progress=False)
    lam = Study.integrate(["random", "sobol.owen"], lambda x: np.exp(-(x * x).sum(axis=1)), [16, 64], **kw)
    # the same rows as samplab.integrate with the callable (one path in the library)
    direct = samplab.integrate(["random", "sobol.owen"], _gauss, [16, 64], sets=6, seed=4, d=2, exact=exact)
    assert local.data == direct
    assert on_dask.to_json() == local.to_json()
    # written atomically by the library: the same text, and a bad folder is a FileError
    assert local.to_json(str(tmp_path / "rows.json")) == (tmp_path / "rows.json").read_text()
    with pytest.raises(samplab.FileError):
        local.to_csv(str(tmp_path / "missing" / "rows.csv"))
    assert [r["rmse"] for r in lam.run(client, progress=False).data["rows"]] == [r["rmse"] for r in direct["rows"]]
    # a checkpoint is tied to the function's code: another function does not reuse it
    study.run(checkpoint=str(tmp_path), progress=False)
    assert study.run(checkpoint=str(tmp_path), progress=False).reused == len(study.chunks)
    other = Study.integrate(["random", "sobol.owen"], lambda x: np.cos(x.sum(axis=1)), [16, 64], **kw)
    assert other.fingerprint != study.fingerprint
    with pytest.raises(samplab.Error, match="needs d="):
        Study.integrate("random", _gauss, 16, exact=exact)
    # without exact, the study computes it to a relative 1e-9 first
    computed = Study.integrate(["random", "sobol.owen"], _gauss, [16, 64], sets=6, seed=4, d=2)
    assert abs(computed.params["exact"] - exact) < 1e-9
    with pytest.raises(samplab.Error, match="a family takes neither"):
        Study.integrate("random", "quad", 16, d=2, exact=1.0)


def test_a_process_pool_or_any_executor_gives_the_same_bytes(tmp_path):
    """Any concurrent.futures executor runs a study: a process pool of spawned workers and a
    thread pool give the local run's bytes (a render study's reference computed first and
    handed to the other chunks), a checkpoint written on the pool is reused here, and an
    object that is neither a Dask client nor an executor is refused."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

    integrate = Study.integrate(["random", "jitter"], "quad", [16, 64], units_per_chunk=1, sets=6, instances=3, seed=2)
    render = Study.render("spheres", [5, 6, 7], reference_samples=64, seeds_per_chunk=2, sampler="jitter", n=4,
                          res=(32, 24))
    local = [s.run(progress=False).to_json() for s in (integrate, render)]
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        assert [s.run(pool, progress=False).to_json() for s in (integrate, render)] == local
        on_pool = integrate.run(pool, checkpoint=str(tmp_path), progress=False)
        assert on_pool.computed == len(integrate.chunks)
    again = integrate.run(checkpoint=str(tmp_path), progress=False)
    assert (again.reused, again.to_json()) == (len(integrate.chunks), local[0])
    with ThreadPoolExecutor(2) as pool:
        assert [s.run(pool, progress=False).to_json() for s in (integrate, render)] == local
    with pytest.raises(samplab.Error, match="neither a Dask client nor a concurrent.futures.Executor"):
        integrate.run(object(), progress=False)



# One small study of each kind the library declares (``samplab_render::study::KINDS``), as
# the arguments of its constructor and of the CLI's STUDY.json alike.
EVERY_KIND = {
    "integrate": dict(samplers=["random", "jitter"], integrand="quad", n=[16, 64], sets=6, instances=3, seed=2,
                      units_per_chunk=5),
    "spectrum": dict(sampler="jitter.gaussian:sigma=0.25", n=64, sets=40, res=16, seed=8, sets_per_chunk=16),
    "discrepancy": dict(metrics=["star", "l2-star"], sampler="nrooks", n=16, sets=30, seed=3, sets_per_chunk=7),
    "render": dict(scene="spheres", seeds=[5, 6, 7], reference_samples=64, seeds_per_chunk=2, sampler="jitter", n=4,
                   res=[32, 24]),
}


def test_every_kind_gives_one_process_bytes_on_a_pool_dask_and_the_job_array_cli(client, cli, tmp_path):
    """Each study kind of the library's one list, run in this process, on a spawned process
    pool, on Dask, and as a job array of separate `samplab study run` processes (chunks in
    reverse order, a render's chunk 0 first): the same bytes everywhere, and the CLI's
    merge prints exactly what `to_json` returns."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    from samplab import _samplab

    kinds = [k["kind"] for k in _samplab.study_kinds()]
    assert sorted(kinds) == sorted(EVERY_KIND), "a study kind without an example here"
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        for kind, arguments in EVERY_KIND.items():
            study = getattr(Study, kind)(**arguments)
            local = study.run(progress=False).to_json()
            assert study.run(pool, progress=False).to_json() == local, kind
            assert study.run(client, progress=False).to_json() == local, kind
            folder = tmp_path / kind
            folder.mkdir()
            (folder / "study.json").write_text(json.dumps({"kind": kind, **arguments}))
            cli("study", "plan", folder / "study.json", "-o", folder / "plan.json")
            order = list(reversed(range(len(study.chunks))))
            if kind == "render":
                order = [0] + order[:-1]
            for chunk in order:
                cli("study", "run", folder / "plan.json", "--chunk", chunk, "--dir", folder / "chunks")
            assert cli("study", "merge", folder / "plan.json", "--dir", folder / "chunks") == local, kind
