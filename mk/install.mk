# The install space as a user gets it: the release build (make build) installed by `cmake --install` into
# INSTALL_SPACE (make build's CMAKE_INSTALL_PREFIX), emptied first so that no file of an earlier install
# stands in for a rule gone; then, with only its setup.bash sourced, rosrun (test/install/check_rosrun.sh),
# the tools, launch files and panel (check_install.sh), and another package's rostests on it
# (check_example.sh, examples/sim_fixture_example).
# And the package in a catkin workspace of its own with the tests off (a temporary folder outside the
# repository, so that no crawler finds the package twice), configured as catkin_make configures it: the
# package needs no test dependency. `make test` runs it before ctest's main suite; `make install-check` alone.
EXTRA_TESTS += install-check
# Outside the repository: roslaunch looks for a launch file anywhere in the package's folder, build/ too, and
# would find each twice. One folder per user and clone, under /tmp.
INSTALL_SPACE ?= /tmp/rigid_body_sim-install-$(shell id -u)-$(shell printf %s '$(CURDIR)' | md5sum | cut -c1-8)

.PHONY: install-check

# cmake --install runs the install rules alone: it builds nothing (make test builds the tests in $(BUILD) at
# the same time).
install-check: build
	rm -rf $(INSTALL_SPACE)
	cmake --install $(BUILD) >$(BUILD)/install.log 2>&1 || { tail -40 $(BUILD)/install.log; exit 1; }
	@ws=$$(mktemp -d /tmp/rigid_body_sim_ws.XXXXXX) && trap 'rm -rf "$$ws"' EXIT && \
	mkdir "$$ws/src" && ln -s "$(CURDIR)" "$$ws/src/rigid_body_sim" && catkin_init_workspace "$$ws/src" >/dev/null && \
	echo "install-check: the package configured in a catkin workspace with the tests off ($$ws)" && \
	{ cmake -S "$$ws/src" -B "$$ws/build" -DCATKIN_DEVEL_PREFIX="$$ws/devel" -DCMAKE_INSTALL_PREFIX="$$ws/install" \
	    -DCATKIN_ENABLE_TESTING=OFF >"$$ws/configure.log" 2>&1 || { tail -40 "$$ws/configure.log"; exit 1; }; }
	bash test/install/check_rosrun.sh $(INSTALL_SPACE)
	bash test/install/check_install.sh $(INSTALL_SPACE)
	bash test/install/check_example.sh $(INSTALL_SPACE) examples/sim_fixture_example
