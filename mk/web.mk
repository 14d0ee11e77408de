# The web view's pictures, into docs/images (docs/rviz.md, "A lesson in the browser"):
#   make web-screenshot   lesson.launch web:=true in headless Chromium, the page a class sees (no token) after
#                         1.6 s of the race below the critical angles, at 1600x900 and at a phone's 390x844
# Its bench (not part of make bench: it takes a master and a browser's worth of ports):
#   make web-bench        bench/web_load.py: 300 pages, a watching one and a frozen one against the web view; fails
#                         if the watching page gets fewer than 45 frames a second (docs/performance.md)
WEB_PICTURES_OUT = $(BUILD)/pictures/web

.PHONY: web-screenshot web-bench

web-screenshot: build
	source $(DEVEL)/setup.bash && python3 test/web/web_screenshot.py $(WEB_PICTURES_OUT)
	cp $(WEB_PICTURES_OUT)/web_lesson.png $(WEB_PICTURES_OUT)/web_lesson_phone.png docs/images/

web-bench: build
	source $(DEVEL)/setup.bash && python3 bench/web_load.py --window 15
