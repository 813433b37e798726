#!/usr/bin/env bash
# One image over a Slurm job array: task i renders sample indices [i*S, (i+1)*S) of every
# pixel, then one dependent job merges the parts. From the repository root, with `prism`
# on PATH on every node and OUT on a shared file system:
#   jid=$(sbatch --parsable --export=ALL,SCENE=scenes/cornell-bunny.gltf examples/farm/slurm.sh)
#   sbatch --dependency=afterok:$jid --wrap \
#     "prism merge prism-out/part-*.exr -o prism-out/image.exr -o prism-out/image.png"
#SBATCH --job-name=prism-part
#SBATCH --array=0-15
#SBATCH --cpus-per-task=2
#SBATCH --output=prism-part-%a.log
set -euo pipefail

SCENE=${SCENE:-scenes/cornell-box.gltf}
OUT=${OUT:-prism-out}
SPP_PER_TASK=${SPP_PER_TASK:-64}      # total spp = array size * SPP_PER_TASK
SEED=${SEED:-0}
mkdir -p "$OUT"

i=${SLURM_ARRAY_TASK_ID}
start=$(( i * SPP_PER_TASK ))
end=$(( start + SPP_PER_TASK ))
# Same scene, size and seed everywhere: every sample's random numbers depend only on
# (seed, pixel, sample index), so the parts are disjoint slices of one render. A task that
# is requeued renders the same slice again.
prism render "$SCENE" --width 1024 --height 1024 --seed "$SEED" --quiet \
    --sample-range "$start..$end" -o "$OUT/part-$i.exr"
