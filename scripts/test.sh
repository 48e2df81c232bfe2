#!/usr/bin/env bash
# Builds impactkit and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j2
