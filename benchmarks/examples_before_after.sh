#!/bin/bash
# Before/after check of a change that must not change any answer (issue 33's harness).
#
# Usage:  benchmarks/examples_before_after.sh BEFORE_TREE AFTER_TREE [WORK]
#
# BEFORE_TREE and AFTER_TREE are source trees (e.g. `git worktree add /tmp/before <rev>` and this
# checkout). With each tree's src/ first on PYTHONPATH and this checkout's .venv python, it runs
# `design --json` and `design --out` of every example of BEFORE_TREE/examples (the same names
# are read from AFTER_TREE), `pattern --out` of the case study, `analyze --json` of the paper's
# case 1, and `design --json` of benchmarks/specs/*.toml, tests/data/*.toml and
# tests/data/diagnosis/*.toml; then compares the JSON answers key by key (without *_seconds
# timings and the budget; keys new in AFTER are listed, not failures) and the output folders with
# benchmarks/compare_sets.py (manifest SHA-256s after dropping run stamps). Exit 0: the same.
set -u
BEFORE=$(cd "$1" && pwd); AFTER=$(cd "$2" && pwd); WORK=${3:-$(mktemp -d)}
HERE=$(cd "$(dirname "$0")/.." && pwd)
PY="$HERE/.venv/bin/python"
export PYTHONHASHSEED=0  # ezdxf orders two OBJECTS entries by hash
run() {  # run TREE OUT
  local tree=$1 out=$2 ex b
  mkdir -p "$out/json" "$out/sets"
  for ex in "$BEFORE"/examples/*.toml; do
    b=$(basename "$ex" .toml); ex="$tree/examples/$b.toml"
    PYTHONPATH="$tree/src" "$PY" -m corrugate design "$ex" --json > "$out/json/$b.json" 2> /dev/null
    rm -rf "$out/sets/$b"
    PYTHONPATH="$tree/src" "$PY" -m corrugate design "$ex" --out "$out/sets/$b" -q > /dev/null 2>&1
  done
  rm -rf "$out/sets/pattern"
  PYTHONPATH="$tree/src" "$PY" -m corrugate pattern --W 8 --n 8 --alpha 84 --material dura-lar \
    --out "$out/sets/pattern" -q > /dev/null 2>&1
  PYTHONPATH="$tree/src" "$PY" -m corrugate analyze --W 8 --n 8 --alpha 84 --material dura-lar \
    --model paper --eta 0 --eta 90 --json > "$out/json/analyze_case1.json"
  for ex in "$BEFORE"/benchmarks/specs/*.toml "$BEFORE"/tests/data/*.toml "$BEFORE"/tests/data/diagnosis/*.toml; do
    b=x_$(basename "$ex" .toml)
    PYTHONPATH="$tree/src" timeout 300 "$PY" -m corrugate design "$ex" --json > "$out/json/$b.json" 2> /dev/null
  done
}
run "$BEFORE" "$WORK/before"
run "$AFTER" "$WORK/after"
"$PY" - "$WORK/before/json" "$WORK/after/json" <<'PYEOF'
import json, pathlib, sys

def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if not (k.endswith("_seconds") or k == "budget")}
    return [strip(x) for x in v] if isinstance(v, list) else v

def diff(a, b, path=""):
    if isinstance(a, dict) and isinstance(b, dict):
        out = [f"{path}/{k}: missing after" for k in a if k not in b]
        out += [f"{path}/{k}: new key after" for k in b if k not in a]
        return out + [d for k in a if k in b for d in diff(a[k], b[k], f"{path}/{k}")]
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in diff(x, y, f"{path}[{i}]")]
    return [] if a == b else [f"{path}: {str(a)[:80]} -> {str(b)[:80]}"]

bad = 0
for f in sorted(pathlib.Path(sys.argv[1]).glob("*.json")):
    d = diff(strip(json.loads(f.read_text())), strip(json.loads((pathlib.Path(sys.argv[2]) / f.name).read_text())))
    real = [x for x in d if "new key after" not in x]
    print(f"{f.name}: {'DIFFERS' if real else 'same'}" + (f" ({len(d)} new keys)" if d and not real else ""))
    for x in real[:20]:
        print("   ", x)
    bad += bool(real)
sys.exit(1 if bad else 0)
PYEOF
j=$?
"$PY" "$HERE/benchmarks/compare_sets.py" "$WORK/before/sets" "$WORK/after/sets"; s=$?
echo "answers rc=$j files rc=$s ($WORK)"
[ $j = 0 ] && [ $s = 0 ]
