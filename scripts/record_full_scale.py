#!/usr/bin/env python3
"""Record the verdicts of a full-scale report for the fast report's index.

    samplab reproduce --full --out full      # note its wall-clock time
    scripts/record_full_scale.py full SECONDS "MACHINE"

writes crates/samplab-report/data/full_scale.json: the date, the seed (read from the
report's index), the time, the machine and every claim's verdict as the report names it;
and the report's timing.json into the "full" part of crates/samplab-report/data/timings.json
(each experiment's seconds, which order the next full runs longest first).
"""
import datetime
import json
import pathlib
import re
import sys

report, seconds, machine = pathlib.Path(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
index = (report / "index.html").read_text()
seed = int(re.search(r"seed (\d+)", index).group(1))
if "scale full" not in index:
    sys.exit(f"{report} is not a full-scale report")
claims = json.loads((report / "claims.json").read_text())
out = {
    "date": datetime.date.today().isoformat(),
    "seed": seed,
    "seconds": seconds,
    "machine": machine,
    "verdicts": {f"{c['paper']}/{c['id']}": c["verdict_shown"] for c in claims},
}
target = pathlib.Path(__file__).resolve().parent.parent / "crates/samplab-report/data/full_scale.json"
target.write_text(json.dumps(out, indent=2, sort_keys=True) + "\n")
print(f"{target}: {len(claims)} verdicts")
timing = json.loads((report / "timing.json").read_text())["full"]
timings_file = target.parent / "timings.json"
timings = json.loads(timings_file.read_text())
timings["full"] = {
    "recorded": f"{out['date']}, {timing['threads']} threads, {machine} (samplab reproduce --full, report/timing.json)",
    "experiments": timing["experiments"],
}
timings_file.write_text(json.dumps(timings, indent=2, sort_keys=True) + "\n")
print(f"{timings_file}: {len(timing['experiments'])} experiments' times")
