# reliability: filled in by its issue
