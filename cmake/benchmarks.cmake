# benchmarks: filled in by its issue
