# The soak (not part of `make test`): sim_node as fast as possible for a simulated hour, every body
# reconfigured at random every simulated second, recorded to a bag; see docs/reliability.md, "Long runs".
#   make soak [SOAK_SEED=1] [SOAK_DURATION=3600] [SOAK_MAX_SPEED=5]     (report and bag in out/soak/)
SOAK_SEED ?= 1
SOAK_DURATION ?= 3600
SOAK_MAX_SPEED ?= 5

.PHONY: soak

soak: build
	bash scripts/soak --devel $(DEVEL) --seed $(SOAK_SEED) --duration $(SOAK_DURATION) --max-speed $(SOAK_MAX_SPEED)
