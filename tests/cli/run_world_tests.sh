#!/usr/bin/env bash
# Region jobs on a real Slurm (issue 15): a single-node cluster started and stopped here
# (scripts/slurm-local.sh), the meadow planned into several tasks, submitted with the plan's submit.sh
# (Ghost Tile step -> job array -> join), and the joined world compared with a single-process run instance
# for instance through an independent reader (check_gltf.mjs --dump-instances); the region files alone
# also add up to it. Then a task killed mid-run and requeued, stale and missing regions refused by join,
# and a scene edited after planning refused by its tasks. UG_BIN is the binary; needs root.
set -u
bin="${UG_BIN:?UG_BIN must name the undergrowth binary}"
root="$(cd "$(dirname "$0")/../.." && pwd)"
tmp="$(mktemp -d /tmp/ug-world.XXXXXX)"
cluster="$tmp/slurm"
cleanup() { bash "$root/scripts/slurm-local.sh" stop "$cluster" >/dev/null 2>&1; rm -rf "$tmp"; }
trap cleanup EXIT
passed=0
failed=0
t0=$SECONDS
ok() { passed=$((passed + 1)); echo "ok   - $1 [$((SECONDS - t0)) s]"; }
bad() { failed=$((failed + 1)); echo "FAIL - $1"; }
check="$root/tests/gltf/check_gltf.mjs"
scene="$root/assets/scenes/meadow.json"

if ! bash "$root/tests/gltf/setup.sh" >"$tmp/npm.txt" 2>&1; then
  bad "the glTF reader (tests/gltf/setup.sh): $(cat "$tmp/npm.txt")"; echo "passed $passed, failed $failed"; exit 1; fi
start_out=$(bash "$root/scripts/slurm-local.sh" start "$cluster" 2>&1)
if [ $? -ne 0 ]; then bad "slurm: the single-node cluster starts: $start_out"; echo "passed $passed, failed $failed"; exit 1; fi
ok "slurm: the single-node cluster starts"
export SLURM_CONF="$cluster/slurm.conf"

# Waits until none of the given jobs is pending or running (at most $2 seconds).
wait_jobs() {
  local ids="$1" limit="$2" t=0
  while [ "$t" -lt $((limit * 5)) ]; do
    [ -z "$(squeue -h -j "$ids" -t PD,R,CG,CF,RQ,S 2>/dev/null)" ] && return 0
    sleep 0.2; t=$((t + 1))
  done
  return 1
}
job_states() { scontrol -o show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | sort | uniq -c | tr -s ' '; }
dump() { node "$check" "$1" --dump-instances "$2" >/dev/null 2>"$2.err"; }

# 1. The whole meadow in one process: the reference.
if "$bin" instantiate "$scene" -o "$tmp/single.glb" --cache "$tmp/cache" --threads 2 >/dev/null 2>"$tmp/single.err" &&
   dump "$tmp/single.glb" "$tmp/single.txt"; then ok "single process: $(wc -l <"$tmp/single.txt") instances"; else
  bad "single process: $(cat "$tmp/single.err" "$tmp/single.txt.err" 2>/dev/null)"; fi

# 2. Plan, submit, wait, compare.
plan="$tmp/plan"
if "$bin" plan "$scene" --out "$plan" --memory-per-job 200M --threads-per-task 1 >"$tmp/plan.out" 2>&1; then
  ok "plan: $(tr '\r' '\n' <"$tmp/plan.out" | grep -m1 '^plan ')"; else bad "plan: $(cat "$tmp/plan.out")"; fi
tasks=$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['regions']))" "$plan/plan.json" 2>/dev/null || echo 0)
if [ "$tasks" -ge 4 ]; then ok "plan: $tasks tasks (>= 4)"; else bad "plan: $tasks tasks, wanted >= 4"; fi
if ids=$(bash "$plan/submit.sh" 2>&1); then ok "submit.sh: $ids"; else bad "submit.sh: $ids"; fi
read -r _ cache_id _ array_id _ join_id <<<"$ids"
# plan built the Ghost Tile into the plan's cache, so submit.sh submits no cache step ("cache -").
if [ "$cache_id" = "-" ]; then ok "submit.sh: no cache step, the plan's cache holds the Ghost Tile"; else bad "submit.sh: a cache step ($cache_id) though the cache is full"; fi
if wait_jobs "$array_id,$join_id" 600; then ok "slurm: the three steps ended"; else bad "slurm: jobs still queued after 600 s: $(squeue)"; fi
states="$(job_states "$array_id")"
if [ "$(job_states "$join_id")" = " 1 COMPLETED" ] && ! grep -qv COMPLETED <<<"$states"; then ok "slurm: every task and the join completed ($states)"; else
  bad "slurm: states array [$states] join [$(job_states "$join_id")]: $(tail -5 "$plan"/logs/*.log)"; fi
