"""Distributed studies: the engine's overhead, and what Subr & Kautz's Figure 6 would cost.

Run by `bench/compare study` (which installs the package and Dask into bench/.venv).

1. Overhead: one integration study in chunks of about a second, run locally (chunk after
   chunk, each on rayon's two threads) and on a LocalCluster of two worker processes with
   one thread each; medians of three runs, cluster start-up left out (reported apart).
2. Figure 6 at 10^4 realizations per point (12 strategies x 3 test cases x 7 counts x 10
   instances): every (strategy, case, count) unit is timed on one thread at 200
   realizations, scaled by 50 (a unit's cost is linear in its realizations), and summed;
   on W workers the work divides by W (2520 units: far more than 64) plus the overhead
   measured in 1.
"""

import os
import subprocess
import sys
import time

from samplab import Study
from timing import median_time

NS = [16, 36, 64, 144, 256, 576, 1024]
STRATEGIES = ["random", "poisson", "jitter", "sobol.owen", "halton.xor", "nrooks", "hammersley.xor",
              "jitter.box:delta=0.05", "jitter.gaussian:sigma=0.1", "jitter.gaussian:sigma=0.25",
              "jitter.gaussian:sigma=0.5", "jitter.gaussian:sigma=1"]
CASES = ["quad", "delaunay-constant", "delaunay-linear"]


def overhead():
    import distributed

    study = Study.integrate(["random", "jitter"], "disk", [4096], sets=60000, instances=4, seed=1)
    per_chunk = median_time(lambda: Study.integrate(["random"], "disk", [4096], sets=60000, instances=1, seed=1).run(progress=False), 1)
    local = median_time(lambda: study.run(progress=False), min_runs=3)
    t = time.perf_counter()
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                       env={"RAYON_NUM_THREADS": "1"})
    client = distributed.Client(cluster)
    client.wait_for_workers(2)
    startup = time.perf_counter() - t
    on_dask = median_time(lambda: study.run(client, progress=False), min_runs=3)
    same = study.run(client, progress=False).to_json() == study.run(progress=False).to_json()
    client.close()
    cluster.close()
    print(f"integration study, {len(study.chunks)} chunks of ~{per_chunk:.2f} s (2 threads):")
    print(f"  local (rayon, 2 threads)                 {local:7.2f} s")
    print(f"  LocalCluster, 2 workers x 1 thread       {on_dask:7.2f} s   ratio {on_dask / local:.3f}  (same bytes: {same})")
    print(f"  cluster start-up (not included)          {startup:7.2f} s")
    return on_dask / local


def figure6(ratio):
    total, longest = 0.0, (0.0, "")
    for case in CASES:
        for s in STRATEGIES:
            for n in NS:
                st = Study.integrate([s], case, [n], sets=200, instances=1, seed=3)
                t = time.perf_counter()
                st.run(progress=False)
                unit = (time.perf_counter() - t) * 50  # one unit: x50 realizations
                total += unit * 10  # x10 instances
                longest = max(longest, (unit, f"{s} on {case} at N = {n}"))
    print("Subr & Kautz Fig. 6 at 10^4 realizations (12 strategies x 3 cases x 7 counts x 10 instances):")
    print(f"  1 worker (one thread)                    {total / 60:7.1f} min")
    for w in (2, 64):
        # the work divided, times the overhead measured above, and never below the longest unit
        print(f"  {w:2d} workers (one thread each)            {max(total / w * ratio, longest[0]) / 60:7.1f} min")
    print(f"  longest unit: {longest[1]}, {longest[0]:.1f} s")


if __name__ == "__main__":
    if sys.argv[1:2] == ["figure6"]:
        figure6(float(sys.argv[2]))
    else:
        r = overhead()
        # part 2 on one thread: a process of its own, its pool sized by the environment
        env = dict(os.environ, RAYON_NUM_THREADS="1")
        subprocess.run([sys.executable, __file__, "figure6", str(r)], env=env, check=True)
