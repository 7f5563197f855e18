#!/usr/bin/env bash
# Installs Debian packages through apt-get when a program is missing: the one way the
# project's setup scripts (setup-browser.sh, setup-calculix.sh) get system programs. Idempotent.
# Needs root (CI runs as root); as another user it prints the command and exits 1.
#
#   scripts/apt-install.sh WHO PROGRAM PACKAGE...
set -euo pipefail
who="$1" program="$2"
shift 2
if command -v "$program" > /dev/null; then
    echo "$who: $(command -v "$program") is installed"
    exit 0
fi
if [[ "$(id -u)" -ne 0 ]]; then
    echo "$who: $program is missing; as root: apt-get install -y $*" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq "$@"
echo "$who: installed $(command -v "$program")"
