#!/usr/bin/env bash
# svbrdf-render --slurm on a real Slurm cluster of one node: munged, slurmctld and slurmd started here
# with a configuration written for the test (loopback only, free ports, every file in a temporary
# folder), a 4-tile render submitted through `svbrdf-render --slurm submit`, and the merged EXR and PNG
# compared value for value with one render of the whole frame; and two frames of an animated camera,
# as tiles merged and as frames whole, compared with the frames rendered on one machine; and a small
# LOD comparison in 2 parts through `svbrdf-lod-report --slurm submit`, its assembled report's images
# and numbers compared byte for byte with the report of one process. Skips (exit 77) without Slurm and munge
# (Debian: slurm-wlm, munge) or without root (slurmd starts the tasks as their user). Every daemon is
# stopped on the way out, whatever happened.
#   slurm_farm_test.sh SVBRDF_RENDER SCENE.gltf SVBRDF_LOD_REPORT
set -u
render=$(realpath "$1")
scene=$(realpath "$2")
lod_report=$(realpath "$3")

for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo idiff python3; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "slurm test skipped: $tool is not installed (Debian: apt-get install slurm-wlm munge)"
    exit 77
  fi
done
if [[ $(id -u) -ne 0 ]]; then
  echo "slurm test skipped: it must run as root to start slurmd"
  exit 77
fi

