#!/usr/bin/env bash
# Check the report in a real browser: headless Chromium (Debian's package, installed here
# when absent) screenshots index.html and every paper page into REPORT/screenshots/, and
# every <img> of every page must be a decodable PNG with a non-zero size.
#
# Usage: scripts/screenshot_report.sh [REPORT_DIR]   (default: report; run `samplab reproduce` first)
# CI may skip this when Chromium cannot be installed; the link test in
# crates/samplab-report/tests/report.rs always runs.
set -euo pipefail
report="${1:-report}"
[ -f "$report/index.html" ] || { echo "no $report/index.html: run samplab reproduce first" >&2; exit 2; }
source "$(dirname "$0")/chromium.sh"
mkdir -p "$report/screenshots"
status=0
for page in "$report"/*.html; do
  name="$(basename "$page" .html)"
  headless --window-size=1200,2400 --screenshot="$report/screenshots/$name.png" "file://$(realpath "$page")" >/dev/null 2>&1
  [ -s "$report/screenshots/$name.png" ] || { echo "no screenshot of $page" >&2; status=1; }
done
# every image a page shows must exist and decode as a PNG with a size
python3 - "$report" <<'PY' || status=1
import re, struct, sys, pathlib
root = pathlib.Path(sys.argv[1])
bad = 0
for page in root.glob("*.html"):
    for src in re.findall(r'<img src="([^"]+)"', page.read_text()):
        f = root / src
        data = f.read_bytes() if f.is_file() else b""
        if data[:8] != b"\x89PNG\r\n\x1a\n":
            print(f"{page.name}: broken image {src}"); bad += 1; continue
        w, h = struct.unpack(">II", data[16:24])
        if w == 0 or h == 0:
            print(f"{page.name}: empty image {src}"); bad += 1
print(f"images checked; {bad} broken")
sys.exit(1 if bad else 0)
PY
echo "screenshots in $report/screenshots/"
exit $status
