# Pictures, into docs/images (README and docs/physics.md):
#   make screenshot   rviz under Xvfb on config/demo.yaml, checked as the ctest pictures_rviz_screenshot checks it
#   make pictures     the screenshot and the plots of scripts/plot_run.py: demo.yaml (rod, rollers, energy)
#                     and incline.yaml (the race); the numbers behind them are printed
PICTURES_OUT = $(BUILD)/pictures
SIMULATE = $(BUILD)/devel/lib/rigid_body_sim/simulate

.PHONY: screenshot pictures

screenshot: build
	mkdir -p docs/images
	test/pictures/rviz_screenshot.sh $(BUILD)/devel $(PICTURES_OUT)/rviz.png
	cp $(PICTURES_OUT)/rviz.png docs/images/rviz.png

pictures: screenshot
	$(SIMULATE) config/demo.yaml --duration 10 --sample-rate 1000 --out-dir $(PICTURES_OUT)/demo >/dev/null
	python3 scripts/plot_run.py config/demo.yaml $(PICTURES_OUT)/demo --out-dir $(PICTURES_OUT)/plots \
	  --prefix demo_ --figures rod,rollers,energy
	$(SIMULATE) config/incline.yaml --duration 2 --sample-rate 1000 --out-dir $(PICTURES_OUT)/incline >/dev/null
	python3 scripts/plot_run.py config/incline.yaml $(PICTURES_OUT)/incline --out-dir $(PICTURES_OUT)/plots \
	  --prefix incline_ --figures race
	cp $(PICTURES_OUT)/plots/demo_rod.png $(PICTURES_OUT)/plots/demo_rollers.png \
	  $(PICTURES_OUT)/plots/demo_energy.png $(PICTURES_OUT)/plots/incline_race.png docs/images/
	ls -l docs/images
