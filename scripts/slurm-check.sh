#!/usr/bin/env bash
# A real check against Slurm, self-contained: it starts a private single-node cluster (its own
# munged, slurmctld and slurmd, with their own configuration, key, socket, spool, state, logs and
# free high ports, all under one work folder), submits a pipeline as a job array of shards plus
# the dependent merge job (pipelines/slurm/submit.sh, exactly as docs/guide/ensembles.md says), waits, and
# compares the merged tables with a plain ensemble run of the same pipeline.
#
# It touches nothing outside its work folder except, if they are missing and only after saying
# so, installing Debian's slurm-wlm and munge, which it purges again when it exits (every package
# the installation added, dependencies included; KEEP_PACKAGES=1 keeps them). It refuses, before
# changing anything, to run where a Slurm it did not create is present (a slurm.conf in a system
# location, SLURM_CONF set, or a running Slurm daemon): that is a real cluster's node and the
# check does not belong there. The daemons it starts are stopped by their process ids when it
# exits, on success or failure, and so are the job steps of its own slurmd (told by the
# configuration in their environment), never a process picked by its name alone.
#
# Needs root (slurmd launches the jobs). The binary: $STICKSLIP, else target/release/stickslip.
# Work folder: a new one from `mktemp -d` (WORK=… names a folder of your own instead: it must
# not exist yet, or be one this check made). Waits at most TIMEOUT seconds (default 3600) for
# the jobs.
set -euo pipefail

usage="usage: scripts/slurm-check.sh [pipeline, default pipelines/paper-100.toml] [shards, default 8]"
case ${1:-} in
    -h | --help) echo "$usage"; exit 0 ;;
    -*) echo "$usage" >&2; exit 2 ;;
