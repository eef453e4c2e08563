# Sourced by the browser checks (scripts/screenshot_report.sh, scripts/screenshot_site.sh):
# installs Debian's chromium when absent and this user may, and defines `headless`, which
# runs it headless with a throwaway profile (removed on exit) and the given arguments.
if ! command -v chromium >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ]; then
    apt-get update -qq && apt-get install -y -qq chromium >/dev/null
  else
    echo "chromium is not installed and this user cannot install it" >&2; exit 2
  fi
fi
chromium_profile="$(mktemp -d)"
trap 'rm -rf "$chromium_profile"' EXIT
headless() {
  chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$chromium_profile" --hide-scrollbars "$@"
}
