# Pictures, into docs/images (README and docs/physics.md):
#   make screenshot   rviz under Xvfb: each launch's view (sim, rod, incline, lesson) checked as the ctests
#                     pictures_rviz_*_view check them, and the panel's Plots tab at the end of pictures_rviz_panel
#   make pictures     the screenshot and the plots of scripts/plot_run.py: demo.yaml (rollers, energy),
#                     incline.yaml (the race) and a sweep of the text's random θ0 (the rod's bounces and
#                     energy drift over θ0 in [0, 2π], 1001 rods of 10 s); the numbers behind them are printed;
#                     and examples/python/text_vs_core.py's figure (docs/python.md)
#   make figures      the figures docs/physics.md and docs/sweeps.md state about those runs, written into them,
#                     the key tables of docs/configuration.md and the event tables of docs/events.md, from the
#                     description
PICTURES_OUT = $(BUILD)/pictures
SIMULATE = $(DEVEL)/lib/rigid_body_sim/simulate
# θ0 = i 2π/1000 (0 and 2π both included): θ0 + π (the same rod, its ends swapped) is on the grid too
THETA0_RODS = 1001

.PHONY: screenshot pictures figures

screenshot: build
	mkdir -p docs/images
	test/pictures/rviz_screenshot.sh $(DEVEL) $(PICTURES_OUT)/rviz.png
	test/pictures/rviz_screenshot.sh $(DEVEL) $(PICTURES_OUT)/rviz_rod.png --launch rod.launch --moments 34
	test/pictures/rviz_screenshot.sh $(DEVEL) $(PICTURES_OUT)/rviz_incline.png --launch incline.launch
	test/pictures/rviz_screenshot.sh $(DEVEL) $(PICTURES_OUT)/rviz_lesson.png --launch lesson.launch
	RVIZ_SCRIPT=rviz_panel.py test/pictures/rviz_screenshot.sh $(DEVEL) $(PICTURES_OUT)/rviz_panel.png \
	  --simulate $(SIMULATE)
	cd $(PICTURES_OUT) && cp rviz.png rviz_rod.png rviz_incline.png rviz_lesson.png rviz_panel.png \
	  $(CURDIR)/docs/images/

pictures: screenshot
	$(SIMULATE) config/demo.yaml --duration 10 --sample-rate 1000 --out-dir $(PICTURES_OUT)/demo >/dev/null
	source $(DEVEL)/setup.bash && python3 scripts/plot_run.py config/demo.yaml $(PICTURES_OUT)/demo --out-dir $(PICTURES_OUT)/plots \
	  --prefix demo_ --figures rollers,energy
	$(SIMULATE) config/incline.yaml --duration 2 --sample-rate 1000 --out-dir $(PICTURES_OUT)/incline >/dev/null
	source $(DEVEL)/setup.bash && python3 scripts/plot_run.py config/incline.yaml $(PICTURES_OUT)/incline --out-dir $(PICTURES_OUT)/plots \
	  --prefix incline_ --figures race
	$(SIMULATE) config/rod.yaml --sweep rod.theta0=0:6.283185307179586:$(THETA0_RODS) --duration 10 \
	  --out-dir $(PICTURES_OUT)/theta0 >/dev/null
	source $(DEVEL)/setup.bash && python3 scripts/plot_run.py config/rod.yaml $(PICTURES_OUT)/theta0 --out-dir $(PICTURES_OUT)/plots \
	  --prefix theta0_
	source $(DEVEL)/setup.bash && python3 examples/python/text_vs_core.py --figure $(PICTURES_OUT)/plots/text_vs_core.png
	cp $(PICTURES_OUT)/plots/text_vs_core.png docs/images/
	cp $(PICTURES_OUT)/plots/demo_rollers.png $(PICTURES_OUT)/plots/demo_energy.png \
	  $(PICTURES_OUT)/plots/incline_race.png $(PICTURES_OUT)/plots/theta0_sweep_rod.png docs/images/
	ls -l docs/images

# The figures docs/physics.md and docs/sweeps.md state about runs, computed from those runs and written into
# the docs (the ctest doc_figures fails while a doc differs).
figures: build
	source $(DEVEL)/setup.bash && python3 scripts/doc_figures.py $(SIMULATE) --write
	$(DEVEL)/lib/rigid_body_sim/describe_body_types --docs docs/configuration.md
	$(DEVEL)/lib/rigid_body_sim/describe_body_types --docs docs/events.md
