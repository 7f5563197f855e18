#!/usr/bin/env bash
# Installs Debian's CalculiX (ccx, package calculix-ccx) for the CalculiX adapter
# (adapters/calculix/), when it is missing: scripts/apt-install.sh (root; as another user it
# prints the command and stops).
set -euo pipefail
"$(dirname "$0")/apt-install.sh" setup-calculix ccx calculix-ccx
