#!/bin/bash
# Submits a stickslip ensemble as a Slurm job array of N shards and a merge job that runs once
# every shard has succeeded.
#   pipelines/slurm/submit.sh <pipeline.toml> <shared output folder> <N shards> [cpus per task]
# Prints the two job ids. The output folder must be on a file system every node sees.
set -euo pipefail
pipeline=$(realpath "$1"); out=$(realpath -m "$2"); shards=$3; cpus=${4:-1}
here=$(dirname "$(realpath "$0")")
export PIPELINE=$pipeline OUT=$out SHARDS=$shards STICKSLIP=${STICKSLIP:-stickslip}
array=$(sbatch --parsable --array=1-"$shards" --cpus-per-task="$cpus" --export=ALL "$here/ensemble.sbatch")
merge=$(sbatch --parsable --dependency=afterok:"$array" --export=ALL "$here/merge.sbatch")
echo "array job $array ($shards shards), merge job $merge → $out"
