# The install space as a user gets it: the package built by catkin_make in a workspace of its own (a
# temporary folder outside the repository, so that no package crawler finds the package twice), installed
# into that workspace's install/, then run by test/install/check_install.sh with only install/setup.bash
# sourced; rosrun from the workspace's devel and install spaces (check_rosrun.sh); and another package's
# rostests on that install space (check_example.sh, examples/sim_fixture_example). `make test` runs it
# before ctest's main suite; `make install-check` alone.
EXTRA_TESTS += install-check

.PHONY: install-check

install-check: deps
	@ws=$$(mktemp -d /tmp/rigid_body_sim_ws.XXXXXX) && trap 'rm -rf "$$ws"' EXIT && \
	mkdir "$$ws/src" && ln -s "$(CURDIR)" "$$ws/src/rigid_body_sim" && \
	echo "install-check: catkin_make install in $$ws (log: $$ws/build.log)" && \
	{ (cd "$$ws" && catkin_make install -DCATKIN_ENABLE_TESTING=OFF $(RELEASE_FLAGS) -j$(JOBS)) \
	    >"$$ws/build.log" 2>&1 || { tail -40 "$$ws/build.log"; exit 1; }; } && \
	bash test/install/check_rosrun.sh "$$ws/devel" && bash test/install/check_rosrun.sh "$$ws/install" && \
	bash test/install/check_install.sh "$$ws/install" && \
	bash test/install/check_example.sh "$$ws/install" examples/sim_fixture_example
