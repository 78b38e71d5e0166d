#!/usr/bin/env bash
# Regenerates every figure of docs/results.md under the replay rules before the honest ones (13 to 30
# minutes on 2 cores); the honest rules' section is experiments/honest-replay.sh's. Data stays in
# out/, plots in docs/results/. Tables: python experiments/results-tables.py out. The real sets are
# converted with the converters' defaults (docs/world.md); nothing here may be changed to favour a method.
#
# usage: experiments/make-results.sh      (or: make results)
#   PY=PYTHON        the interpreter (default .venv/bin/python)
#   SHARED=DIR       the folder holding kasteren_house_a/ and egtea_gaze_plus/ (default ../shared/datasets);
#                    a set whose folder is missing is skipped
set -euo pipefail
if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"
  exit 0
fi
if [ $# -gt 0 ]; then echo "make-results.sh: takes no arguments (--help)" >&2; exit 2; fi
cd "$(dirname "$0")/.."
PY=${PY:-.venv/bin/python}
SHARED=${SHARED:-../shared/datasets}
# the replay rules these figures were made under, before the honest rules (docs/evaluation.md, "Replay")
OLD=(--candidates vocabulary --decision start --every-step)
$PY -m oracle generate --personas 105 --days 7 --seed 0 --out out/bench
$PY -m oracle evaluate out/bench/test.jsonl "${OLD[@]}" --baselines --ablations \
    --json out/persona-recommended.json --report out/persona-recommended.md --plots docs/results/persona
$PY -m oracle tune out/bench/tune.jsonl --metric top1 --budget 80 --out out/tuned-top1.yaml
$PY -m oracle evaluate out/bench/test.jsonl "${OLD[@]}" --settings out/tuned-top1.yaml --baselines \
    --json out/persona-tuned.json --report out/persona-tuned.md --plots docs/results/persona-tuned
# one real dataset: converted, then evaluated with the recommended and the tuned settings
real_set() {  # NAME (convert's name and out/NAME) FOLDER (under $SHARED)
  [ -d "$SHARED/$2" ] || return 0
  $PY -m oracle convert "$1" "$SHARED/$2" --out "out/$1"
  for s in recommended out/tuned-top1.yaml; do
    tag=$(basename "$s" .yaml)
    $PY -m oracle evaluate "out/$1/chains.jsonl" --odb "out/$1/odb" --mapping "out/$1/mapping.yaml" \
        "${OLD[@]}" --settings "$s" --baselines --json "out/$1-$tag.json" --report "out/$1-$tag.md" \
        --plots "docs/results/$1-$tag"
  done
}
real_set kasteren kasteren_house_a
real_set egtea egtea_gaze_plus
# self-tuning ablations of the routine predictor: its first variant alone, and the likelihood mixture
for m in routine-fixed routine-mixture; do
  $PY -m oracle evaluate out/bench/test.jsonl "${OLD[@]}" --method "$m" --json "out/persona-$m.json"
  if [ -d out/kasteren ]; then
    $PY -m oracle evaluate out/kasteren/chains.jsonl --odb out/kasteren/odb --mapping out/kasteren/mapping.yaml \
        "${OLD[@]}" --method "$m" --json "out/kasteren-$m.json"
  fi
  if [ -d out/egtea ]; then
    $PY -m oracle evaluate out/egtea/chains.jsonl --odb out/egtea/odb --mapping out/egtea/mapping.yaml \
        "${OLD[@]}" --method "$m" --json "out/egtea-$m.json"
  fi
done
# nltk.lm against the online Kneser-Ney of the baselines (docs/evaluation.md, "Kneser-Ney and Witten-Bell")
{ $PY experiments/nltk-speed.py out/bench/test.jsonl 200
  if [ -d out/kasteren ]; then $PY experiments/nltk-speed.py out/kasteren/chains.jsonl 1319; fi; } | tee out/nltk-speed.txt
