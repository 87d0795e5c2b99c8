#!/usr/bin/env bash
# Starts `mpiexec -n 2 pvserver` on a free port, runs a pvpython client
# script against it, and stops the server. The client gets the port as its
# last argument. Run under one X server (xvfb-run) for both.
#
# Usage: RunClientServer.sh MPIEXEC PVSERVER PVPYTHON SCRIPT [ARGS...]
set -euo pipefail
mpiexec=$1 pvserver=$2 pvpython=$3
shift 3
port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
log=$(mktemp)
"$mpiexec" --allow-run-as-root --oversubscribe -n 2 "$pvserver" --sp="$port" > "$log" 2>&1 &
server=$!
trap 'kill "$server" 2> /dev/null || true; rm -f "$log"' EXIT
for _ in $(seq 120); do
  grep -q "Accepting connection" "$log" && break
  kill -0 "$server" 2> /dev/null || { cat "$log"; echo "FAILED: pvserver exited"; exit 1; }
  sleep 0.5
done
grep -q "Accepting connection" "$log" || { cat "$log"; echo "FAILED: pvserver did not start"; exit 1; }
status=0
"$pvpython" "$@" "$port" || status=$?
# The server exits when its client disconnects.
for _ in $(seq 60); do
  kill -0 "$server" 2> /dev/null || break
  sleep 0.5
done
cat "$log"
exit "$status"
