#!/usr/bin/env bash
# Renders a report page (index.html) in headless Chromium to a full-page screenshot, to check
# that it opens from disk without network resources or errors.
#   scripts/render-report.sh [report folder, default reports/paper] [screenshot, default <folder>/screenshot.png]
# Installs Debian's chromium if it is missing (needs root and the package registry).
set -euo pipefail
dir=${1:-reports/paper}
shot=${2:-$dir/screenshot.png}
page=$(realpath "$dir/index.html")
[ -f "$page" ] || { echo "no $page: run the pipeline first" >&2; exit 1; }
if ! command -v chromium >/dev/null; then
    echo "installing chromium (Debian package)…" >&2
    apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
log=$(mktemp)
# Long enough for every figure; Chromium clips the screenshot to the window.
timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --hide-scrollbars --window-size=1300,9000 \
    --screenshot="$(realpath -m "$shot")" "file://$page" >"$log" 2>&1 || { cat "$log" >&2; exit 1; }
[ -s "$shot" ] || { echo "no screenshot written" >&2; cat "$log" >&2; exit 1; }
# A page that failed to load a resource says so on the console.
if grep -E "ERR_FILE_NOT_FOUND|net::ERR_|Uncaught" "$log" >&2; then
    echo "the page reported errors (above)" >&2
    exit 1
fi
echo "rendered $page → $shot ($(stat -c %s "$shot") bytes)"
