#!/usr/bin/env bash
# Create the project's virtual environment with Python 3.11+, installing Debian's python3-venv
# first when the interpreter cannot make one (a fresh Debian machine lacks ensurepip).
set -euo pipefail
PYTHON=${1:-python3}
VENV=${2:-.venv}
"$PYTHON" -c 'import sys; assert sys.version_info >= (3, 11), sys.version' 2>/dev/null || {
  echo "venv: $PYTHON is not Python 3.11 or newer" >&2; exit 1; }
if ! "$PYTHON" -m venv "$VENV" 2>/dev/null; then
  rm -rf "$VENV"
  if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi
  ver=$("$PYTHON" -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')
  $SUDO apt-get update -qq || true
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "python${ver}-venv" >/dev/null
  "$PYTHON" -m venv "$VENV"
fi
"$VENV/bin/python" -m pip install -q --upgrade pip