if dump "$plan/world.glb" "$tmp/world.txt" && cmp -s "$tmp/single.txt" "$tmp/world.txt"; then
  ok "join: the joined world equals the single process, instance for instance"; else
  bad "join: joined world differs from the single process: $(diff "$tmp/single.txt" "$tmp/world.txt" | head -5) $(cat "$tmp/world.txt.err" 2>/dev/null)"; fi
: >"$tmp/regions.txt"
for f in "$plan"/regions/region_*.glb; do dump "$f" "$tmp/r.txt" && cat "$tmp/r.txt" >>"$tmp/regions.txt"; done
if sort "$tmp/regions.txt" | cmp -s - "$tmp/single.txt"; then ok "regions: the $tasks region files add up to the single process"; else
  bad "regions: their union differs from the single process ($(wc -l <"$tmp/regions.txt") vs $(wc -l <"$tmp/single.txt") lines)"; fi
if python3 - "$plan/manifest.json" "$(wc -l <"$tmp/single.txt")" "$tasks" <<'PY'; then ok "join: the manifest lists every region, its bounds, count and hash"; else bad "join: manifest"; fi
import json, sys
m = json.load(open(sys.argv[1]))
assert m["instances"] == int(sys.argv[2]), m["instances"]
assert len(m["regions"]) == int(sys.argv[3])
assert sum(r["instances"] for r in m["regions"]) == m["instances"]
for r in m["regions"]:
    assert all(a < b for a, b in zip(r["min"], r["max"])) and len(r["glb_hash"]) == 16 and r["glb_bytes"] > 0, r
assert m["joined"].endswith("world.glb")
PY
# A world bigger than join's --max-bytes stays as region files plus the manifest (which still lists them).
if out=$("$bin" join "$plan" -o "$tmp/too_big.glb" --max-bytes 64K 2>&1) && grep -q "stays as $tasks region files" <<<"$out" &&
   [ ! -e "$tmp/too_big.glb" ] &&
   python3 -c 'import json,sys; m=json.load(open(sys.argv[1])); assert m["joined"] is None and "joined_refused" in m and len(m["regions"]) == int(sys.argv[2]), m' \
     "$plan/manifest.json" "$tasks"; then
  ok "join: a world over --max-bytes stays as region files plus the manifest"; else bad "join --max-bytes: $out"; fi
# A re-run of a task whose outputs are complete skips it and changes nothing.
before=$(md5sum "$plan"/regions/region_0000.*)
out=$("$bin" instantiate --plan "$plan" --task 0 2>&1)
if grep -q "skipped" <<<"$out" && [ "$before" = "$(md5sum "$plan"/regions/region_0000.*)" ]; then ok "task: complete outputs are skipped"; else bad "task re-run: $out"; fi

# Submitting the plan again with its cache emptied: the cache step rebuilds the Ghost Tile first, every
# task finds its outputs complete and skips, and the join runs again.
rm -f "$plan"/cache/ghosttile-*.ugt
if ids=$(bash "$plan/submit.sh" 2>&1); then ok "submit.sh again: $ids"; else bad "submit.sh again: $ids"; fi
read -r _ cache_id _ array_id _ join_id <<<"$ids"
wait_jobs "$cache_id,$array_id,$join_id" 600 || bad "slurm: second submission still queued"
if [ "$cache_id" != "-" ] && [ "$(job_states "$cache_id")" = " 1 COMPLETED" ] && ls "$plan"/cache/ghosttile-*.ugt >/dev/null 2>&1 &&
   [ "$(grep -l skipped "$plan"/logs/task_*.log | wc -l)" -eq "$tasks" ] && [ "$(job_states "$join_id")" = " 1 COMPLETED" ]; then
  ok "submit.sh again: the cache step rebuilt the Ghost Tile, all $tasks tasks skipped, the join ran"; else
  bad "submit.sh again: cache [$(job_states "$cache_id")] join [$(job_states "$join_id")]: $(tail -3 "$plan"/logs/*.log)"; fi

# 3. A second plan of the same scene (other regions, so another id) in which region 1 starts with a stale
#    output of the first plan and region 0 is killed mid-run, then requeued.
plan2="$tmp/plan2"
"$bin" plan "$scene" --out "$plan2" --memory-per-job 150M --threads-per-task 1 >"$tmp/plan2.out" 2>&1 || bad "plan 2: $(cat "$tmp/plan2.out")"
if [ "$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['id'] != json.load(open(sys.argv[2]))['id'])" "$plan/plan.json" "$plan2/plan.json")" = True ]; then
  ok "plan 2: another plan id"; else bad "plan 2: same id as plan 1"; fi
cp "$plan"/regions/region_0001.* "$plan2/regions/"
if "$bin" join "$plan2" -o "$tmp/x.glb" >"$tmp/join.out" 2>&1; then bad "join: accepted missing regions"; else
  grep -q "regions are missing" "$tmp/join.out" && ok "join: missing regions refused: $(head -c 160 "$tmp/join.out")" || bad "join missing: $(cat "$tmp/join.out")"; fi
