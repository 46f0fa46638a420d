# Timing helpers shared by the benchmark scripts (sourced, not run).
# seconds CMD...: runs CMD, prints "wall_s maxrss_kb".
seconds() { /usr/bin/time -f "%e %M" "$@" 2>&1 >/dev/null | tail -1; }
# The machines are shared: each tool runs several times, alternating with its
# peer, and the fastest run of each counts (noise only ever adds time).
# fastest: "wall rss" lines on stdin -> the smallest wall time (and the largest rss).
fastest() { awk 'NR == 1 || $1 < w { w = $1 } $2 > m { m = $2 } END { print w, m }'; }
# usage CMD...: runs CMD, prints "wall_s maxrss_kb cpu_s" (user + system).
usage() { /usr/bin/time -f "%e %M %U %S" "$@" 2>&1 >/dev/null | tail -1 | awk '{ print $1, $2, $3 + $4 }'; }
# fastest_cpu: "wall rss cpu" lines -> the smallest cpu (with its wall) and the largest rss.
fastest_cpu() { awk 'NR == 1 || $3 < c { c = $3; w = $1 } $2 > m { m = $2 } END { print w, m, c }'; }
# best CMD...: runs CMD 3 times -> "wall rss cpu" of the least CPU (and the largest rss).
best() { for _ in 1 2 3; do usage "$@"; done | fastest_cpu; }
