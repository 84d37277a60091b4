#!/bin/bash
# A Slurm job array running one shard of a fourbar study per task.
#   sbatch --array=0-15 cases/studies/slurm_sweep.sh cases/studies/paper_speed.ini 16 results/studies/paper_speed
# then, once every task has finished:
#   fourbar merge results/studies/paper_speed
# A task that dies can be resubmitted alone (sbatch --array=7 ...): a shard resumes where it stopped.
#SBATCH --job-name=fourbar-sweep
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --time=01:00:00
#SBATCH --output=fourbar-sweep-%A_%a.log
set -euo pipefail
study=${1:?study file}
shards=${2:?number of shards (= array size)}
out=${3:?output folder on a shared file system}
exec "${FOURBAR:-fourbar}" sweep "$study" --shard "${SLURM_ARRAY_TASK_ID}/${shards}" --out "$out"