array2=$(sbatch --parsable "$plan2/job.sbatch" 2>&1) || bad "sbatch plan 2: $array2"
array2=${array2%%;*}
killed=no
for _ in $(seq 600); do
  if grep -q "started" "$plan2/logs/task_0.log" 2>/dev/null; then
    pkill -9 -f -- "--plan $plan2 --task 0 " && killed=yes
    break
  fi
  sleep 0.05
done
sleep 1
if [ "$killed" = yes ] && ! grep -q " instances (" "$plan2/logs/task_0.log"; then ok "task 0 killed mid-run ($(job_states "${array2}_0"))"; else
  bad "task 0 was not killed mid-run (killed=$killed): $(cat "$plan2/logs/task_0.log" 2>/dev/null)"; fi
wait_jobs "$array2" 600 || bad "plan 2: tasks still queued"
scontrol requeue "${array2}_0" >"$tmp/requeue.out" 2>&1 || bad "requeue: $(cat "$tmp/requeue.out")"
# Slurm holds a requeued job back for a while (its begin time); a test need not wait for that.
scontrol update JobId="${array2}_0" StartTime=now >>"$tmp/requeue.out" 2>&1 || bad "requeue start: $(cat "$tmp/requeue.out")"
sleep 1
wait_jobs "$array2" 600 || bad "plan 2: requeued task still queued"
if [ "$(grep -c started "$plan2/logs/task_0.log")" -eq 2 ] && grep -q " instances (" "$plan2/logs/task_0.log"; then
  ok "task 0 requeued and ran to the end"; else bad "task 0 requeue: $(cat "$plan2/logs/task_0.log")"; fi
if grep -q "started" "$plan2/logs/task_1.log" && ! grep -q "skipped" "$plan2/logs/task_1.log"; then ok "task 1: a stale region of another plan is redone, not skipped"; else
  bad "task 1 stale: $(cat "$plan2/logs/task_1.log")"; fi
if "$bin" join "$plan2" -o "$tmp/world2.glb" >"$tmp/join2.out" 2>&1 && dump "$tmp/world2.glb" "$tmp/world2.txt" &&
   cmp -s "$tmp/single.txt" "$tmp/world2.txt"; then ok "join after the kill and requeue: equals the single process"; else
  bad "join 2: $(cat "$tmp/join2.out") $(diff "$tmp/single.txt" "$tmp/world2.txt" 2>&1 | head -3)"; fi
ls -a "$plan2/regions" | grep -q "\.tmp-" && bad "a temporary file was left behind: $(ls -a "$plan2/regions")" || ok "no half-written file left"

# 4. join refuses a region of another plan.
cp "$plan"/regions/region_0002.ugi "$plan2/regions/region_0002.ugi"
if "$bin" join "$plan2" >"$tmp/join3.out" 2>&1; then bad "join: accepted a region of another plan"; else
  grep -q "is from plan" "$tmp/join3.out" && ok "join: a region of another plan refused: $(head -c 200 "$tmp/join3.out")" || bad "join stale: $(cat "$tmp/join3.out")"; fi

# 5. A scene edited after its plan: the task refuses to run.
mkdir -p "$tmp/edit/scenes" && cp -r "$root/assets/models" "$tmp/edit/" && cp "$scene" "$tmp/edit/scenes/meadow.json"
"$bin" plan "$tmp/edit/scenes/meadow.json" --out "$tmp/plan3" --memory-per-job 1G >/dev/null 2>&1 || bad "plan 3"
sed -i 's/"seed": 1,/"seed": 2,/' "$tmp/edit/scenes/meadow.json"
out=$("$bin" instantiate --plan "$tmp/plan3" --task 0 2>&1); rc=$?
if [ $rc -eq 1 ] && grep -q "changed since plan" <<<"$out"; then ok "task: a scene edited since the plan is refused"; else bad "task on edited scene (exit $rc): $out"; fi
# A hand-edited plan is refused by its id.
sed -i '0,/"seed": [0-9]*/s//"seed": 99/' "$tmp/plan3/plan.json"
out=$("$bin" join "$tmp/plan3" 2>&1); rc=$?
if [ $rc -eq 1 ] && grep -q "/id: does not match" <<<"$out"; then ok "join: a hand-edited plan is refused"; else bad "edited plan (exit $rc): $out"; fi
out=$("$bin" plan "$scene" --out "$tmp/plan4" --memory-per-job 1M 2>&1); rc=$?
if [ $rc -eq 1 ] && grep -q "needs more than" <<<"$out"; then ok "plan: a budget too small for one chunk is refused: $(tr '\r' '\n' <<<"$out" | grep -m1 'needs more than' | head -c 200)"; else bad "plan tiny budget (exit $rc): $out"; fi

echo "passed $passed, failed $failed"
[ "$failed" -eq 0 ]
