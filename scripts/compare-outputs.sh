#!/usr/bin/env bash
# Behaviour check for a refactoring: run the README's commands (and the CLI's
# help and error paths) with the binaries of two commits and compare every
# stdout and stderr byte and every exit code, and the CSV/JSON files they
# write. Figures are only checked to exist (their drawing may change).
#
#   scripts/compare-outputs.sh BEFORE [AFTER]     (AFTER defaults to HEAD)
#
# Wall times are the only output allowed to differ: `map`/`merge` print
# `in 1.23 s`, `trade` a `time [ms]` column (its width too) and `"seconds"` in JSON; they are
# replaced by `<time>` before comparing.
#
# Each commit is checked out in a temporary worktree and built in release
# mode (CARGO_TARGET_DIR=target/compare/<commit>, reused between runs).
# Prints one line per command (same / DIFFERENT) and exits 1 on a difference.
set -euo pipefail

before=${1:?usage: scripts/compare-outputs.sh BEFORE [AFTER]}
after=${2:-HEAD}
root=$(git rev-parse --show-toplevel)
work=$(mktemp -d "${TMPDIR:-/tmp}/stickslip-compare.XXXXXX")
trap 'git -C "$root" worktree remove --force "$work/tree-before" >/dev/null 2>&1 || true;
      git -C "$root" worktree remove --force "$work/tree-after" >/dev/null 2>&1 || true;
      rm -rf "$work"' EXIT

# The commands, as the README writes them (`stickslip` is the binary under
# test). They run in the commit's tree root; `out/` is a scratch folder there.
commands=(
  'stickslip sweep --model paper --param W=0.2:9:200 --set Q0=70'
  'stickslip models'
  'stickslip describe --model paper'
  'stickslip describe --model paper --json'
  'stickslip describe --model stribeck'
  'stickslip orbit --model paper --structure "P_{3_31 0_11 3_13 4_33}" --set W=3.7,Q0=70'
  'stickslip orbit --model paper --structure "P_{3_31 0_11 3_13 4_33}" --set W=3.7,Q0=70 --json'
  'stickslip orbit --model paper --structure "P_{3_31 0_11 3_13 4_33}" --set W=3.7,Q0=70 --plot out/orbit_w3.7.svg'
  'stickslip simulate --model paper --set W=5,Q0=70 --json'
  'stickslip simulate --model paper --set W=5,Q0=70'
  'stickslip simulate --model paper --set W=1,Q0=70'
  'stickslip simulate --model paper --set W=1,Q0=70 --json'
  'stickslip orbit --structure "P_{3_33 4_33}" --set W=3.7,Q0=70 --json'
  'stickslip orbit --structure "P_{3_33 4_33}" --set W=5,Q0=70 --guess 0.0458,3.0183'
  'stickslip orbit --structure "P_{3_31 0_11 3_13 4_33}" --set W=1,Q0=70 --guess 0.6672,6.5814'
  'stickslip simulate --model coulomb --set m=2.5,d=0,c=30,V=0,mus=1.4012680897900847,muk=1.4012680897900847,g=9.8,Q0=70,W=4.3817804600413295'
  'stickslip simulate --model coulomb --set V=0,mus=2,muk=2,Q0=1,m=1,c=1,g=1,W=0.5 --json'
  'stickslip sweep --model paper --param W=3.6:4.3:15 --set Q0=70'
  'stickslip sweep --model paper --param W=3.6:4.3:15 --set Q0=70 --json'
  'stickslip sweep --model paper --param W=0.2:9:200 --set Q0=70 --plot out/sweep_q70.png'
  'stickslip map --model paper --x W=0.2:8:80 --y Q0=0:180:60 --out out/map.csv --plot out/map_paper.png'
  'stickslip map --model paper --x W=2:6:12 --y Q0=20:120:8 --out out/shard-0.csv --shard 0/2'
  'stickslip map --model paper --x W=2:6:12 --y Q0=20:120:8 --out out/shard-1.csv --shard 1/2'
  'stickslip merge out/shard-0.csv out/shard-1.csv --out out/merged.csv'
  'stickslip trade --model stribeck --plot out/trade_stribeck.png'
  'stickslip trade --model stribeck --json'
  'stickslip check tests/ui/models/bad_names.ssm models/paper.ssm'
  'stickslip check --json tests/ui/models/bad_names.ssm'
  'stickslip --help'
  'stickslip models --help'
  'stickslip describe --help'
  'stickslip check --help'
  'stickslip orbit --help'
  'stickslip simulate --help'
  'stickslip sweep --help'
  'stickslip map --help'
  'stickslip merge --help'
  'stickslip trade --help'
  'stickslip orbit --model nope --structure "P_{3_33 4_33}"'
  'stickslip simulate --model paper --set Z=1'
  'stickslip simulate --model paper --set W=abc'
  'stickslip simulate --model paper --set m=-1'
  'stickslip simulate --model paper --set W=5,Q0=70 --plot out/x.gif'
  'stickslip orbit --model paper --structure "P_{3_33 9_99}" --set W=3.7,Q0=70'
  'stickslip sweep --model paper --param Z=1:2:3'
  'stickslip map --model paper --x W=1:2:3 --y Q0=1:2:3 --out /nonexistent/dir/map.csv'
  'stickslip merge out/does-not-exist.csv --out out/m.csv'
  'stickslip trade --model paper'
  'stickslip orbit --model stribeck --structure "P_{3_33 4_33}"'
)
files=(out/map.csv out/shard-0.csv out/shard-1.csv out/merged.csv)
figures=(out/orbit_w3.7.svg out/sweep_q70.png out/map_paper.png out/trade_stribeck.png)

