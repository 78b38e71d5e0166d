#!/usr/bin/env bash
# The honest replay's figures (docs/results.md, "Honest replay, learned baselines, chains"): the three
# reported sets replayed once under the honest rules (docs/evaluation.md, "Replay") with every
# baseline, the learned ones (logit, gbdt) and the stacked predictor; then the chain accuracy.
# Data stays in out/; tables: python experiments/honest-tables.py out.
# The sets are made as experiments/make-results.sh makes them (converters' defaults; nothing here may
# be changed to favour a method).
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-.venv/bin/python}
SHARED=${SHARED:-/work/shared/datasets}
[ -f out/bench/test.jsonl ] || $PY -m oracle generate --personas 105 --days 7 --seed 0 --out out/bench
[ -d out/kasteren ] || $PY -m oracle convert kasteren "$SHARED/kasteren_house_a" --out out/kasteren
[ -d out/egtea ] || $PY -m oracle convert egtea "$SHARED/egtea_gaze_plus" --out out/egtea
KA=(out/kasteren/chains.jsonl --odb out/kasteren/odb --mapping out/kasteren/mapping.yaml)
EG=(out/egtea/chains.jsonl --odb out/egtea/odb --mapping out/egtea/mapping.yaml)
$PY -m oracle evaluate "${KA[@]}" --baselines --also stacked --json out/i39-kasteren.json
for r in 0:8 8:16 16:24 24:; do
  $PY experiments/shards.py run "${EG[@]}" --users "$r" --out "out/i39-egtea-${r%%:*}.shard.json" &
done
wait
$PY experiments/shards.py merge out/i39-egtea-{0,8,16,24}.shard.json --json out/i39-egtea.json
# the persona test split in three shards of users side by side, merged into what one evaluate writes
for r in 0:30 30:60 60:; do
  $PY experiments/shards.py run out/bench/test.jsonl --users "$r" --out "out/i39-persona-${r%%:*}.shard.json" &
done
wait
$PY experiments/shards.py merge out/i39-persona-0.shard.json out/i39-persona-30.shard.json out/i39-persona-60.shard.json \
    --json out/i39-persona.json
$PY experiments/chains.py "${KA[@]}" --json out/i39-chains-kasteren.json
$PY experiments/chains.py "${EG[@]}" --json out/i39-chains-egtea.json
# the persona set was made by the kitchen world: its rules chain too (--world)
$PY experiments/chains.py out/bench/test.jsonl --world --json out/i39-chains-persona.json
