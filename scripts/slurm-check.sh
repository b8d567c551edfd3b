#!/usr/bin/env bash
# A real check against Slurm: installs Debian's slurm-wlm and munge, starts a single-node cluster
# on this machine, submits a pipeline as a job array of shards plus the dependent merge job
# (pipelines/slurm/submit.sh, exactly as the README says), waits, and compares the merged tables
# with a plain ensemble run of the same pipeline.
#   scripts/slurm-check.sh [pipeline, default pipelines/paper-100.toml] [shards, default 8]
# Needs root (packages, daemons). Work folder: /tmp/stickslip-slurm (override with WORK=…).
set -euo pipefail
cd "$(dirname "$0")/.."
pipeline=${1:-pipelines/paper-100.toml}
shards=${2:-8}
work=${WORK:-/tmp/stickslip-slurm}
host=$(hostname -s)
cpus=$(nproc)

say() { printf '\n== %s\n' "$*"; }

say "packages"
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    apt-get update -qq >/dev/null
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
fi
dpkg-query -W slurm-wlm munge

say "stickslip"
cargo build --release -q -p stickslip
bin=$(realpath target/release/stickslip)

say "munge"
mkdir -p /etc/munge /run/munge /var/lib/munge /var/log/munge
[ -s /etc/munge/munge.key ] || dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key status=none
chown -R munge:munge /etc/munge /run/munge /var/lib/munge /var/log/munge 2>/dev/null || true
chmod 0700 /etc/munge && chmod 0400 /etc/munge/munge.key
pgrep -x munged >/dev/null || su -s /bin/sh munge -c /usr/sbin/munged 2>/dev/null || /usr/sbin/munged --force
munge -n | unmunge >/dev/null && echo "munge works"

say "slurm (single node $host, $cpus CPUs)"
mkdir -p /etc/slurm /var/spool/slurmd /var/spool/slurmctld /var/log/slurm
mem=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.8 }' /proc/meminfo)
cat > /etc/slurm/slurm.conf <<CONF
ClusterName=stickslip
SlurmctldHost=$host
AuthType=auth/munge
SlurmUser=root
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
DefMemPerCPU=1000
ReturnToService=2
MpiDefault=none
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmdSpoolDir=/var/spool/slurmd
StateSaveLocation=/var/spool/slurmctld
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=check Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
pkill -x slurmctld 2>/dev/null || true
pkill -x slurmd 2>/dev/null || true
sleep 1
slurmctld -c
slurmd
for _ in $(seq 60); do
    state=$(sinfo -h -o %T 2>/dev/null | head -n1 || true)
    [ "$state" = "idle" ] && break
    sleep 1
done
sinfo
[ "$state" = "idle" ] || { echo "the node did not come up ($state)"; tail -n 20 /var/log/slurm/*.log; exit 1; }

say "submit $pipeline as $shards shards + merge"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
start=$(date +%s.%N)
STICKSLIP=$bin "$OLDPWD/pipelines/slurm/submit.sh" "$OLDPWD/$pipeline" "$work/out" "$shards" 1 | tee submit.txt
merge_job=$(sed -n 's/.*merge job \([0-9]*\).*/\1/p' submit.txt)
[ -n "$merge_job" ] || { echo "could not read the merge job id"; exit 1; }
for _ in $(seq 3600); do
    squeue -h -j "$merge_job" 2>/dev/null | grep -q . || break
    sleep 1
done
end=$(date +%s.%N)
cat slurm-stickslip-merge-*.out
grep -q "^merged" slurm-stickslip-merge-*.out || { echo "merge job did not succeed"; tail -n 5 slurm-stickslip-*.out; exit 1; }
slurm_s=$(echo "$end - $start" | bc)

say "plain ensemble of the same pipeline"
start=$(date +%s.%N)
"$bin" pipeline "$OLDPWD/$pipeline" --out "$work/plain" --quiet > plain.txt
head -n 1 plain.txt
end=$(date +%s.%N)
plain_s=$(echo "$end - $start" | bc)

say "compare"
"$bin" compare "$work/out" "$work/plain"
printf 'Slurm array of %s shards + merge: %.1f s wall; plain ensemble: %.1f s (same machine, %s CPUs)\n' \
    "$shards" "$slurm_s" "$plain_s" "$cpus"
echo "slurm check passed"
