#!/usr/bin/env bash
# Set up (install + build) and run phasmid's main job on its embedded defaults.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
./build/phasmid demo -o "${1:-demo_output}"
