#!/usr/bin/env bash
# Issue 34, item 4: imports every face of every STEP / IGES file under a folder, one process per
# file (build/release/tests/cad_corpus_study; a crash or a hang, killed after TIMEOUT seconds,
# costs only its file), and prints per file and in total: faces, faces imported, failure
# classes with their counts, and the comparison with OpenCASCADE's closest points.
#
# usage: scripts/cad_corpus_study.sh <folder> [out folder] [points per face]
#   env: STUDY (the program; default build/release/tests/cad_corpus_study), TIMEOUT (300)
set -euo pipefail
dir=${1:?usage: cad_corpus_study.sh <folder> [out folder] [points per face]}
out=${2:-build/cad_corpus_study}
points=${3:-20}
study=${STUDY:-build/release/tests/cad_corpus_study}
timeout_s=${TIMEOUT:-300}
mkdir -p "$out"
: >"$out/all.txt"
find "$dir" -type f \( -iname '*.step' -o -iname '*.stp' -o -iname '*.iges' -o -iname '*.igs' \) |
  sort | while read -r f; do
  log="$out/$(echo "$f" | tr '/' '_').txt"
  rc=0
  timeout "$timeout_s" nice "$study" "$f" "$points" >"$log" 2>/dev/null || rc=$?
  if ! grep -q '^FILE' "$log"; then
    if [ "$rc" = 124 ]; then echo -e "FILE\t$f\tcrashed\ttimeout after ${timeout_s} s" >>"$log"
    else echo -e "FILE\t$f\tcrashed\texit status $rc" >>"$log"; fi
  fi
  cat "$log" >>"$out/all.txt"
done
python3 - "$out/all.txt" <<'PY'
import re, sys, collections
files = []; cur = []
for line in open(sys.argv[1], errors="replace"):
    c = line.rstrip("\n").split("\t")
    if c[0] == "FACE":
        cur.append(c)
    elif c[0] == "FILE":
        files.append((c, cur)); cur = []
whole = nofaces = partial = unreadable = crashed = 0
faces = imported = cmpfail = points = same = closer = none = ties = outside = unconv = approx = 0
approx_worst = 0.0
ill = 0
ill_reach = 0.0
classes = collections.Counter(); cmpclasses = collections.Counter(); examples = {}
crashes = []
def cls(msg):
    m = re.sub(r"^face \d+ \([a-z]+\): ", "", msg)
    m = re.sub(r"-?\d+(\.\d+)?(e[-+]?\d+)?", "#", m)
    return m[:140]
for c, fl in files:
    if c[2] == "unreadable": unreadable += 1; continue
    n_ok = sum(1 for f in fl if f[3] == "ok")
    if c[2] == "crashed":
        crashed += 1; crashes.append(f"{c[1]} ({c[3]}, after {len(fl)} faces)")
        faces += len(fl); imported += n_ok
    else:
        n = int(c[3]); faces += n; imported += n_ok
        if n == 0: nofaces += 1
        elif n_ok == n: whole += 1
        else: partial += 1
    for f in fl:
        if f[3] == "fail":
            k = cls(f[4]); classes[k] += 1; examples.setdefault(k, c[1] + ": " + f[4])
        elif len(f) > 5 and f[5] == "cmpfail":
            cmpfail += 1; k = re.sub(r"x = \([^)]*\): ", "", f[6]); k = cls(k)
            cmpclasses[k] += 1; examples.setdefault("cmp:" + k, c[1] + ": face " + f[1] + ": " + f[6])
        elif len(f) > 5 and f[5] == "cmp":
            points += int(f[6]); same += int(f[7]); closer += int(f[8]); none += int(f[9])
            ties += int(f[11]) if len(f) > 11 else 0
            outside += int(f[12]) if len(f) > 12 else 0
            unconv += int(f[13]) if len(f) > 13 else 0
            if len(f) > 15:
                approx += int(f[14]); approx_worst = max(approx_worst, float(f[15]))
            if len(f) > 17:
                ill += int(f[16]); ill_reach = max(ill_reach, float(f[17]))
print(f"files: {len(files)}; with faces, imported whole: {whole}; partly: {partial}; "
      f"no faces: {nofaces}; unreadable: {unreadable}; crashed/timed out: {crashed}")
print(f"faces: {faces}; imported: {imported}; failed: {faces - imported}")
print(f"comparison with OCCT: points {points}, same foot {same}, ours closer {closer}, "
      f"OCCT none {none}, feet apart on a bound {ties}, OCCT's foot outside an untrimmed face "
      f"{outside}, equal distances with OCCT's foot not stationary {unconv}, approximated faces' "
      f"feet apart, each stationary on its own surface {approx} (at most {approx_worst:.3g} h), "
      f"feet of an ill-conditioned foot apart within its round-off reach {ill} (reach at most "
      f"{ill_reach:.3g} h); "
      f"faces whose comparison failed: {cmpfail}")
print("import failure classes (count, message with numbers as #):")
for k, v in classes.most_common(): print(f"  {v:6d}  {k}\n          e.g. {examples[k][:300]}")
print("comparison failure classes:")
for k, v in cmpclasses.most_common(): print(f"  {v:6d}  {k}\n          e.g. {examples['cmp:' + k][:300]}")
for c in crashes: print("crashed:", c)
PY
