#!/usr/bin/env bash
# The install space alone, as a user runs it: with nothing but INSTALL/setup.bash sourced (env -i: no devel
# space, no source folder on any path), rospack finds the package in INSTALL, and
#   rosrun rigid_body_sim simulate       writes the CSV of config/demo.yaml
#   python3: rigid_body_sim.core         runs it again, bit for bit, read back with rigid_body_sim.runs
#   rosrun rigid_body_sim plot_run.py    plots that CSV, with rosbag made unimportable (CSV needs no ROS)
#   roslaunch rigid_body_sim sim.launch  duration:=3 record:=true on a master of its own: exit 0, the bag
#                                        in ROS_HOME; with bag:=run.bag (and web:=true: the web view starts,
#                                        its page found), run.bag in the current folder
#   rosrun rigid_body_sim bag_summary.py summarises that bag; plot_run.py plots it
#   rospack plugins --attrib=plugin rviz lists the installed plugin_description.xml (the rviz panel), and its
#                                        library is installed with every library it needs found
# Usage: check_install.sh INSTALL_DIR
set -euo pipefail
install=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat >"$work/run.bash" <<'EOF'
set -euo pipefail
install=$1 work=$2
set +u; source "$install/setup.bash"; set -u  # setup.bash reads unset variables
fail() { echo "check_install: FAILED: $*" >&2; exit 1; }
share=$(rospack find rigid_body_sim)
[ "$share" = "$install/share/rigid_body_sim" ] || fail "rospack finds $share, not the install space"
config=$share/config/demo.yaml

rosrun rigid_body_sim simulate "$config" --duration 3 --out-dir "$work/csv" >/dev/null || fail "simulate"
[ -s "$work/csv/rod.csv" ] || fail "simulate wrote no rod.csv"
# rigid_body_sim.core from the install space: the same run, bit for bit, as simulate's CSV read back
python3 - "$install" "$config" "$work/csv" <<'PY' || fail "rigid_body_sim.core"
import pathlib, sys
from rigid_body_sim import core, runs
assert core.__file__.startswith(sys.argv[1] + "/"), core.__file__ + " is not the install space's"
mine, theirs = core.World(pathlib.Path(sys.argv[2])).run(3.0), runs.read_run(sys.argv[3])
assert mine.keys() == theirs.keys() and all((mine[b][f] == theirs[b][f]).all() for b in mine for f in mine[b])
PY
plot_run=$(catkin_find --libexec rigid_body_sim plot_run.py)
[ "${plot_run#"$install"}" != "$plot_run" ] || fail "plot_run.py is not installed ($plot_run)"
python3 - "$plot_run" "$config" "$work/csv" "$work/plots_csv" >/dev/null <<'PY' || fail "plot_run.py on CSV without rosbag"
import runpy, sys
sys.modules["rosbag"] = None  # an import of rosbag now fails: a CSV run must not need it
sys.argv = [sys.argv[1], "--out-dir"] + sys.argv[4:] + sys.argv[2:4]
runpy.run_path(sys.argv[0], run_name="__main__")
PY
rosrun rigid_body_sim plot_run.py "$config" "$work/csv" --out-dir "$work/plots_rosrun" >/dev/null || fail "rosrun plot_run.py"
for png in rod rollers energy; do
  [ -s "$work/plots_csv/$png.png" ] && [ -s "$work/plots_rosrun/$png.png" ] || fail "no $png.png"
done

[ "$(catkin_find --libexec rigid_body_sim sim_node)" = "$install/lib/rigid_body_sim/sim_node" ] \
  || fail "sim_node: $(catkin_find --libexec rigid_body_sim sim_node), not the installed one"
port=$(python3 -c 'from rigid_body_sim.sim_tools import free_port; print(free_port())')
export ROS_MASTER_URI=http://127.0.0.1:$port
launch() {  # sim.launch duration:=3 record:=true ARGS...
  timeout 120 roslaunch -p "$port" rigid_body_sim sim.launch duration:=3 record:=true "$@" \
    >"$work/launch.log" 2>&1 || { tail -30 "$work/launch.log"; fail "sim.launch $*"; }
}
launch  # the default bag: in ROS_HOME
[ -s "$ROS_HOME/rigid_body_sim.bag" ] || fail "no bag in ROS_HOME ($ROS_HOME)"
web=$(python3 -c 'from rigid_body_sim.sim_tools import free_port; print(free_port())')
cd "$work" && launch bag:=run.bag web:=true web_port:="$web"  # a relative bag: from the folder roslaunch was started in
[ -s "$work/run.bag" ] || fail "bag:=run.bag did not write $work/run.bag"
# the web view found its page in the install space (it refuses to start without it)
grep -q "web view of /sim on 127.0.0.1:$web" "$work/launch.log" || fail "no web view: $(grep web "$work/launch.log")"
rosrun rigid_body_sim bag_summary.py "$work/run.bag" "$config" >"$work/summary.txt" || fail "bag_summary.py"
grep -q "/sim/rod/state" "$work/summary.txt" || fail "bag_summary.py: no rod states"
rosrun rigid_body_sim plot_run.py "$config" "$work/run.bag" --out-dir "$work/plots_bag" >/dev/null \
  || fail "plot_run.py on the bag"
[ -s "$work/plots_bag/rod.png" ] || fail "no rod.png from the bag"

rospack plugins --attrib=plugin rviz | grep -qx "rigid_body_sim $share/plugin_description.xml" \
  || fail "rviz does not see the installed plugin_description.xml: $(rospack plugins --attrib=plugin rviz)"
panel=$install/lib/librigid_body_sim_rviz.so
[ -f "$panel" ] || fail "the panel's library is not installed ($panel)"
! ldd "$panel" | grep "not found" || fail "the panel's library misses libraries"
echo "check_install: ok ($install)"
EOF
env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 ROS_HOME="$work/ros_home" ROS_IP=127.0.0.1 \
  bash "$work/run.bash" "$install" "$work"
