# make stress-start (not part of `make test`): sim_node started STRESS_RUNS times under one master of its
# own, alternating a refused config (exit 1 with its one line) and a good one (a first state, then exit 0 on
# SIGINT); prints the count of every outcome and fails on any other. STRESS_ARGS=--strace keeps the system
# calls of the starts that end otherwise (in $(BUILD)/stress-start/).
STRESS_RUNS ?= 1000
STRESS_ARGS ?=

.PHONY: stress-start

stress-start: build
	source $(DEVEL)/setup.bash && /usr/bin/python3 scripts/stress_start.py --devel $(DEVEL) \
	  --runs $(STRESS_RUNS) --keep $(BUILD)/stress-start $(STRESS_ARGS)
