#!/usr/bin/env bash
# Check the documentation site in a real browser: headless Chromium (Debian's package,
# installed here when absent and this user may) loads the home page, the report's index, the
# atlas's comparison page, five sampler pages and the Python API, screenshots each into
# SITE/screenshots/, and fails on any console message (a script error, say). That every
# image and link of every page resolves and every image decodes is scripts/site.py's check,
# which scripts/docs runs.
#
# Usage: scripts/screenshot_site.sh [SITE]   (default: site; run scripts/docs first)
set -euo pipefail
site="${1:-site}"
[ -f "$site/index.html" ] || { echo "no $site/index.html: run scripts/docs first" >&2; exit 2; }
source "$(dirname "$0")/chromium.sh"
mkdir -p "$site/screenshots"
status=0
pages=(index.html report/index.html atlas/index.html python/samplab.html)
for s in random jitter poisson gbn sobol.owen; do pages+=("atlas/samplers/$s.html"); done
for page in "${pages[@]}"; do
  [ -f "$site/$page" ] || { echo "$page: missing" >&2; status=1; continue; }
  shot="$site/screenshots/$(echo "$page" | tr '/' '_' | sed 's/\.html$//').png"
  log="$(headless --enable-logging=stderr --v=0 --window-size=1280,2000 --screenshot="$shot" "file://$(realpath "$site/$page")" 2>&1 >/dev/null || true)"
  [ -s "$shot" ] || { echo "$page: no screenshot" >&2; status=1; }
  if grep -q 'CONSOLE' <<<"$log"; then
    echo "$page: console messages:" >&2
    grep 'CONSOLE' <<<"$log" >&2
    status=1
  fi
done
echo "${#pages[@]} pages loaded; screenshots in $site/screenshots/"
exit $status
