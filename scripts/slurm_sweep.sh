#!/usr/bin/env bash
# Slurm array job: one speed sweep cut into N contiguous shards, one array task per shard.
# Submit from the repository root, after building (scripts/setup.sh) and creating results/:
#   mkdir -p results && sbatch scripts/slurm_sweep.sh
# Task i runs shard i/N (0-based) of the speed list as one continuation chain and writes
# results/sweep_shard_i/ (sweep.csv + one folder per speed).
#SBATCH --job-name=gaitopt-sweep
#SBATCH --array=0-3
#SBATCH --cpus-per-task=1
#SBATCH --mem=1G
#SBATCH --time=01:00:00
#SBATCH --output=results/slurm_sweep_%A_%a.log
set -euo pipefail

# Number of shards: must match --array=0-(N-1) above.
N="${SLURM_ARRAY_TASK_COUNT:-4}"
CONFIG="${CONFIG:-configs/default.yaml}"
SPEEDS="${SPEEDS:-0.2:1.0:0.05}"

# sbatch runs a copy of this script from its spool directory: work from the submit directory.
cd "${SLURM_SUBMIT_DIR:-.}"
build/gaitopt sweep --config "$CONFIG" --speeds "$SPEEDS" \
  --shard "$SLURM_ARRAY_TASK_ID/$N" --quiet \
  --out "results/sweep_shard_$SLURM_ARRAY_TASK_ID"

# Merge step, once every task has finished (by hand, or as a dependent job
#   sbatch --dependency=afterany:<array job id> --wrap '...'):
#   build/gaitopt sweep-merge --out results/sweep_merged \
#     results/sweep_shard_0 results/sweep_shard_1 results/sweep_shard_2 results/sweep_shard_3
# The merged folder holds sweep.csv only; the per-speed folders stay in the shard folders.
