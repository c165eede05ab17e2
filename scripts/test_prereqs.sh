#!/usr/bin/env bash
# make test: the system programs the window tests use (Xvfb, xdotool, xwininfo), from Debian's packages.
# Installed with apt-get when this runs as root (CI, a fresh machine); otherwise, or when apt-get fails,
# one line says so and the tests that need them skip with a line of their own. Students never need them.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
LOG="$ROOT/log/bootstrap/test-prereqs.log"

declare -A PACKAGE_OF=([Xvfb]=xvfb [xdotool]=xdotool [xwininfo]=x11-utils)
missing=()
for program in "${!PACKAGE_OF[@]}"; do
  command -v "$program" >/dev/null || missing+=("${PACKAGE_OF[$program]}")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null; then
  echo "test: ${missing[*]} not installed (the window tests skip): 'sudo apt-get install ${missing[*]}'"
  exit 0
fi
mkdir -p "$(dirname "$LOG")"
echo "test: installing ${missing[*]} for the window tests ..."
if ! { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"; } >"$LOG" 2>&1; then
  echo "test: apt-get could not install ${missing[*]} (the window tests skip); see $LOG"
fi
