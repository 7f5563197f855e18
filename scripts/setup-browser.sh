#!/usr/bin/env bash
# Installs Debian's chromium (/usr/bin/chromium) for the report's headless-browser check
# (scripts/report_browser_check.py), when it is missing: scripts/apt-install.sh (root; as
# another user it prints the command and stops). The browser comes from the Debian archive,
# never a download of its own.
set -euo pipefail
"$(dirname "$0")/apt-install.sh" setup-browser chromium chromium fonts-liberation
