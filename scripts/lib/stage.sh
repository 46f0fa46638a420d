# Sourced by the scripts: `stage NAME COMMAND...` runs COMMAND and prints one
# line "stage: NAME  N s  (CPU M s)" on stderr: wall time, then the CPU time
# (user + system) of the processes it waited for, so a stage that leaves the
# cores idle shows (CPU well under cores x wall); the exit status when
# non-zero. With GLOBE_STAGE_LOG set, the line is also appended there
# (.ci/run prints them all as one table at the end). The command's exit
# status is returned.
stage_cpu_ticks() {  # this shell's waited-for children: cutime + cstime (proc(5))
  local stat
  read -r stat </proc/$$/stat
  stat=${stat##*) }  # past the command name, which may hold spaces
  set -- $stat
  echo $((${14} + ${15}))
}
stage() {
  local name=$1 start=$SECONDS status=0 ticks
  shift
  ticks=$(stage_cpu_ticks)
  "$@" || status=$?
  local line cpu
  cpu=$((($(stage_cpu_ticks) - ticks) / $(getconf CLK_TCK)))
  line=$(printf '%-28s %5d s  (CPU %5d s)' "$name" $((SECONDS - start)) "$cpu")
  [ $status -ne 0 ] && line+="  (exit $status)"
  echo "stage: $line" >&2
  if [ -n "${GLOBE_STAGE_LOG:-}" ]; then echo "$line" >>"$GLOBE_STAGE_LOG"; fi
  return $status
}
