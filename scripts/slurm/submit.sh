#!/usr/bin/env bash
# Runs a globe-tiler or globe-vectorize build as a Slurm array job of shards
# and a merge job that starts when every shard has succeeded
# (docs/scale-out.md).
#
#   scripts/slurm/submit.sh --shards N [options] -- PROGRAM COMMAND INPUT... -o OUT.mbtiles [build options]
#
# PROGRAM COMMAND ... is the one-machine command line (e.g. globe-tiler
# terrain dem.vrt -o nl.mbtiles --precision 0.01, or globe-vectorize lines
# roads.gpkg -o roads.mbtiles). Writes two batch scripts
# into the scratch folder and submits them with sbatch:
#   NAME.shards.sbatch  --array=0-(N-1): shard $SLURM_ARRAY_TASK_ID/N of the
#                       build into SCRATCH/NAME.shard-I.mbtiles (--resume: a
#                       re-run continues a killed shard)
#   NAME.merge.sbatch   --dependency=afterok:<array job>: PROGRAM merge of the
#                       N shards into OUT.mbtiles (--resume as well)
# Inputs, OUT and the scratch folder must be on a file system every node sees.
#
# Options:
#   --shards N        number of shards (array tasks)
#   --scratch DIR     shard packages, scripts and logs (default OUT's folder/NAME.shards)
#   --sbatch "ARGS"   extra sbatch options for both jobs (partition, time, cpus)
#   --only I[,J...]   resubmit just these shards (after a failure) and a new merge job
#   --dry-run         write the scripts, print the sbatch commands, submit nothing
# Prints the job ids on stdout: "shards JOBID", "merge JOBID".
set -euo pipefail

usage() { sed -n 2,25p "$0" >&2; exit 2; }
n="" scratch="" extra="" only="" dry=0
while [ $# -gt 0 ]; do
  case "$1" in
  --shards) n=${2:-}; shift 2 ;;
  --scratch) scratch=${2:-}; shift 2 ;;
  --sbatch) extra=${2:-}; shift 2 ;;
  --only) only=${2:-}; shift 2 ;;
  --dry-run) dry=1; shift ;;
  --) shift; break ;;
  -h | --help) usage ;;
  *) echo "submit.sh: unknown option '$1' (the build command goes after --)" >&2; exit 2 ;;
  esac
done
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: --shards N is required (N >= 1)" >&2; exit 2; }
[ $# -ge 3 ] || { echo "submit.sh: give the build command after --" >&2; exit 2; }

program=$1
shift
if [[ "$program" == */* ]]; then program=$(cd "$(dirname "$program")" && pwd)/$(basename "$program"); fi
command -v "$program" >/dev/null || { echo "submit.sh: $program: not found" >&2; exit 1; }
# The build's arguments without -o (and without --shard, which this adds).
out="" args=()
while [ $# -gt 0 ]; do
  case "$1" in
  -o | --output) out=${2:-}; shift 2 ;;
  --output=*) out=${1#--output=}; shift ;;
  --shard) shift 2 ;;
  --shard=*) shift ;;
  *) args+=("$1"); shift ;;
  esac
done
[ -n "$out" ] || { echo "submit.sh: the build command has no -o OUT.mbtiles" >&2; exit 2; }
[ -d "$(dirname "$out")" ] || { echo "submit.sh: $(dirname "$out"): no such folder (for -o $out)" >&2; exit 1; }
out=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
name=$(basename "$out" .mbtiles)
scratch=${scratch:-$(dirname "$out")/$name.shards}
mkdir -p "$scratch/logs"
scratch=$(cd "$scratch" && pwd)

quoted() { printf ' %q' "$@"; }
shards=()
for ((i = 0; i < n; i++)); do shards+=("$scratch/$name.shard-$i.mbtiles"); done

cat >"$scratch/$name.shards.sbatch" <<SCRIPT
#!/bin/bash
#SBATCH --job-name=$name-shards
#SBATCH --array=0-$((n - 1))
#SBATCH --output=$scratch/logs/shard-%a.log
# Shard \$SLURM_ARRAY_TASK_ID of $n (written by scripts/slurm/submit.sh).
set -euo pipefail
i=\$SLURM_ARRAY_TASK_ID
exec$(quoted "$program" "${args[@]}") --shard "\$i/$n" -o "$scratch/$name.shard-\$i.mbtiles" --resume --progress json
SCRIPT
cat >"$scratch/$name.merge.sbatch" <<SCRIPT
#!/bin/bash
#SBATCH --job-name=$name-merge
#SBATCH --output=$scratch/logs/merge.log
# The merge of the $n shards (written by scripts/slurm/submit.sh).
set -euo pipefail
exec$(quoted "$program" merge "${shards[@]}") -o $(printf '%q' "$out") --resume --progress json
SCRIPT

array_args=()
[ -n "$only" ] && array_args=(--array="$only")
# shellcheck disable=SC2206
extra_args=($extra)
run() {
  if [ "$dry" -eq 1 ]; then
    echo "sbatch$(quoted "$@")" >&2
    echo "DRYRUN"
  else
    sbatch --parsable "$@" | cut -d';' -f1
  fi
}
shard_job=$(run "${extra_args[@]}" "${array_args[@]}" "$scratch/$name.shards.sbatch")
merge_job=$(run "${extra_args[@]}" --dependency="afterok:$shard_job" --kill-on-invalid-dep=yes \
  "$scratch/$name.merge.sbatch")
echo "shards $shard_job"
echo "merge $merge_job"
echo "submit.sh: $n shards of $name (job $shard_job), merge into $out after them (job $merge_job);" \
  "logs in $scratch/logs/. A failed shard I: $0 --only I --shards $n --scratch $scratch -- ..." >&2
