# Reliability: the config loader fuzzed with libFuzzer, and the unit tests (ctest label `unit`) under
# AddressSanitizer + UndefinedBehaviorSanitizer, each in a build folder of its own. `make test` runs both
# before ctest's main suite; `make fuzz` / `make asan` run one.
FUZZ_BUILD ?= build/fuzz
ASAN_BUILD ?= build/asan
# A fixed number of runs (the same inputs for a given libFuzzer and seed), every one of them required;
# max_total_time only stops a hang (100000 runs take 15 to 100 s here, by the load).
FUZZ_RUNS ?= 100000
FUZZ_SECONDS ?= 300
FUZZ_SOURCES := test/fuzz/fuzz_config_loader.cpp src/io/config_loader.cpp $(wildcard src/core/*.cpp src/core/types/*.cpp)
SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
export ASAN_OPTIONS := halt_on_error=1:detect_leaks=1:abort_on_error=0
export UBSAN_OPTIONS := halt_on_error=1:print_stacktrace=1

EXTRA_TESTS += fuzz asan

.PHONY: fuzz asan

$(FUZZ_BUILD)/fuzz_config_loader: $(FUZZ_SOURCES) $(wildcard include/rigid_body_sim/*/*.h include/rigid_body_sim/core/types/*.h src/core/types/*.h) | deps
	mkdir -p $(FUZZ_BUILD) && touch $(FUZZ_BUILD)/CATKIN_IGNORE  # keeps catkin_lint out of it
	clang++ -std=c++17 -g -O1 -fsanitize=fuzzer $(SANITIZE) -Iinclude $(FUZZ_SOURCES) -lyaml-cpp -o $@

# New inputs go to a scratch corpus in the build folder; the committed seed corpus stays as it is.
fuzz: deps $(FUZZ_BUILD)/fuzz_config_loader
	rm -rf $(FUZZ_BUILD)/corpus && mkdir -p $(FUZZ_BUILD)/corpus $(FUZZ_BUILD)/artifacts
	@echo "fuzz: $(FUZZ_RUNS) runs of the config loader (at most $(FUZZ_SECONDS) s), log in $(FUZZ_BUILD)/fuzz.log"
	@$(FUZZ_BUILD)/fuzz_config_loader -runs=$(FUZZ_RUNS) -max_total_time=$(FUZZ_SECONDS) -seed=1 \
	  -max_len=4096 -dict=test/fuzz/config.dict -print_final_stats=1 \
	  -artifact_prefix=$(FUZZ_BUILD)/artifacts/ $(FUZZ_BUILD)/corpus test/fuzz/corpus >$(FUZZ_BUILD)/fuzz.log 2>&1 \
	  || { tail -60 $(FUZZ_BUILD)/fuzz.log; echo "fuzz: FAILED, the input is in $(FUZZ_BUILD)/artifacts/"; exit 1; }
	@grep -E "^Done|number_of_executed_units|average_exec_per_sec|new_units_added" $(FUZZ_BUILD)/fuzz.log
	@runs=$$(sed -n 's/^stat::number_of_executed_units: *//p' $(FUZZ_BUILD)/fuzz.log); \
	  [ "$$runs" = "$(FUZZ_RUNS)" ] || { echo "fuzz: FAILED, $$runs of $(FUZZ_RUNS) runs in $(FUZZ_SECONDS) s"; exit 1; }

# gcc's ASan and UBSan; only the unit tests (and the tools they run) are built, and ctest runs them.
# At -Og, gcc's level for debugging (a subset of the -O1 that the sanitizers' docs advise; a load whose value
# is never used may go, as there), with line tables (-g1: every report's frames with file and line):
# compiled in 91 s and run in 37 s here; at -O0 the tests took 71 s (Eigen unoptimized: test_scene 39 s).
asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCATKIN_ENABLE_TESTING=ON -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 \
	  -DCMAKE_CXX_FLAGS="-Og $(SANITIZE)" -DCMAKE_EXE_LINKER_FLAGS="$(SANITIZE)" \
	  -DCMAKE_SHARED_LINKER_FLAGS="$(SANITIZE)" >/dev/null
	cmake --build $(ASAN_BUILD) -j$(JOBS) --target unit_tests -- --no-print-directory
	cd $(ASAN_BUILD) && ctest -j$(JOBS) -L '^unit$$' --no-tests=error --output-on-failure