esac
[ $# -le 2 ] || { echo "$usage" >&2; exit 2; }

cd "$(dirname "$0")/.."
repo=$PWD
pipeline=${1:-pipelines/paper-100.toml}
shards=${2:-8}
work=${WORK:-}
timeout_s=${TIMEOUT:-3600}
marker=.stickslip-slurm-check

say() { printf '\n== %s\n' "$*"; }
die() { printf 'slurm check failed: %s\n' "$*" >&2; exit 1; }

# ---- arguments and prerequisites (nothing is changed yet) ----
[ -f "$pipeline" ] || die "no pipeline file $pipeline"
pipeline=$(realpath "$pipeline")
[[ $shards =~ ^[1-9][0-9]*$ ]] || die "shards must be a positive integer, not '$shards'"
[[ $timeout_s =~ ^[1-9][0-9]*$ ]] || die "TIMEOUT must be a positive number of seconds"
bin=${STICKSLIP:-target/release/stickslip}
[ -x "$bin" ] || die "no stickslip binary at $bin: build it (cargo build --release -p stickslip) or set STICKSLIP"
bin=$(realpath "$bin")
if [ -n "$work" ]; then
    [[ $work = /* ]] || work=$PWD/$work
    case $work in / | /tmp | /root | /home | /etc | /var | /usr) die "WORK=$work is not a folder of its own" ;; esac
    [ -L "$work" ] && die "WORK=$work is a symbolic link: give a real folder"
fi

# Live processes (zombies aside) named $1 exactly, as "pid command line" lines.
procs() {
    local pid
    for pid in $(pgrep -x "$1" || true); do
        [[ $(ps -o stat= -p "$pid" 2>/dev/null) == Z* ]] && continue
        printf '%s %s\n' "$pid" "$(tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null)"
    done
}

# Refuses, with the reasons, when a Slurm the check did not create is present, or the work folder
# is not the check's own. Changes nothing.
preflight() {
    local reasons=() f name line
    for f in /etc/slurm/slurm.conf /etc/slurm-llnl/slurm.conf /usr/local/etc/slurm.conf; do
        [ -e "$f" ] && reasons+=("a Slurm configuration exists: $f")
    done
    [ -n "${SLURM_CONF:-}" ] && reasons+=("SLURM_CONF is set ($SLURM_CONF)")
    for name in slurmctld slurmd slurmdbd slurmstepd slurmrestd sackd; do
        while IFS= read -r line; do
            [ -n "$line" ] || continue
            if [ -n "$work" ] && [[ $line == *"$work/"* ]]; then
                reasons+=("a $name left over from an earlier check in $work runs (stop it: kill ${line%% *}): $line")
            else
                reasons+=("a $name the check did not start runs: $line")
            fi
        done < <(procs "$name")
    done
    while IFS= read -r line; do
        [ -n "$work" ] && [[ $line == *"$work/"* ]] && reasons+=("a munged left over from an earlier check in $work runs (stop it: kill ${line%% *})")
    done < <(procs munged)
    if [ -n "$work" ] && [ -e "$work" ] && [ ! -e "$work/$marker" ] && [ -n "$(ls -A "$work" 2>/dev/null)" ]; then
        reasons+=("the work folder $work exists and was not made by this check (set WORK to a new folder)")
    fi
    if [ ${#reasons[@]} -gt 0 ]; then
        echo "slurm check refused: this machine has a Slurm the check did not create, or its work folder is taken." >&2
        printf '  - %s\n' "${reasons[@]}" >&2
        echo "Nothing was changed. Run the check on a machine without Slurm (a VM or container)." >&2
        exit 1
    fi
}

say "preflight"
preflight
# Root only after the refusals above: they must reach whoever runs it, root or not.
[ "$(id -u)" = 0 ] || die "needs root (slurmd runs the jobs; packages may be installed)"
echo "no Slurm configuration or daemon present"
while IFS= read -r line; do
    [ -n "$line" ] && echo "note: a munged the check did not start runs ($line); left alone, the check uses its own"
done < <(procs munged)

say "packages"
missing=()
for cmd in munged munge unmunge slurmctld slurmd sbatch squeue sinfo scancel; do
    command -v "$cmd" >/dev/null || missing+=("$cmd")
done
installed=() # the packages this check installed, purged again on exit
installed_packages() { dpkg-query -W -f '${db:Status-Abbrev} ${Package}\n' 2>/dev/null | awk '$1 ~ /^ii/ { print $2 }' | sort; }
purge_installed() {
    [ ${#installed[@]} -gt 0 ] || return 0
    if [ "${KEEP_PACKAGES:-0}" = 1 ]; then
        echo "KEEP_PACKAGES=1: leaving the packages this check installed: ${installed[*]}"
        return 0
    fi
    echo "purging the ${#installed[@]} packages this check installed: ${installed[*]}"
    DEBIAN_FRONTEND=noninteractive apt-get purge -y -qq "${installed[@]}" >/dev/null ||
        { echo "could not purge: ${installed[*]} (apt-get purge them by hand)" >&2; return 1; }
}
trap 'rc=$?; purge_installed || rc=1; exit $rc' EXIT
if [ ${#missing[@]} -gt 0 ]; then
    echo "missing ${missing[*]}: installing Debian's slurm-wlm and munge (purged again when the check ends):"
    echo "  apt-get update && apt-get install -y --no-install-recommends slurm-wlm munge"
    before=$(installed_packages)
    apt-get update -qq >/dev/null
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null ||
        { mapfile -t installed < <(comm -13 <(echo "$before") <(installed_packages)); die "apt-get install failed"; }
    mapfile -t installed < <(comm -13 <(echo "$before") <(installed_packages))
    echo "installed ${#installed[@]} packages: ${installed[*]}"
    preflight # the packages must not have brought a Slurm of their own
fi
dpkg-query -W slurm-wlm munge 2>/dev/null || true

# ---- from here on everything lives in $work and is undone on exit ----
if [ -z "$work" ]; then
    work=$(mktemp -d /tmp/stickslip-slurm.XXXXXX) # new, empty and ours (mode 0700): no race on its name
elif [ -e "$work" ]; then
    [ -e "$work/$marker" ] || [ -z "$(ls -A "$work")" ] || die "WORK=$work holds files this check did not make"
    find "$work" -mindepth 1 -delete # a folder this check made: emptied in place, never replaced
else
    mkdir -m 0700 "$work"
fi
echo "work folder $work"
host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.8 }' /proc/meminfo)
etc=$work/etc spool=$work/spool state=$work/state log=$work/log run=$work/run mungedir=$work/munge
export SLURM_CONF=$etc/slurm.conf

# Is TCP port $1 unused (no socket of any state bound to it, IPv4 or IPv6)?
port_free() {
    local hex
    hex=$(printf '%04X' "$1")
    ! awk -v p=":$hex" 'FNR > 1 && substr($2, length($2) - 4) == p { found = 1 } END { exit !found }' \
        /proc/net/tcp /proc/net/tcp6 2>/dev/null
}
ctld_port=
for _ in $(seq 100); do
    p=$((40000 + RANDOM % 20000))
    if port_free "$p" && port_free $((p + 1)); then ctld_port=$p; break; fi
done
[ -n "$ctld_port" ] || die "found no two free adjacent ports in 40000–60000"
slurmd_port=$((ctld_port + 1))

# The job steps of this check's own slurmd: slurmstepd processes whose environment holds this
# check's SLURM_CONF (inherited from its slurmd), whatever else runs on the machine.
own_steps() {
    local pid
    for pid in $(pgrep -x slurmstepd || true); do
        tr '\0' '\n' <"/proc/$pid/environ" 2>/dev/null | grep -qxF "SLURM_CONF=$SLURM_CONF" && echo "$pid"
    done
}
pids=() names=() job_ids=()
cleanup() {
    local rc=$? i pid left=()
    trap - EXIT INT TERM
    if [ ${#job_ids[@]} -gt 0 ] && [ $rc -ne 0 ]; then
        scancel "${job_ids[@]}" 2>/dev/null || true
        for _ in $(seq 20); do squeue -h -j "$(IFS=,; echo "${job_ids[*]}")" 2>/dev/null | grep -q . || break; sleep 0.5; done
    fi
    # Job steps this check's slurmd started (told by their SLURM_CONF), by process id.
    for pid in $(own_steps); do
        kill "$pid" 2>/dev/null || true
    done
    for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
        pid=${pids[i]}
        if ! kill -TERM "$pid" 2>/dev/null; then
            echo "${names[i]} (pid $pid) had already exited"
            wait "$pid" 2>/dev/null || true
            continue
        fi
        for _ in $(seq 40); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
        if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid" 2>/dev/null || true; fi
        wait "$pid" 2>/dev/null || true
        if kill -0 "$pid" 2>/dev/null; then left+=("${names[i]} $pid"); else echo "stopped ${names[i]} (pid $pid)"; fi
    done
    rm -rf "$mungedir" "$run" # the private key and sockets
    if [ ${#left[@]} -gt 0 ]; then
        echo "could not stop: ${left[*]}" >&2
        rc=1
    elif [ ${#pids[@]} -gt 0 ]; then
        echo "cleaned up: no daemon of the check runs; logs and outputs in $work"
    fi
    if [ $rc -ne 0 ] && [ -d "$log" ]; then
        for f in "$log"/* "$work"/job/slurm-*.out; do
            [ -s "$f" ] && { echo "--- tail of $f"; tail -n 15 "$f"; }
        done >&2
    fi
    purge_installed || rc=1
    exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# Starts a daemon in the foreground of a background job and remembers its pid.
start() {
    local name=$1
    shift
    "$@" >"$log/$name.out" 2>&1 &
    pids+=("$!") names+=("$name")
    echo "started $name (pid $!)"
}

say "work folder $work"
mkdir "$etc" "$spool" "$state" "$log" "$run" "$mungedir" "$work/job"
touch "$work/$marker"
chmod 0700 "$mungedir"
chmod 0755 "$work" "$run" # munged wants its socket folder reachable by every user
echo "ports: slurmctld $ctld_port, slurmd $slurmd_port (both were free)"

say "munge (private key and socket)"
socket=$run/munge.socket
dd if=/dev/urandom bs=1024 count=1 of="$mungedir/munge.key" status=none
chmod 0400 "$mungedir/munge.key"
start munged munged --foreground --socket="$socket" --key-file="$mungedir/munge.key" \
    --pid-file="$run/munged.pid" --log-file="$log/munged.log" --seed-file="$mungedir/munged.seed"
for _ in $(seq 40); do [ -S "$socket" ] && break; sleep 0.25; done
[ -S "$socket" ] || die "munged did not create its socket $socket"
munge --socket="$socket" -n | unmunge --socket="$socket" >/dev/null || die "munge does not work"
echo "munge works"

say "slurm (single node $host, $cpus CPUs)"
cat >"$SLURM_CONF" <<CONF
# Written by scripts/slurm-check.sh for its private single-node cluster; removed with $work.
ClusterName=stickslip-check
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
SlurmUser=root
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
DefMemPerCPU=1000
ReturnToService=2
MpiDefault=none
MailProg=/bin/true
SlurmctldPidFile=$run/slurmctld.pid
SlurmdPidFile=$run/slurmd.pid
SlurmdSpoolDir=$spool
StateSaveLocation=$state
SlurmctldLogFile=$log/slurmctld.log
SlurmdLogFile=$log/slurmd.log
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=check Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
start slurmctld slurmctld -D -c -f "$SLURM_CONF"
start slurmd slurmd -D -f "$SLURM_CONF" -N "$host"
state=
for _ in $(seq 60); do
    state=$(sinfo -h -o %T 2>/dev/null | head -n1 || true)
    [ "$state" = "idle" ] && break
    sleep 1
done
sinfo
[ "$state" = "idle" ] || die "the node did not come up (state '${state:-none}')"

say "submit $pipeline as $shards shards + merge"
cd "$work/job"
start_t=$(date +%s.%N)
STICKSLIP=$bin "$repo/pipelines/slurm/submit.sh" "$pipeline" "$work/out" "$shards" 1 | tee submit.txt
array_job=$(sed -n 's/^array job \([0-9]*\).*/\1/p' submit.txt)
merge_job=$(sed -n 's/.*merge job \([0-9]*\).*/\1/p' submit.txt)
{ [ -n "$array_job" ] && [ -n "$merge_job" ]; } || die "could not read the job ids from submit.sh"
job_ids=("$array_job" "$merge_job")
waited=0
while squeue -h -j "$array_job,$merge_job" 2>/dev/null | grep -q .; do
    reason=$(squeue -h -j "$merge_job" -o %r 2>/dev/null || true)
    [ "$reason" = DependencyNeverSatisfied ] && die "a shard failed, the merge job will never run"
    [ "$waited" -lt "$timeout_s" ] || die "the jobs did not finish in $timeout_s s"
    sleep 1
    waited=$((waited + 1))
done
end_t=$(date +%s.%N)
merge_out=slurm-stickslip-merge-$merge_job.out
[ -f "$merge_out" ] || die "the merge job wrote no $merge_out"
cat "$merge_out"
grep -q "^merged" "$merge_out" || die "the merge job did not succeed"
slurm_s=$(awk -v a="$start_t" -v b="$end_t" 'BEGIN { print b - a }')

say "plain ensemble of the same pipeline"
start_t=$(date +%s.%N)
"$bin" pipeline "$pipeline" --out "$work/plain" --quiet >plain.txt
end_t=$(date +%s.%N)
head -n 1 plain.txt
plain_s=$(awk -v a="$start_t" -v b="$end_t" 'BEGIN { print b - a }')

say "compare"
"$bin" compare "$work/out" "$work/plain"
printf 'Slurm array of %s shards + merge: %.1f s wall; plain ensemble: %.1f s (same machine, %s CPUs)\n' \
    "$shards" "$slurm_s" "$plain_s" "$cpus"

# With SPLIT=N: one pipeline (SPLIT_PIPELINE, default TPV5 at 500 m) with every seed split over N
# MPI ranks as one job of pipelines/slurm/split.sbatch, launched by SPLIT_LAUNCH (default srun with
# the PMIx plugin), against a plain run. Needs a stickslip built with `--features mpi`.
if [ -n "${SPLIT:-}" ]; then
    split_pipeline=${SPLIT_PIPELINE:-pipelines/tpv5-500m.toml}
    launch=${SPLIT_LAUNCH:-srun --mpi=pmix}
    say "submit $split_pipeline as one job of $SPLIT MPI ranks ($launch, pipelines/slurm/split.sbatch)"
    srun --mpi=list 2>&1 | tr '\n' ' ' | sed 's/^/srun --mpi=list: /'
    echo
    split_job=$(PIPELINE=$repo/$split_pipeline OUT=$work/split STICKSLIP=$bin LAUNCH=$launch \
        sbatch --parsable --ntasks="$SPLIT" --cpus-per-task=1 --export=ALL "$repo/pipelines/slurm/split.sbatch")
    job_ids+=("$split_job")
    start_t=$(date +%s.%N)
    waited=0
    while squeue -h -j "$split_job" 2>/dev/null | grep -q .; do
        [ "$waited" -lt "$timeout_s" ] || die "the split job did not finish in $timeout_s s"
        sleep 1
        waited=$((waited + 1))
    done
    end_t=$(date +%s.%N)
    split_out=slurm-stickslip-split-$split_job.out
    [ -f "$split_out" ] || die "the split job wrote no $split_out"
    cat "$split_out"
    grep -q "each seed split over $SPLIT MPI ranks" "$split_out" || die "the job did not split its seeds over $SPLIT ranks"
    split_s=$(awk -v a="$start_t" -v b="$end_t" 'BEGIN { print b - a }')
    start_t=$(date +%s.%N)
    "$bin" pipeline "$repo/$split_pipeline" --out "$work/split-plain" --quiet >/dev/null
    end_t=$(date +%s.%N)
    "$bin" compare "$work/split" "$work/split-plain"
    printf 'Slurm job of %s MPI ranks: %.1f s wall; one process: %.1f s\n' "$SPLIT" "$split_s" \
        "$(awk -v a="$start_t" -v b="$end_t" 'BEGIN { print b - a }')"
fi
echo "slurm check passed"
