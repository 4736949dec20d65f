# Sourced by the benchmark scripts: a feltd serve on a free loopback port.
#
#   start_feltd FELTD SCENE [FLAGS...]   sets pid, server (127.0.0.1:PORT) and log (its output)
#   stop_feltd                           ends it and removes the log
# shellcheck shell=bash

start_feltd() {
  local feltd="$1" scene="$2"
  shift 2
  log="$(mktemp)"
  "$feltd" serve --listen 127.0.0.1:0 --scene-dir "$root/scenes" --scene "$scene" "$@" \
    >"$log" 2>&1 &
  pid=$!
  for _ in $(seq 100); do grep -q "listening on" "$log" && break; sleep 0.1; done
  server="127.0.0.1:$(sed -n 's/^listening on .*:\([0-9]*\)$/\1/p' "$log")"
}

stop_feltd() {
  [ -n "${pid:-}" ] || return 0
  kill "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  rm -f "$log"
  pid=""
}
