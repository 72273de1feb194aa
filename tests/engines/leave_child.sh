#!/bin/sh
# A fake engine that writes a valid trajectory (the file $2) and exits 0, but
# leaves a helper running that holds standard output open; its pid goes to $1.
# The harness must not wait for the helper: it kills what the engine left.
# Usage: leave_child.sh PIDFILE TRAJECTORY SCENE
sleep 1000 &
echo $! > "$1"
cat "$2"
