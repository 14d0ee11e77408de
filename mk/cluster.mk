# A one-node Slurm on this machine and a sweep through it (docs/cluster.md):
#   make cluster-up      starts munged, slurmctld and slurmd in $(CLUSTER_DIR); then
#                        export SLURM_CONF=$(CLUSTER_DIR)/slurm.conf for sbatch, squeue and scripts/slurm_sweep
#   make cluster-down    stops them (their pid files) and removes $(CLUSTER_DIR)
#   make cluster-test    a cluster of its own in $(CLUSTER_TEST_DIR): 10,000 rods in 8 shards through
#                        scripts/slurm_sweep, byte for byte the single-machine sweep; then a failing shard
CLUSTER_DIR ?= $(abspath $(BUILD))/cluster
CLUSTER_TEST_DIR ?= $(abspath $(BUILD))/cluster-test

# part of `make test`: reliable and about 20 s (the measurements are in docs/cluster.md)
EXTRA_TESTS += cluster-test

.PHONY: cluster-up cluster-down cluster-test

cluster-up: deps
	bash scripts/local_slurm up $(CLUSTER_DIR)

cluster-down:
	bash scripts/local_slurm down $(CLUSTER_DIR)

cluster-test: build
	bash test/cluster/cluster_test.sh $(DEVEL) $(CLUSTER_TEST_DIR)
