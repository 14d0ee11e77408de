#!/usr/bin/env bash
# rviz under Xvfb: test/pictures/rviz_screenshot.py in a virtual 1280x800 screen, with software OpenGL.
# Usage: rviz_screenshot.sh DEVEL_SPACE OUT.png [more options of rviz_screenshot.py]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
devel=$(cd "$1" && pwd); out=$2; shift 2
export PATH=/usr/bin:$PATH                 # Debian's python3: ROS's modules are Debian's
set +u; source "$devel/setup.bash"; set -u
# Loopback by address, logs of our own; software OpenGL, as on a machine without a GPU.
export ROS_IP=127.0.0.1 ROS_HOME=$(mktemp -d) LIBGL_ALWAYS_SOFTWARE=1
unset ROS_HOSTNAME
trap 'rm -rf "$ROS_HOME"' EXIT
exec_status=0
xvfb-run -a -s "-screen 0 1280x800x24" /usr/bin/python3 "$here/rviz_screenshot.py" --out "$out" "$@" || exec_status=$?
exit $exec_status
