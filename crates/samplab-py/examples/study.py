"""The Python guide's study example (docs/guide/python.md): Subr & Kautz's convergence study on a Dask LocalCluster,
checkpointed, byte-identical to the local run; then a CSV and a plot.

    python examples/study.py OUT [--quick]

On a real cluster, replace the LocalCluster by the scheduler's address:
Client("tcp://scheduler:8786"). Worker processes are started by spawning this script
again, hence the __main__ guard.
"""

import os
import sys

from dask.distributed import Client, LocalCluster

from samplab import Study


def main(out: str, quick: bool) -> None:
    os.makedirs(out, exist_ok=True)
    sets = 200 if quick else 10_000
    study = Study.integrate(["random", "jitter", "sobol.owen"], "quad", [16, 64, 256, 1024],
                            sets=sets, instances=10, units_per_chunk=1)
    local = study.run()  # here, on the Rust core's threads
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, env={"RAYON_NUM_THREADS": "1"}, dashboard_address=None)
    with cluster, Client(cluster) as client:
        result = study.run(client, checkpoint=os.path.join(out, "fig6.ckpt"))  # the same chunks on the workers
    assert result.to_json() == local.to_json()
    print({f["sampler"]: round(f["exponent"], 2) for f in result.data["fits"]})
    result.to_csv(os.path.join(out, "fig6.csv"))
    result.plot().figure.savefig(os.path.join(out, "fig6.png"))


if __name__ == "__main__":
    main(sys.argv[1], "--quick" in sys.argv)
