# make flaky [RUNS=10] (not part of `make test`): the suites that start a master (ctest labels node, script,
# pictures, web) run RUNS times, as `make test` runs them; prints per test its failures out of RUNS and its time,
# and fails if any test failed once. The logs of the rounds with a failure stay in $(BUILD)/flaky/ (with
# the picture tests' screenshots, findings and roslaunch logs, and the ROS_HOME with every node's log).
# HOG=N: N processes keep a core busy each all along (the busy machine every test must pass on).
RUNS ?= 10
HOG ?= 0
FLAKY_LABELS ?= node|script|pictures|web

.PHONY: flaky

flaky: build
	cmake --build $(BUILD) --target tests -j$(JOBS) -- --no-print-directory
	/usr/bin/python3 scripts/flaky.py --build $(BUILD) --runs $(RUNS) --labels '$(FLAKY_LABELS)' \
	  --keep $(BUILD)/flaky --hog $(HOG) --jobs $(TEST_JOBS)
