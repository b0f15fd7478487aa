#!/usr/bin/env bash
# Install the Debian packages stuart_bt's features need, only those that are missing.
# Idempotent and quick when everything is present. Needs root (or sudo) to install.
set -euo pipefail

have_cmd() { command -v "$1" >/dev/null 2>&1; }
have_lib() { ldconfig -p 2>/dev/null | grep -q "$1"; }

missing=()
have_cmd dot        || missing+=(graphviz)          # stuart-bt show --format svg|png
have_cmd espeak-ng  || missing+=(espeak-ng)         # speech audio (tts daemon, sim backend)
have_lib libEGL.so.1      || missing+=(libegl1)     # MuJoCo headless rendering (MUJOCO_GL=egl)
have_lib libEGL_mesa.so.0 || missing+=(libegl-mesa0 libgl1-mesa-dri)
have_cmd chromium   || missing+=(chromium)          # browser tests of the web view (Playwright drives it)
have_cmd sox        || missing+=(sox)               # noisy copies of spoken test commands (hearing tests)
have_lib libportaudio.so.2 || missing+=(libportaudio2)  # the microphone source (sounddevice)
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -eq 0 ]; then SUDO=""; elif have_cmd sudo; then SUDO="sudo"; else
  echo "system-deps: missing ${missing[*]} and no root/sudo to install them; related tests will skip" >&2
  exit 0
fi
echo "system-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq || true
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
