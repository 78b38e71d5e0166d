#!/usr/bin/env bash
# The thesis oracle against the same oracle over the normalised distances of thesis 6.4 (an
# option, docs/algorithm.md "Normalised distances"), on the three reported sets, honest replay rules.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-.venv/bin/python}
$PY -m oracle evaluate out/kasteren/chains.jsonl --odb out/kasteren/odb --mapping out/kasteren/mapping.yaml \
    --method thesis --also thesis-normalized --json out/i39-normalized-kasteren.json
$PY -m oracle evaluate out/egtea/chains.jsonl --odb out/egtea/odb --mapping out/egtea/mapping.yaml \
    --method thesis --also thesis-normalized --json out/i39-normalized-egtea.json
$PY -m oracle evaluate out/bench/test.jsonl --method thesis --also thesis-normalized --json out/i39-normalized-persona.json
