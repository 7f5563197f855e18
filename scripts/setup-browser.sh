#!/usr/bin/env bash
# Installs Debian's chromium (/usr/bin/chromium) for the report's headless-browser check
# (scripts/report_browser_check.py), when it is missing. Idempotent. Needs root (CI runs as
# root); the browser comes from the Debian archive through apt-get, never a download of its own.
set -euo pipefail
if [[ -x /usr/bin/chromium ]]; then
    echo "setup-browser: $(/usr/bin/chromium --version 2>/dev/null || echo /usr/bin/chromium) is installed"
    exit 0
fi
if [[ "$(id -u)" -ne 0 ]]; then
    echo "setup-browser: /usr/bin/chromium is missing; as root: apt-get install -y chromium fonts-liberation" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq chromium fonts-liberation
echo "setup-browser: installed $(/usr/bin/chromium --version 2>/dev/null)"
