"""rigid_body_sim's Python package: its messages and services (.msg, .srv), its reconfigure configs (.cfg)
and `rigid_body_sim.testing`, the helpers of another package's tests against the node."""
