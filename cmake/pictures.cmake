# pictures: filled in by its issue
