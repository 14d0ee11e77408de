# The two commands for a newcomer on a fresh Debian 12 machine:
#   make demo   installs what is missing, builds, and runs the demo
#   make test   installs what is missing, builds, and runs every test (ctest; honest exit code)
# and for the edit loop:
#   make check  the unit tests alone (ctest label unit: no master), under a minute
SHELL := /bin/bash
# Debian's python3 first: ROS's Python modules are Debian's (a pyenv python3 cannot import them).
export PATH := /usr/bin:$(PATH)
BUILD ?= build
# The devel space lives beside build/, not in it: rosrun runs nothing under <package>/build/ (its find skips
# that folder). Every other build (mk/: build/asan, build/fuzz, build/bench) lives there, so that rosrun
# finds the release programs only.
DEVEL ?= $(CURDIR)/devel
JOBS ?= $(shell nproc)
# The release build (make build, which install-check installs): optimized, with debug line tables only
# (-g1): a backtrace (gdb, a crash) still names every function, file and line. Full -g (gdb's local
# variables) makes a file of the ros layer take 1.6 times as long to compile
# (src/ros/reconfigure_servers.cpp: 8.8 s, 5.6 s with -g1): `make build DEBUG_INFO=-g` for that.
DEBUG_INFO ?= -g1
RELEASE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 $(DEBUG_INFO) -DNDEBUG"
# Suites with a build of their own (sanitizers, fuzzing) that `make test` runs before ctest's main suite;
# the files under mk/ add theirs, and their own targets (bench, screenshot, soak ...).
EXTRA_TESTS :=
include $(sort $(wildcard mk/*.mk))

.PHONY: all deps build demo test test-build check lint clean

all: build

deps:
	bash scripts/install-deps all

build: deps
	cmake -S . -B $(BUILD) -DCATKIN_DEVEL_PREFIX=$(DEVEL) -DCMAKE_INSTALL_PREFIX=$(INSTALL_SPACE) \
	  -DCATKIN_ENABLE_TESTING=ON $(RELEASE_FLAGS) >/dev/null
	touch $(DEVEL)/CATKIN_IGNORE  # keeps catkin_lint out of it, as catkin does for build/
	cmake --build $(BUILD) -j$(JOBS) -- --no-print-directory

demo: build
	bash scripts/demo $(DEVEL)

# ctest runs from the build folder: `ctest --test-dir` needs CMake 3.20 (Debian 11 has 3.18, Noetic 3.16).
# --no-tests=error (CMake 3.17): a run that finds no test (a label or registration gone) fails.
# -j: TEST_JOBS tests at once, two more than the cores: most tests wait (for a master, a node, a deadline). On
# 2 cores (Debian 11) ctest kept 74 % of them busy at 3 tests and took 160 s; at 4, 139 s.
# Each starts its own master on a free port. Those that render in software (rviz, Chromium: RENDERS in
# test/CMakeLists.txt) run two at a time at most.
TEST_JOBS ?= $(shell echo $$(($(JOBS) + 2)))
CTEST = env -u ROS_HOSTNAME ROS_IP=127.0.0.1 ROS_HOME=$$(mktemp -d) ctest -j$(TEST_JOBS) --no-tests=error --output-on-failure
# After the build, the suites of mk/ (EXTRA_TESTS), the lint and the build of the tests run two at a time:
# the single-core and waiting parts of one (the lint, the fuzzer, the install space's launches and rostests,
# the Slurm test, a test run) leave a core that the other takes. The longest build (asan) first; beside it
# the suites that wait or take one core, then the build of the tests: the last two running are builds,
# which keep both cores busy. deps and build are done: -o keeps the sub-make from running them again (and
# from starting the suites that need them last, as gmake does with a goal whose prerequisite was running).
# Each one's output comes whole when it ends (--output-sync); the first to fail stops the rest from
# starting. Each build keeps its own JOBS jobs (gmake says so: "-jN forced in submake: resetting jobserver
# mode").
test: build
	$(MAKE) --no-print-directory -j2 --output-sync=target -o deps -o build \
	  $(filter asan,$(EXTRA_TESTS)) $(filter-out asan,$(EXTRA_TESTS)) lint test-build
	cd $(BUILD) && $(CTEST)

test-build: build
	cmake --build $(BUILD) --target tests -j$(JOBS) -- --no-print-directory

check: build
	cmake --build $(BUILD) --target unit_tests -j$(JOBS) -- --no-print-directory
	cd $(BUILD) && ctest -j$(JOBS) -L '^unit$$' --no-tests=error --output-on-failure

# Python scripts without a .py ending (scripts/slurm_sweep): their first line names python. flake8 and mypy
# find only *.py files in the folders they are given, so these are named to them one by one.
PYTHON_SCRIPTS = $(shell git ls-files | grep -v '\.[^/]*$$' | xargs -r awk 'FNR == 1 && /^\#!.*python/ { print FILENAME } { nextfile }')

# The repository's root is the package: its folder is named after the clone, not the package.
lint: deps
	catkin_lint -W2 --strict --ignore package_path_name . examples/sim_fixture_example
	git ls-files '*.cpp' '*.h' | xargs clang-format --dry-run -Werror
	flake8 scripts bench test examples src/rigid_body_sim setup.py $(PYTHON_SCRIPTS)
	mypy
	mypy examples/sim_fixture_example/test  # alone: its `rostest` is ROS's, not test/rostest/
	$(if $(PYTHON_SCRIPTS),mypy $(PYTHON_SCRIPTS))

clean:
	rm -rf $(BUILD) $(DEVEL)
