# Sourced by the scripts: `stage NAME COMMAND...` runs COMMAND and prints one
# line "stage: NAME  N s" (wall time, exit status when non-zero) on stderr. With
# GLOBE_STAGE_LOG set, the line is also appended there (.ci/run prints them all
# as one table at the end). The command's exit status is returned.
stage() {
  local name=$1 start=$SECONDS status=0
  shift
  "$@" || status=$?
  local line
  line=$(printf '%-28s %5d s' "$name" $((SECONDS - start)))
  [ $status -ne 0 ] && line+="  (exit $status)"
  echo "stage: $line" >&2
  if [ -n "${GLOBE_STAGE_LOG:-}" ]; then echo "$line" >>"$GLOBE_STAGE_LOG"; fi
  return $status
}
