"""Ctrl-C stops a long call promptly: KeyboardInterrupt is raised, no result is returned
and no output file is written. Each case runs in a child interpreter that sends SIGINT to
itself while the call runs (as a terminal's Ctrl-C does)."""

import os
import subprocess
import sys
import textwrap

import pytest

CASES = {
    "render": "samplab.render('spheres', spp=4096)",
    "spectrum": "samplab.spectrum(samplab.generate('jitter', n=4096, sets=400), res=256, direct=True)",
    "integrate": "samplab.integrate(['random', 'jitter'], 'disk', n=[65536], sets=100000)",
    "generate": "samplab.generate('poisson', n=4096, sets=100000)",
    # one set whose making used to ignore the stop: each stops within its own loop now
    "force-matrix": "samplab.generate('force-matrix', n=100000)",
    "dart-throwing": "samplab.generate('poisson', n=3000000)",
    "maximal-poisson": "samplab.generate('poisson.maximal', n=300000)",
    # a small set whose making is long: 2048 values, which alone once decided that the
    # call ran unwatched (then finished after minutes, or raised a PanicException)
    "lloyd-small": "samplab.generate('lloyd:iterations=100000', n=1024)",
    "reproduce": "samplab.reproduce(out, full=True)",
    # one set's exact discrepancy (the branch and bound's worst case: more than 30 s whole),
    # stopped within the computation
    "extreme-discrepancy": "samplab.discrepancy('extreme', samplab.generate('hammersley', n=8192))",
    # the optimized pixel sampler's preparation (29 s whole), then its values
    "heitz2019": "samplab.pixels('heitz2019', res=(64, 64), spp=256, dims=32)",
    # a slow Python integrand: its remaining batches are skipped once the signal comes
    "slow-callable": "samplab.predict([lambda x: (time.sleep(0.05), x[:, 0])[1]], ['random'], n=[64], res=64, cache=False)",
}


@pytest.mark.skipif(os.name != "posix", reason="SIGINT to oneself")
@pytest.mark.parametrize("name", sorted(CASES))
def test_ctrl_c_stops_a_long_call(name, tmp_path):
    script = textwrap.dedent(
        f"""
        import os, signal, threading, time, samplab
        out = {str(tmp_path / 'report')!r}
        # Ctrl-C raises KeyboardInterrupt, as in a terminal, even where the tests were
        # started with SIGINT ignored (a background job of a shell without job control),
        # which Python would keep
        signal.signal(signal.SIGINT, signal.default_int_handler)
        # the work after the signal in CPU seconds of this process (every thread): what a
        # loaded machine does not stretch, as it stretches wall time
        at = []
        def ctrl_c():
            at.append(time.process_time())
            os.kill(os.getpid(), signal.SIGINT)
        threading.Timer(1.0, ctrl_c).start()
        try:
            {CASES[name]}
        except KeyboardInterrupt:
            print("stopped; CPU seconds after the signal", time.process_time() - at[0])
        else:
            print("finished")
        """
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    words = run.stdout.split()
    assert words[0] == "stopped;", run.stdout
    # the call is gone after little work (two threads busy for a second at most)
    assert float(words[-1]) < 2.0, run.stdout
    assert os.listdir(tmp_path) == [], "an output was left behind"
