# A one-node Slurm on this machine (docs/cluster.md):
#   make cluster-up      starts munged, slurmctld and slurmd in $(CLUSTER_DIR); then
#                        export SLURM_CONF=$(CLUSTER_DIR)/slurm.conf for sbatch, squeue and scripts/slurm_sweep
#   make cluster-down    stops them (their pid files) and removes $(CLUSTER_DIR)
CLUSTER_DIR ?= $(abspath $(BUILD))/cluster

.PHONY: cluster-up cluster-down

cluster-up: deps
	bash scripts/local_slurm up $(CLUSTER_DIR)

cluster-down:
	bash scripts/local_slurm down $(CLUSTER_DIR)
