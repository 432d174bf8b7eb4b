#!/usr/bin/env bash
# An experiment on a Slurm cluster: one job array of N shards (`hybridlab run --shard i/N`), then
# one job that merges them once every shard has succeeded (sbatch --dependency=afterok).
#
#   experiments/slurm_array.sh CONFIG N [RESULTS]     submit; prints "ARRAY_JOB_ID MERGE_JOB_ID"
#
# RESULTS (default results/<config name>) gets shards/0 .. shards/N-1, logs/ and, from the merge
# job, merged/: the result set `hybridlab report` reads. The binary is $HYBRIDLAB (default
# build/hybridlab of this checkout); the reference cache is $HYBRIDLAB_CACHE (default
# RESULTS/reference-cache). RESULTS and the cache must be on a file system every node sees.
# Partition, time limit, account, ...: sbatch's own variables (SBATCH_PARTITION,
# SBATCH_TIMELIMIT, SBATCH_ACCOUNT) or options after `--`, given to both jobs:
#   SBATCH_TIMELIMIT=4:00:00 experiments/slurm_array.sh experiments/configs/stability.toml 8 -- --partition=cpu
#
# A task that is requeued (node failure, preemption) resumes its shard: `--resume` skips the runs
# it recorded. Tasks that need the same reference share the cache safely: every file is written
# under a temporary name unique to its process and host and renamed into place (atomic_file.h).
# The script runs itself as the array task (--task) and as the merge job (--merge).
#SBATCH --job-name=hybridlab
#SBATCH --cpus-per-task=8
#SBATCH --requeue
set -euo pipefail

usage() {
  echo "usage: experiments/slurm_array.sh CONFIG N [RESULTS] [-- SBATCH_OPTIONS...]" >&2
  exit 2
}

case "${1:-}" in
  --task)
    # Array task SLURM_ARRAY_TASK_ID: its shard, resumed if this task ran before.
    hybridlab=$2 config=$3 shards=$4 results=$5
    i=${SLURM_ARRAY_TASK_ID:?--task runs as a Slurm array task}
    out=$results/shards/$i
    # A requeued task may have been killed on another node, whose lock the runner cannot check;
    # Slurm runs one instance of a task at a time, so that lock is this task's own, stale.
    if [ "${SLURM_RESTART_COUNT:-0}" -gt 0 ] && [ -f "$out/.lock" ]; then
      echo "slurm_array.sh: requeued (restart ${SLURM_RESTART_COUNT}): removing the lock of the earlier attempt: $(cat "$out/.lock")"
      rm -f "$out/.lock"
    fi
    exec "$hybridlab" run "$config" --shard "$i/$shards" --out "$out" --resume --quiet
    ;;
  --merge)
    hybridlab=$2 config=$3 shards=$4 results=$5
    dirs=()
    for ((i = 0; i < shards; i++)); do dirs+=("$results/shards/$i"); done
    exec "$hybridlab" merge --out "$results/merged" "${dirs[@]}"
    ;;
  -h|--help|"")
    usage
    ;;
esac

# Submission.
config=${1:?config}
shards=${2:?shard count}
shift 2
results=""
if [ $# -gt 0 ] && [ "$1" != "--" ]; then results=$1; shift; fi
if [ $# -gt 0 ]; then
  [ "$1" = "--" ] || usage
  shift
fi
sbatch_options=("$@")
if ! [[ "$shards" =~ ^[1-9][0-9]{0,4}$ ]]; then
  echo "slurm_array.sh: shard count '$shards': expected a whole number from 1 to 99999" >&2
  exit 2
fi
if [ ! -f "$config" ]; then
  echo "slurm_array.sh: $config: no such config file" >&2
  exit 2
fi
if ! command -v sbatch >/dev/null; then
  echo "slurm_array.sh: sbatch not found: submit from a Slurm login node" >&2
  exit 2
fi
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
hybridlab=$(realpath "${HYBRIDLAB:-$here/../build/hybridlab}")
if [ ! -x "$hybridlab" ]; then
  echo "slurm_array.sh: $hybridlab: no hybridlab program (build it, or set HYBRIDLAB)" >&2
  exit 2
fi
config=$(realpath "$config")
name=$(basename "$config" .toml)
results=$(realpath -m "${results:-results/$name}")
# Check the config (and --shard) here, before anything is queued: bad input fails now, not on a node.
"$hybridlab" run "$config" --shard "0/$shards" --out "$results/shards/0" --dry-run >/dev/null
mkdir -p "$results/shards" "$results/logs"
export HYBRIDLAB_CACHE=${HYBRIDLAB_CACHE:-$results/reference-cache}
# sbatch copies this script to the node's spool; every path it needs is passed, absolute.
array=$(sbatch --parsable "${sbatch_options[@]}" --array="0-$((shards - 1))" --job-name="hybridlab-$name" \
          --output="$results/logs/shard-%a.out" --export=ALL "$here/slurm_array.sh" --task "$hybridlab" "$config" "$shards" "$results")
array=${array%%;*}
merge=$(sbatch --parsable "${sbatch_options[@]}" --dependency="afterok:$array" --kill-on-invalid-dep=yes \
          --job-name="hybridlab-$name-merge" --cpus-per-task=1 --output="$results/logs/merge.out" --export=ALL \
          "$here/slurm_array.sh" --merge "$hybridlab" "$config" "$shards" "$results")
merge=${merge%%;*}
echo "$array $merge"
