#!/bin/sh
# A fake engine that starts a helper, writes the helper's pid to $1, and never
# finishes: the harness must kill the whole process group at its time limit.
# Usage: hang.sh PIDFILE SCENE
sleep 1000 &
echo $! > "$1"
sleep 1000
