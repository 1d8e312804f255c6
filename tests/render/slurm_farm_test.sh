#!/usr/bin/env bash
# svbrdf-render --slurm on a real Slurm cluster of one node: munged, slurmctld and slurmd started here
# with a configuration written for the test (loopback only, free ports, every file in a temporary
# folder), a 4-tile render submitted through `svbrdf-render --slurm submit`, and the merged EXR and PNG
# compared value for value with one render of the whole frame. Skips (exit 77) without Slurm and munge
# (Debian: slurm-wlm, munge) or without root (slurmd starts the tasks as their user). Every daemon is
# stopped on the way out, whatever happened.
#   slurm_farm_test.sh SVBRDF_RENDER SCENE.gltf
set -u
render=$(realpath "$1")
scene=$(realpath "$2")

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
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=256 State=UNKNOWN
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

# The cluster's tasks write the MIP cache too: the build tree's, as the suites'.
args=("$scene" --res 48x32 --spp 6 --seed 11 --aov --quiet)
"$render" "${args[@]}" -o "$dir/single.exr" || fail "the single-machine render failed"

cd "$dir/farm" || fail "no farm folder"
submitted=$("$render" "${args[@]}" -o out.exr --slurm submit --slurm-tiles 4) || fail "the submission failed"
echo "$submitted"
[[ $submitted =~ tiles:\ job\ ([0-9]+).*merge:\ job\ ([0-9]+) ]] || fail "no job ids in: $submitted"
merge_job=${BASH_REMATCH[2]}
# Done when the merge job has left the queue (a generous limit: tasks start within seconds).
for _ in $(seq 240); do
  [[ -z $(squeue -h -j "$merge_job" 2>/dev/null) ]] && break
  sleep 0.5
done
[[ -z $(squeue -h -j "$merge_job" 2>/dev/null) ]] && [[ -f out.exr ]] || fail "the merge did not finish: $(squeue 2>&1)"

# Every value of every channel (the files' bytes differ: OpenImageIO stamps the EXR with the time).
# idiff: exit 0 only when no difference exceeds the thresholds, here 0.
for f in exr png; do
  idiff -q -a -fail 0 -warn 0 "$dir/single.$f" "out.$f" || fail "the merged $f differs from the single-machine render's"
done
for i in 0 1 2 3; do [[ -f out.tile-$i-of-4.exr ]] || fail "tile $i is missing"; done
echo "slurm test: 4 tiles rendered by Slurm and merged: EXR and PNG identical to the single render's"
