# make bench: builds in Release with the Google Benchmark suite (build/bench/), runs every measurement (core
# cost, the text's program, the node, recording, sweeps; about 7 min) and writes one table into
# docs/performance.md. BENCH_ARGS=--quick shortens the node runs to 12 s for a try-out.
BENCH_BUILD ?= build/bench
BENCH_ARGS ?=
BENCH_JOBS ?= 2

.PHONY: bench

bench:
	bash scripts/install-deps bench
	cmake -S . -B $(BENCH_BUILD) -DCMAKE_BUILD_TYPE=Release -Drigid_body_sim_BENCHMARKS=ON -DCATKIN_ENABLE_TESTING=OFF >/dev/null
	cmake --build $(BENCH_BUILD) -j$(BENCH_JOBS) -- --no-print-directory
	source $(BENCH_BUILD)/devel/setup.bash && python3 bench/run_bench.py $(BENCH_BUILD) $(BENCH_ARGS)
