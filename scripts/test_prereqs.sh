#!/usr/bin/env bash
# make test: the system programs the window tests use (Xvfb, xdotool, xwininfo) and the browser the
# browser tests drive (Chromium's headless shell, through Playwright), from Debian's packages. Installed with apt-get
# when this runs as root (CI, a fresh machine); otherwise, or when apt-get fails, one line says so and
# the tests that need them skip with a line of their own. Students never need them. In CI (CI=true)
# nothing may be skipped: a program that cannot be installed fails `make test` here.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
LOG="$ROOT/log/bootstrap/test-prereqs.log"

declare -A PACKAGE_OF=([Xvfb]=xvfb [xdotool]=xdotool [xwininfo]=x11-utils
  [chromium-headless-shell]=chromium-headless-shell)
missing=()
for program in "${!PACKAGE_OF[@]}"; do
  command -v "$program" >/dev/null || missing+=("${PACKAGE_OF[$program]}")
done
[ ${#missing[@]} -eq 0 ] && exit 0

# One line about what is missing; in CI that ends `make test`, elsewhere the tests that need it skip.
give_up() {
  if [ "${CI:-}" = true ]; then
    echo "test: $1; in CI (CI=true) the window and browser tests must run, so the run fails" >&2
    exit 1
  fi
  echo "test: $1 (the window and browser tests skip)"
  exit 0
}

if [ "$(id -u)" -ne 0 ] || ! command -v apt-get >/dev/null; then
  give_up "${missing[*]} not installed: 'sudo apt-get install ${missing[*]}'"
fi
mkdir -p "$(dirname "$LOG")"
echo "test: installing ${missing[*]} for the window and browser tests ..."
if ! { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"; } >"$LOG" 2>&1; then
  give_up "apt-get could not install ${missing[*]}; see $LOG"
fi
