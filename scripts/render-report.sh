#!/usr/bin/env bash
# Renders a report page (index.html) in headless Chromium to a full-page screenshot, to check
# that it opens from disk without network resources or errors.
#   scripts/render-report.sh [--install] [report folder, default reports/paper] [screenshot, default <folder>/screenshot.png]
# Needs `chromium` on PATH (.ci/run installs it before the tests). When it is missing, the script
# installs nothing unless asked: with --install, or a "y" at its prompt on a terminal, it runs
# `apt-get install chromium` (Debian's package; needs root); otherwise it prints that command and
# exits with status 1.
set -euo pipefail

usage="usage: scripts/render-report.sh [--install] [report folder, default reports/paper] [screenshot, default <folder>/screenshot.png]"
install=no
args=()
for arg in "$@"; do
    case $arg in
        --install) install=yes ;;
        -h | --help) echo "$usage"; exit 0 ;;
        -*) echo "$usage" >&2; exit 2 ;;
        *) args+=("$arg") ;;
    esac
done
[ ${#args[@]} -le 2 ] || { echo "$usage" >&2; exit 2; }
dir=${args[0]:-reports/paper}
shot=${args[1]:-$dir/screenshot.png}
[ -f "$dir/index.html" ] || { echo "no $dir/index.html: run the pipeline first" >&2; exit 1; }
page=$(realpath "$dir/index.html")

if ! command -v chromium >/dev/null; then
    cmd="apt-get update && apt-get install -y chromium"
    if [ "$install" = no ] && [ -t 0 ] && [ -t 2 ]; then
        read -r -p "chromium is not installed. Install Debian's chromium now ($cmd, as root)? [y/N] " answer
        [[ $answer == [yY]* ]] && install=yes
    fi
    if [ "$install" = no ]; then
        echo "chromium is not installed. Install it (as root) with:" >&2
        echo "  $cmd" >&2
        echo "or rerun this script with --install." >&2
        exit 1
    fi
    [ "$(id -u)" = 0 ] || { echo "installing chromium needs root: run  sudo $cmd" >&2; exit 1; }
    echo "installing Debian's chromium: $cmd" >&2
    apt-get update -qq >/dev/null
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
    command -v chromium >/dev/null || { echo "chromium still not on PATH after the install" >&2; exit 1; }
fi

profile=$(mktemp -d)
log=$(mktemp)
trap 'rm -rf "$profile" "$log"' EXIT
# Long enough for every figure; Chromium clips the screenshot to the window. --no-sandbox: the
# sandbox cannot start as root or in most containers; the page is a local file.
timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --hide-scrollbars --window-size=1300,9000 \
    --screenshot="$(realpath -m "$shot")" "file://$page" >"$log" 2>&1 ||
    { echo "chromium failed:" >&2; cat "$log" >&2; exit 1; }
[ -s "$shot" ] || { echo "no screenshot written" >&2; cat "$log" >&2; exit 1; }
# A page that failed to load a resource says so on the console.
if grep -E "ERR_FILE_NOT_FOUND|net::ERR_|Uncaught" "$log" >&2; then
    echo "the page reported errors (above)" >&2
    exit 1
fi
echo "rendered $page → $shot ($(stat -c %s "$shot") bytes)"
