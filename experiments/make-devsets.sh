#!/usr/bin/env bash
# Builds the routine predictor's development sets (docs/algorithm.md, "Development sets and what
# helped"; fifteen, and since 2026-12-06 a sixteenth of long histories, "Tuning window"), replayed
# only to choose, never reported. Data stays outside the project.
#
# usage: experiments/make-devsets.sh OUT [RAW]
#   OUT: where the sets go (OUT/bench/tune.jsonl, OUT/dev/{,open/,clockless/}{seed1,short}.jsonl,
#        OUT/dev/{open,clockless}/tune.jsonl, OUT/real/NAME/{chains.jsonl,odb,mapping.yaml})
#   RAW: the public files the real sets are made from, as each converter's docstring names them:
#        RAW/mit-subject1 (experiments/devset-mit-subject1.py), RAW/ek55 (experiments/devset-ek55.py),
#        RAW/kasteren-bc (experiments/devset-kasteren-bc.py); a missing folder skips that set.
# Then each set is replayed with: python experiments/routine-variants.py CHAINS [--odb DIR --mapping YAML] ...
# (OUT/sets.txt lists each set's name and those arguments, one line each).
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-.venv/bin/python}
OUT=${1:?usage: experiments/make-devsets.sh OUT [RAW]}
RAW=${2:-}
mkdir -p "$OUT/dev"
# the persona tuning split (the same command makes the reported test split: never replay it)
$PY -m oracle generate --personas 105 --days 7 --seed 0 --out "$OUT/bench"
# a held-out persona set and a sparse-history set, both of each one's files
$PY -m oracle generate --personas 40 --days 7 --seed 1 --out "$OUT/seed1"
cat "$OUT/seed1/tune.jsonl" "$OUT/seed1/test.jsonl" > "$OUT/dev/seed1.jsonl"
$PY -m oracle generate --personas 40 --days 2 --seed 2 --out "$OUT/sparse"
cat "$OUT/sparse/tune.jsonl" "$OUT/sparse/test.jsonl" > "$OUT/dev/short.jsonl"
# long histories (6 personas, 60 days: 1,667-2,912 actions each), where the tuning window binds
$PY -m oracle generate --personas 6 --days 60 --seed 7 --out "$OUT/long"
cat "$OUT/long/tune.jsonl" "$OUT/long/test.jsonl" > "$OUT/dev/long.jsonl"
for chains in "$OUT/bench/tune.jsonl" "$OUT/dev/seed1.jsonl" "$OUT/dev/short.jsonl"; do
  $PY experiments/dev-conditions.py "$chains" "$OUT/dev"
done
{
  echo "tune $OUT/bench/tune.jsonl"
  for name in seed1 short long; do echo "$name $OUT/dev/$name.jsonl"; done
  for condition in open clockless; do
    for name in tune seed1 short; do echo "$name-$condition $OUT/dev/$condition/$name.jsonl"; done
  done
} > "$OUT/sets.txt"
real() {  # NAME: one real set, listed with its odb and mapping
  echo "$1 $OUT/real/$1/chains.jsonl --odb $OUT/real/$1/odb --mapping $OUT/real/$1/mapping.yaml" >> "$OUT/sets.txt"
}
if [ -n "$RAW" ] && [ -d "$RAW/mit-subject1" ]; then
  $PY experiments/devset-mit-subject1.py "$RAW/mit-subject1" "$OUT/real/mit-subject1" && real mit-subject1
fi
if [ -n "$RAW" ] && [ -d "$RAW/ek55" ]; then
  $PY experiments/devset-ek55.py "$RAW/ek55" "$OUT/real/ek55" && real ek55
fi
if [ -n "$RAW" ] && [ -d "$RAW/kasteren-bc" ]; then
  for house in B C; do
    h=$(echo "$house" | tr BC bc)
    $PY experiments/devset-kasteren-bc.py "$house" "$RAW/kasteren-bc" "$OUT/real/kasteren-$h" && real "kasteren-$h"
    $PY experiments/devset-kasteren-bc.py "$house" "$RAW/kasteren-bc" "$OUT/real/kasteren-$h-objects" --object-sensors \
      && real "kasteren-$h-objects"
  done
fi
echo "development sets: $(wc -l < "$OUT/sets.txt") (listed in $OUT/sets.txt)"
