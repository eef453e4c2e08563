#!/usr/bin/env python3
"""Record the atlas's generation speeds (the pages show the recorded ones, so that the
atlas's bytes do not depend on the machine's load).

    scripts/record_atlas_speed.py [BINARY] [--only a,b]   (default: target/release/samplab)

runs `samplab atlas --speed` on one thread (RAYON_NUM_THREADS=1) on a quiet machine and
writes its speed.json into crates/samplab-report/data/atlas_speed.json, the date and the
CPU model added to its "measured" line. With --only, measures those samplers and replaces
their entries alone, the line naming them and their date.
"""
import datetime
import json
import os
import pathlib
import subprocess
import sys
import tempfile

root = pathlib.Path(__file__).resolve().parent.parent
args = sys.argv[1:]
only = []
if "--only" in args:
    i = args.index("--only")
    only = ["--only", args[i + 1]]
    del args[i:i + 2]
binary = args[0] if args else str(root / "target/release/samplab")
cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "?")
with tempfile.TemporaryDirectory() as tmp:
    out = pathlib.Path(tmp) / "atlas"
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    subprocess.run([binary, "atlas", "--speed", "--out", str(out)] + only, env=env, check=True)
    speeds = json.loads((out / "speed.json").read_text())
target = root / "crates/samplab-report/data/atlas_speed.json"
when = f"{datetime.date.today().isoformat()}, {cpu}"
if only:
    recorded = json.loads(target.read_text())
    recorded["samplers"].update(speeds["samplers"])
    recorded["measured"] += f"; {only[1]}: {when}"
    speeds = recorded
else:
    speeds["measured"] += f", {when}"
target.write_text(json.dumps(speeds, indent=2, sort_keys=True) + "\n")
print(f"{len(speeds['samplers'])} speeds recorded in {target}")