run_all() { # commit label
  local tree="$work/tree-$2" target="$root/target/compare/$(git -C "$root" rev-parse --short "$1")"
  git -C "$root" worktree add --detach -q "$tree" "$1"
  (cd "$tree" && CARGO_TARGET_DIR="$target" cargo build --release -q --bin stickslip)
  mkdir -p "$tree/out" "$work/$2"
  local i=0
  for c in "${commands[@]}"; do
    i=$((i + 1))
    (cd "$tree" && set +e
     bash -c "stickslip() { \"$target/release/stickslip\" \"\$@\"; }; $c" \
       >"$work/$2/$i.out" 2>"$work/$2/$i.err" </dev/null
     echo $? >"$work/$2/$i.code")
  done
  for f in "${files[@]}"; do cp "$tree/$f" "$work/$2/$(basename "$f")" 2>/dev/null || echo missing >"$work/$2/$(basename "$f")"; done
  for f in "${figures[@]}"; do [ -s "$tree/$f" ] && echo present >"$work/$2/$(basename "$f").exists" || echo missing >"$work/$2/$(basename "$f").exists"; done
}

normalise() { # file -> file with wall times replaced
  sed -E -e 's/ in [0-9.]+ (s|ms)$/ in <time> \1/' \
         -e 's/^((pieces|integrator) +[^ ]+ +[^ ]+) +[0-9.]+/\1 <time>/' \
         -e 's/"seconds": [0-9.eE+-]+/"seconds": <time>/g' "$1"
}

echo "before: $(git -C "$root" rev-parse --short "$before")  after: $(git -C "$root" rev-parse --short "$after")"
run_all "$before" before
run_all "$after" after
status=0
i=0
for c in "${commands[@]}"; do
  i=$((i + 1))
  for side in before after; do
    for s in out err; do normalise "$work/$side/$i.$s" >"$work/$side/$i.$s.n"; done
  done
  if cmp -s "$work/before/$i.out.n" "$work/after/$i.out.n" && cmp -s "$work/before/$i.err.n" "$work/after/$i.err.n" \
     && cmp -s "$work/before/$i.code" "$work/after/$i.code"; then
    printf 'same       exit %s  %s\n' "$(cat "$work/after/$i.code")" "$c"
  else
    printf 'DIFFERENT  %s\n' "$c"; status=1
    diff <(cat "$work/before/$i.code" "$work/before/$i.out.n" "$work/before/$i.err.n") \
         <(cat "$work/after/$i.code" "$work/after/$i.out.n" "$work/after/$i.err.n") | head -20 || true
  fi
done
for f in "${files[@]}" "${figures[@]/%/.exists}"; do
  b=$(basename "$f")
  if cmp -s "$work/before/$b" "$work/after/$b"; then printf 'same       file %s\n' "$f"
  else printf 'DIFFERENT  file %s\n' "$f"; status=1; fi
done
[ $status = 0 ] && echo "all ${#commands[@]} commands and ${#files[@]} files byte-identical; ${#figures[@]} figures written by both" || echo "differences found"
exit $status
