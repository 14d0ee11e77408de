#!/usr/bin/env bash
# Another package's rostests on the installed node: examples/sim_fixture_example in a workspace of its own
# on top of INSTALL (only INSTALL/setup.bash sourced), built and run with catkin_make run_tests: the
# installed helpers (rigid_body_sim.testing, rigid_body_sim/testing/sim_fixture.h) are all it has. Its five
# tests must end as written: `rolls` (a true claim), `finishes` (an event) and `steeper` (C++: a state and an
# event) pass; `slides` (a false claim) and `cut_short` (the simulation's duration ends before the state the
# test waits for) fail, each with its own line. A test that passes by not running (rostest's "TESTS: 0")
# fails this check.
# Usage: check_example.sh INSTALL_DIR EXAMPLE_DIR
set -euo pipefail
install=$(cd "$1" && pwd)
example=$(cd "$2" && pwd)
ws=$(mktemp -d /tmp/rigid_body_sim_example_ws.XXXXXX)
trap 'rm -rf "$ws"' EXIT
mkdir "$ws/src" && cp -r "$example" "$ws/src/"
env -i HOME="$HOME" PATH=/usr/bin:/bin ROS_IP=127.0.0.1 ROS_HOME="$ws/ros_home" bash -c '
  set -euo pipefail
  set +u; source "$1/setup.bash"; set -u
  cd "$2"
  catkin_make -DCATKIN_ENABLE_TESTING=ON >build.log 2>&1 || { tail -30 build.log; exit 1; }
  set +u; source devel/setup.bash; set -u
  catkin_make run_tests >tests.log 2>&1 || { tail -30 tests.log; exit 1; }
' check_example "$install" "$ws"
python3 - "$ws/build/test_results/sim_fixture_example" <<'PY'
import os
import sys
import xml.etree.ElementTree as ElementTree

results = sys.argv[1]
expected = {  # test -> None (passes), or a text its one failure must say
    "rolls": None,
    "finishes": None,
    "steeper": None,
    "slides": "sliding: x(1 s) =",
    "cut_short": "the simulation ended or died early",
}
failures = []
for test, says in expected.items():
    path = os.path.join(results, f"rosunit-{test}.xml")
    if not os.path.exists(path):
        failures.append(f"{test}: no results ({path})")
        continue
    try:
        suite = ElementTree.parse(path).getroot()
    except ElementTree.ParseError as error:  # empty: the test was killed before it wrote anything
        failures.append(f"{test}: unreadable results ({error})")
        continue
    ran, failed = int(suite.get("tests", 0)), int(suite.get("failures", 0)) + int(suite.get("errors", 0))
    messages = " ".join(f.get("message", "") + (f.text or "") for f in suite.iter("failure"))
    if ran != 1:
        failures.append(f"{test}: {ran} tests ran, not 1")
    elif says is None and failed:
        failures.append(f"{test}: failed: {messages[:500]}")
    elif says is not None and (failed != 1 or says not in messages):
        failures.append(f"{test}: should fail saying '{says}'; failures {failed}: {messages[:500]}")
if failures:
    sys.exit("check_example: FAILED:\n" + "\n".join(failures))
print("check_example: rolls, finishes and steeper passed; slides and cut_short failed, each with its line")
PY
