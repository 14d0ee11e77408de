# The web view's pictures, into docs/images (docs/rviz.md, "A lesson in the browser"):
#   make web-screenshot   lesson.launch web:=true in headless Chromium, the page a class sees (no token) after
#                         1.6 s of the race below the critical angles, at 1600x900 and at a phone's 390x844
# Its bench (not part of make bench: it takes a master and a browser's worth of ports):
#   make web-bench        bench/web_load.py: 300 pages, a watching one and a frozen one against the web view; then
#                         60 pages with a lab each on the race (a probe page timing refused requests' replies);
#                         fails if a page gets fewer than 45 frames a second (the class's, or a lab's of its own),
#                         a refused request's reply takes 100 ms or more (99th percentile) with the labs, or the
#                         node's state gaps' median moves by more than 1 ms with them (docs/performance.md).
#                         About 3 minutes.
WEB_PICTURES_OUT = $(BUILD)/pictures/web

.PHONY: web-screenshot web-bench

web-screenshot: build
	source $(DEVEL)/setup.bash && python3 test/web/web_screenshot.py $(WEB_PICTURES_OUT)
	cp $(WEB_PICTURES_OUT)/web_lesson.png $(WEB_PICTURES_OUT)/web_lesson_phone.png docs/images/

web-bench: build
	source $(DEVEL)/setup.bash && python3 bench/web_load.py --window 15 --labs 60
