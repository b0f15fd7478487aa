#!/usr/bin/env bash
# Install the Debian packages stuart_bt's features need, only those that are missing.
# Idempotent and quick when everything is present. Needs root (or sudo) to install.
set -euo pipefail

# package -> a file or command that shows it is installed
declare -A NEEDS=(
  [graphviz]=dot          # stuart-bt show --format svg|png
)

missing=()
for pkg in "${!NEEDS[@]}"; do
  command -v "${NEEDS[$pkg]}" >/dev/null 2>&1 || missing+=("$pkg")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then SUDO=""; elif command -v sudo >/dev/null; then SUDO="sudo"; else
  echo "system-deps: missing ${missing[*]} and no root/sudo to install them; related tests will skip" >&2
  exit 0
fi
echo "system-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq || true
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
