#!/usr/bin/env bash
# Example: run an experiment as a Slurm job array of N shards, then merge them.
#   sbatch --array=0-7 experiments/slurm_array.sh experiments/configs/paper.toml 8
#   (when all tasks are done)  ./build/hybridlab merge --out results/paper results/paper-shard*
#SBATCH --job-name=hybridlab
#SBATCH --cpus-per-task=8
#SBATCH --time=24:00:00
set -euo pipefail
config=${1:?config file}
shards=${2:?number of shards}
i=${SLURM_ARRAY_TASK_ID:?run as a job array}
name=$(basename "$config" .toml)
# Each task resumes its own shard folder (--resume also starts a new one), so a requeued task
# continues where it stopped. The reference cache should be on a shared file system.
export HYBRIDLAB_CACHE=${HYBRIDLAB_CACHE:-$PWD/.hybridlab-cache}
./build/hybridlab run "$config" --shard "$i/$shards" --out "results/$name-shard$i" --resume
