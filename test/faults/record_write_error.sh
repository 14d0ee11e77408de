#!/usr/bin/env bash
# A bag that can no longer be written (a file-size limit: `ulimit -f`, with SIGXFSZ ignored so that a write
# fails as on a full disk): `simulate --bag` and the node's own recorder (~bag) each stop with one line
# naming the file, exit non-zero (simulate 1, sim_node 4) instead of aborting, leave no CSV half-written,
# and leave FILE.active from which `rosbag reindex` recovers what reached the disk.
#   record_write_error.sh DEVEL
set -euo pipefail
devel=$1
set +u; source "$devel/setup.bash"; set -u
export PATH=/usr/bin:$PATH ROS_HOME=$(mktemp -d) ROS_IP=127.0.0.1
unset ROS_HOSTNAME
work=$(mktemp -d)
config=$(rospack find rigid_body_sim)/config/demo.yaml
limit_kb=2000  # a few chunks of rosbag's 768 kB: some 20 s of demo.yaml

fail() {
  echo "record_write_error: FAILED: $*" >&2
  exit 1
}
# Runs a command with the file-size limit; its status in $status, its output in $work/$1.txt.
limited() {
  local log=$work/$1.txt; shift
  status=0
  bash -c "trap '' XFSZ; ulimit -f $limit_kb; exec \"\$@\"" limited "$@" >"$log" 2>&1 || status=$?
}
# FILE.active is left, and rosbag reindex makes a readable bag of it with messages up to some t > 0.
recovered() {
  local active=$1.active
  [ -e "$active" ] || fail "no $active left"
  [ -e "$1" ] && fail "$1 was written as if complete"
  rosbag reindex "$active" >/dev/null 2>&1 || fail "rosbag reindex $active"
  local messages
  messages=$(rosbag info --yaml --key=messages "$active") || fail "rosbag info $active after reindex"
  [ "$messages" -gt 100 ] || fail "$active: $messages messages after reindex"
  echo "record_write_error: $active: $messages messages recovered by rosbag reindex"
}

# simulate --bag: exit 1, exactly one line, the out dir empty.
limited simulate "$devel/lib/rigid_body_sim/simulate" "$config" --duration 60 --out-dir "$work/out" --bag "$work/simulate.bag"
[ "$status" = 1 ] || fail "simulate exited $status (1 expected): $(cat "$work/simulate.txt")"
[ "$(wc -l <"$work/simulate.txt")" = 1 ] || fail "simulate said more than one line: $(cat "$work/simulate.txt")"
grep -q "^simulate: writing '$work/simulate.bag.active' failed (.*rosbag reindex" "$work/simulate.txt" ||
  fail "simulate's line: $(cat "$work/simulate.txt")"
[ -z "$(ls -A "$work/out")" ] || fail "simulate left files: $(ls "$work/out")"
recovered "$work/simulate.bag"

# sim_node with ~bag, as fast as it can: exit 4, one ERROR line, the process not aborted.
port=$(python3 -c 'from rigid_body_sim.sim_tools import free_port; print(free_port())')
export ROS_MASTER_URI=http://127.0.0.1:$port
roscore -p "$port" >"$work/roscore.txt" 2>&1 &
core=$!
trap 'kill -INT $core 2>/dev/null; wait $core 2>/dev/null; rm -rf "$work" "$ROS_HOME"' EXIT
# The master is up when it answers: looked for every 0.1 s, at most 30 s (then the load below fails).
for _ in $(seq 300); do rosparam list >/dev/null 2>&1 && break; sleep 0.1; done
rosparam load "$config" /sim || fail "no master in 30 s"
limited node timeout 120 rosrun rigid_body_sim sim_node __name:=sim _bag:="$work/node.bag" _real_time_factor:=0 \
  _duration:=600
[ "$status" = 4 ] || fail "sim_node exited $status (4 expected; 124: still running): $(tail -5 "$work/node.txt")"
errors=$(grep -c "\[ERROR\]" "$work/node.txt" || true)
[ "$errors" = 1 ] || fail "sim_node logged $errors ERROR lines: $(grep -v INFO "$work/node.txt")"
grep -q "recording stopped at t = .*: writing '$work/node.bag.active' failed .*exiting with status 4" \
  "$work/node.txt" || fail "sim_node's line: $(grep ERROR "$work/node.txt")"
recovered "$work/node.bag"
echo "record_write_error: ok"
