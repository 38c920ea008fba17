#!/usr/bin/env bash
# One slice of a corpus of recordings per task of a Slurm array job
# (docs/repl.md, "A corpus on a cluster"): task K of N runs
# `bsc replay --shard K/N` on the cores Slurm gave it and writes its JUnit
# file; merge-junit.py adds the slices up once all have ended.
#
#   sbatch --array=0-7 --cpus-per-task=16 examples/cluster/replay-array.sh \
#       --bind SoccerBindings.o -I paper --entry Behavior::gotoBallAndKick \
#       --logs /data/runs paper/Behavior.bs
#
# Arguments are bsc replay's (without --shard, --junit, --jobs or
# --coverage). Environment: BSC (default: bsc on PATH), REPLAY_RESULTS (the
# folder of the slices' files, default replay-results; one per array job,
# since slices of another N would not add up), REPLAY_COVERAGE=1 (each
# slice also writes its lcov tracefile, slice-K-of-N.info, which
# `lcov -a` adds up). Outside Slurm, set SLURM_ARRAY_TASK_ID and
# SLURM_ARRAY_TASK_COUNT to run one slice.
#SBATCH --job-name=bsc-replay
#SBATCH --output=replay-%A_%a.out
set -euo pipefail

if [[ -z ${SLURM_ARRAY_TASK_ID:-} || -z ${SLURM_ARRAY_TASK_COUNT:-} ]]; then
  echo "replay-array.sh: run it as a Slurm array job (sbatch --array=0-N)," \
       "or set SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT" >&2
  exit 2
fi
# Array indices may start anywhere (--array=1-8): slices count from the
# smallest, 1 to N, as --shard does.
K=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-0} + 1))
N=$SLURM_ARRAY_TASK_COUNT
if ((K < 1 || K > N)); then
  echo "replay-array.sh: task $SLURM_ARRAY_TASK_ID is not one of $N" \
       "(SLURM_ARRAY_TASK_MIN is ${SLURM_ARRAY_TASK_MIN:-0});" \
       "the array must be contiguous, as --array=0-$((N - 1))" >&2
  exit 2
fi
RESULTS=${REPLAY_RESULTS:-replay-results}
mkdir -p "$RESULTS"
coverage=()
[[ ${REPLAY_COVERAGE:-} == 1 ]] && coverage=(--coverage "$RESULTS/slice-$K-of-$N.info")
# bsc takes one worker per core it may run on (Slurm's cpuset), so
# --cpus-per-task alone sets the workers.
exec "${BSC:-bsc}" replay --shard "$K/$N" \
  --junit "$RESULTS/slice-$K-of-$N.xml" "${coverage[@]}" "$@"
