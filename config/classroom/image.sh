#!/usr/bin/env bash
# The steps of a class's single-user image for Kubernetes (docs/classroom.md), run as root by the
# image's Dockerfile inside the image, and by tests/test_class_image.py into a folder here:
# this checkout set up on the system's python3, which every account can run, then `owl class image`.
#   bash config/classroom/image.sh [CONFIG_DIR [SERVER_VENV]]   (defaults /etc/jupyter, /opt/owl-kit-lab-server)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
PYTHON=/usr/bin/python3 make -C "$ROOT" --no-print-directory setup
set +u  # the workspace's setup scripts (colcon's) read variables that may be unset
# shellcheck source=/dev/null
source "$ROOT/env.sh" >/dev/null
owl class image --config-dir "${1:-/etc/jupyter}" --server-venv "${2:-/opt/owl-kit-lab-server}"