dir=$(mktemp -d /tmp/svbrdf-slurm.XXXXXX)
pids=()
teardown() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null; done
  if [[ $status -ne 0 ]]; then
    for log in "$dir"/*.log "$dir"/farm/*.log; do [[ -f $log ]] && { echo "== $log"; tail -n 20 "$log"; }; done
  fi
  rm -rf "$dir"
  exit "$status"
}
trap teardown EXIT
fail() { echo "slurm test: $*" >&2; exit 1; }

# Two ports nothing listens on, from the kernel (bound to 0, then released).
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')

mkdir -p "$dir/state" "$dir/spool" "$dir/farm"
mungekey --create --keyfile="$dir/munge.key" || fail "mungekey failed"
chmod 600 "$dir/munge.key"
# --force: munged refuses by default a socket folder others can write into (/tmp).
munged --foreground --force --socket="$dir/munge.sock" --key-file="$dir/munge.key" --log-file="$dir/munged.log" \
  --pid-file="$dir/munged.pid" --seed-file="$dir/munged.seed" >"$dir/munged.out" 2>&1 &
pids+=($!)

# CPUs=8 whatever the machine has (config_overrides: slurmd takes the configured counts, not the
# hardware's): the tasks are small and mostly start-up, and eight at a time keep the test short.
cat >"$dir/slurm.conf" <<CONF
ClusterName=svbrdftest
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmdParameters=config_overrides
NodeName=localhost NodeAddr=127.0.0.1 CPUs=8 RealMemory=256 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$dir/slurm.conf
for _ in $(seq 50); do [[ -S $dir/munge.sock ]] && break; sleep 0.1; done
slurmctld -D -i -f "$SLURM_CONF" >"$dir/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N localhost >"$dir/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 60); do
  [[ $(sinfo -h -o %T 2>/dev/null) == idle ]] && break
  sleep 0.5
done
[[ $(sinfo -h -o %T 2>/dev/null) == idle ]] || fail "the node did not come up: $(sinfo 2>&1)"

# An animated camera for --frames: the sample's box, seen from a rig whose translation moves
# (LINEAR) and a camera under it that turns (LINEAR rotation, by slerp), keys 0 and 1 s; the
# animation's keys in a second buffer, a data URI. Its folder's name has a space.
mkdir -p "$dir/anim scene"
cp "$(dirname "$scene")"/* "$dir/anim scene/"
python3 - "$scene" "$dir/anim scene/animated.gltf" <<'PY' || fail "the animated scene was not written"
import base64, json, math, struct, sys
g = json.load(open(sys.argv[1]))
s = math.sin(math.radians(15)); c = math.cos(math.radians(15))  # a 30-degree turn about +Y
data = struct.pack("<2f", 0, 1) + struct.pack("<6f", 0, 0, 3, 1.5, 0.5, 3) + struct.pack("<8f", 0, 0, 0, 1, 0, s, 0, c)
g["buffers"].append({"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()})
b = len(g["buffers"]) - 1
v = len(g["bufferViews"])
g["bufferViews"] += [{"buffer": b, "byteOffset": 0, "byteLength": 8}, {"buffer": b, "byteOffset": 8, "byteLength": 24},
                     {"buffer": b, "byteOffset": 32, "byteLength": 32}]
a = len(g["accessors"])
g["accessors"] += [{"bufferView": v, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                   {"bufferView": v + 1, "componentType": 5126, "count": 2, "type": "VEC3"},
                   {"bufferView": v + 2, "componentType": 5126, "count": 2, "type": "VEC4"}]
n = len(g["nodes"])
g["nodes"] += [{"name": "rig", "children": [n + 1], "translation": [0, 0, 3]}, {"camera": 0}]
g["scenes"][0]["nodes"].append(n)
g["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.01}}]
g["animations"] = [{"channels": [{"sampler": 0, "target": {"node": n, "path": "translation"}},
                                 {"sampler": 1, "target": {"node": n + 1, "path": "rotation"}}],
                    "samplers": [{"input": a, "output": a + 1}, {"input": a, "output": a + 2}]}]
json.dump(g, open(sys.argv[2], "w"))
PY

# The cluster's tasks write the MIP cache too: the build tree's, as the suites'.
args=("$scene" --res 48x32 --spp 6 --seed 11 --aov --quiet)
"$render" "${args[@]}" -o "$dir/single.exr" || fail "the single-machine render failed"
# Frames 6 and 7 (t = 0.25 and 0.29 s), on one machine: single-frames.0006.exr and .0007.exr.
frame_args=("$dir/anim scene/animated.gltf" --res 40x30 --spp 4 --seed 5 --frames 6-7 --quiet)
"$render" "${frame_args[@]}" -o "$dir/single-frames.exr" || fail "the single-machine render of frames 6-7 failed"
# The LOD comparison's two farthest shots of one case and light, in one process.
lod_args=(--spp 4 --case printed-paper-text --light sun-0 --view head-on --min-distance 4096 -q)
"$lod_report" "${lod_args[@]}" -o "$dir/lod single" || fail "the single-process LOD report failed"

# Three submissions at once: the frame in 4 tiles; frames 6-7 in 2 tiles each, merged (the output's
# name with a # run, in a folder whose name has a space, as the batch scripts must quote them); and
# frames 6-7 a task each, written by the tasks.
farm="$dir/farm"
mkdir -p "$farm/seq tiles" "$farm/seq whole"
cd "$farm" || fail "no farm folder"
submit() {  # FOLDER ARGS...: submits from FOLDER, prints the id of the job that finishes last
  local folder=$1 out
  shift
  out=$(cd "$folder" && "$render" "$@" --slurm submit) || fail "the submission failed: $*"
  echo "$out" >&2
  [[ $out =~ (merge|frames):\ job\ ([0-9]+) ]] || fail "no job id in: $out"
  echo "${BASH_REMATCH[2]}"
}
tiles_job=$(submit "$farm" "${args[@]}" -o out.exr --slurm-tiles 4) || exit 1
seq_tiles_job=$(submit "$farm/seq tiles" "${frame_args[@]}" -o 'seq ##.exr' --slurm-tiles 2) || exit 1
seq_whole_job=$(submit "$farm/seq whole" "${frame_args[@]}" -o seq.exr) || exit 1
lod_out=$(cd "$farm" && "$lod_report" "${lod_args[@]}" -o "lod report" --slurm-parts 2 --slurm submit) ||
  fail "the LOD submission failed"
echo "$lod_out" >&2
[[ $lod_out =~ assemble:\ job\ ([0-9]+) ]] || fail "no job id in: $lod_out"
jobs=("$tiles_job" "$seq_tiles_job" "$seq_whole_job" "${BASH_REMATCH[1]}")
# Done when the last jobs have left the queue (a generous limit: tasks start within seconds).
for _ in $(seq 240); do
  [[ -z $(squeue -h -j "$(IFS=,; echo "${jobs[*]}")" 2>/dev/null) ]] && break
  sleep 0.5
done
[[ -z $(squeue -h -j "$(IFS=,; echo "${jobs[*]}")" 2>/dev/null) ]] || fail "the jobs did not finish: $(squeue 2>&1)"

# Every value of every channel (the files' bytes differ: OpenImageIO stamps the EXR with the time).
# idiff: exit 0 only when no difference exceeds the thresholds, here 0.
same() {  # EXPECTED ACTUAL WHAT
  [[ -f $2 ]] || fail "$3: $2 was not written"
  idiff -q -a -fail 0 -warn 0 "$1" "$2" || fail "$3: $2 differs from the single-machine render's $1"
}
for f in exr png; do same "$dir/single.$f" out.$f "the merged frame"; done
for i in 0 1 2 3; do [[ -f out.tile-$i-of-4.exr ]] || fail "tile $i is missing"; done
for frame in 0006 0007; do
  for f in exr png; do
    same "$dir/single-frames.$frame.$f" "seq tiles/seq ${frame#00}.$f" "frame $frame merged from 2 tiles"
    same "$dir/single-frames.$frame.$f" "seq whole/seq.$frame.$f" "frame $frame rendered whole by a task"
  done
done
idiff -q -a "$dir/single-frames.0006.exr" "$dir/single-frames.0007.exr" >/dev/null &&
  fail "frames 6 and 7 are the same image: the camera did not move"
# The LOD report assembled from 2 parts: every PNG and results.json the bytes of the single run's.
[[ -f "lod report/index.html" ]] || fail "the LOD report was not assembled: $(cat "lod report.parts"/*.log 2>/dev/null | tail -n 5)"
[[ -f "lod report.parts/lod-part-1-of-2.json" ]] || fail "the LOD report's part 1 of 2 is missing"
n=0
for png in "$dir/lod single/img/"*.png; do
  cmp -s "$png" "lod report/img/${png##*/}" || fail "the assembled LOD report's ${png##*/} differs from the single run's"
  n=$((n + 1))
done
[[ $n -gt 0 && $(ls "lod report/img" | wc -l) -eq $n ]] || fail "the assembled LOD report has other images than the single run's"
cmp -s "$dir/lod single/results.json" "lod report/results.json" || fail "the assembled LOD report's numbers differ"
echo "slurm test: 4 tiles, and frames 6-7 as 2 tiles each and whole, rendered by Slurm, and a LOD report in 2 parts: identical to the single runs"
