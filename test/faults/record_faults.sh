#!/usr/bin/env bash
# Recording through sim.launch when the run ends badly (bounded: about 30 s wall each):
#   record_faults.sh sigint DEVEL   Ctrl-C (SIGINT) to roslaunch: the bag is closed cleanly and holds every
#                                   message the node published up to then, no sample missing
#   record_faults.sh kill9 DEVEL    kill -9 of the recorder: a .bag.active is left; `rosbag reindex`
#                                   recovers it, with every sample up to the last flushed chunk
# To know exactly what was published, the node is paused, then stepped once (its last sample is then at
# that step's t, which ~step returns), and the fault comes once the recorder received all it was sent.
set -euo pipefail
mode=$1 devel=$2
here=$(cd "$(dirname "$0")" && pwd)
set +u; source "$devel/setup.bash"; set -u
export PATH=/usr/bin:$PATH ROS_HOME=$(mktemp -d) ROS_IP=127.0.0.1
unset ROS_HOSTNAME
port=$(python3 -c 'from rigid_body_sim.sim_tools import free_port; print(free_port())')
export ROS_MASTER_URI=http://127.0.0.1:$port
work=$(mktemp -d)
bag=$work/run.bag
config=$(rospack find rigid_body_sim)/config/demo.yaml

roslaunch -p "$port" rigid_body_sim sim.launch record:=true bag:="$bag" config:="$config" >"$work/launch.log" 2>&1 &
launch=$!
cleanup() {
  kill -INT $launch 2>/dev/null && wait $launch 2>/dev/null || true
  rm -rf "$work" "$ROS_HOME"
}
trap cleanup EXIT
fail() {
  echo "record_faults $mode: FAILED: $*" >&2
  tail -20 "$work/launch.log" >&2
  exit 1
}
# Bounded waits: poll for a condition, at most $1 seconds.
wait_until() {
  local limit=$1; shift
  for _ in $(seq $((limit * 10))); do "$@" && return 0; sleep 0.1; done
  return 1
}

wait_until 60 test -e "$bag.active" || fail "the recorder did not start"
wait_until 60 rosservice list >/dev/null 2>&1 || fail "no master"
# Recording until the recorder has written a first chunk (768 kB of messages, rosbag record's default
# --chunksize: some 8 s of the demo, markers included). The chunks are LZ4 (sim.launch): each reaches the
# file whole when it closes, about 300 kB, after the bag's 4 kB header. A kill -9 then leaves a bag with
# something to recover.
chunk_written() { [ "$(stat -c %s "$bag.active" 2>/dev/null || echo 0)" -gt $((64 * 1024)) ]; }
wait_until 90 chunk_written || fail "the recorder wrote no chunk in 90 s"
rosservice call /sim/pause >/dev/null || fail "~pause"
t=$(rosservice call /sim/step "steps: 1" | sed -n 's/^t: //p')
[ -n "$t" ] || fail "~step"
# Nothing is published any more: the recorder has every message once its transport received what the node sent.
python3 "$here/wait_delivered.py" /sim /record 30 || fail "the recorder did not receive every message"

case $mode in
  sigint)
    kill -INT $launch
    wait_until 30 bash -c "! kill -0 $launch 2>/dev/null" || fail "roslaunch did not end on SIGINT"
    [ -e "$bag.active" ] && fail "the bag was left .active"
    rosbag info "$bag" >/dev/null || fail "rosbag info"
    python3 "$here/check_bag.py" "$bag" "$config" "$t" complete
    ;;
  kill9)
    recorder=$(pgrep -P $launch -f rosbag/record) || fail "no recorder process under roslaunch"
    kill -9 "$recorder"
    wait_until 10 bash -c "! kill -0 $recorder 2>/dev/null" || fail "the recorder survived kill -9"
    [ -e "$bag.active" ] || fail "no .bag.active after kill -9"
    rosbag info "$bag.active" >/dev/null 2>&1 && fail "an unindexed bag should not open before reindex"
    mkdir "$work/reindexed"
    rosbag reindex --output-dir "$work/reindexed" "$bag.active" >/dev/null || fail "rosbag reindex"
    rosbag info "$work/reindexed/run.bag.active" >/dev/null || fail "rosbag info after reindex"
    python3 "$here/check_bag.py" "$work/reindexed/run.bag.active" "$config" "$t" prefix "$(stat -c %s "$bag.active")"
    ;;
  *) fail "unknown mode (sigint or kill9)" ;;
esac
echo "record_faults $mode: ok"
