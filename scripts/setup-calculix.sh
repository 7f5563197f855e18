#!/usr/bin/env bash
# Installs Debian's CalculiX (/usr/bin/ccx, package calculix-ccx) for the CalculiX adapter
# (adapters/calculix/), when it is missing. Idempotent. Needs root (CI runs as root); ccx
# comes from the Debian archive through apt-get, never a download of its own.
set -euo pipefail
if command -v ccx > /dev/null; then
    echo "setup-calculix: $(command -v ccx) is installed ($(ccx -v 2>/dev/null | grep -m1 -i version | tr -d '\n'))"
    exit 0
fi
if [[ "$(id -u)" -ne 0 ]]; then
    echo "setup-calculix: ccx is missing; as root: apt-get install -y calculix-ccx" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq calculix-ccx
echo "setup-calculix: installed $(command -v ccx) ($(ccx -v 2>/dev/null | grep -m1 -i version | tr -d '\n'))"
