# Contact of elastic bodies with a thin partial coating: Robin DDM in FreeFEM + Python.
#   make run     solve the default scene (shell model, h2 = b/8, E2 = E) into results/default
#   make test    run the tests
# Both install what they need first (FreeFEM from Debian, a pinned Python venv).

PYTHON  := .venv/bin/python
APT_PACKAGES := freefem++ libfreefem++ libglu1-mesa libxcursor1 libxft2 libxinerama1
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: setup run test clean

setup: .venv/.installed .freefem-installed

# FreeFEM and the X11/GL client libraries the gmsh wheel links against, from Debian.
.freefem-installed:
	@if command -v FreeFem++ >/dev/null && [ -e /usr/lib/x86_64-linux-gnu/libGLU.so.1 ]; then \
	  echo "FreeFEM and gmsh's libraries are present"; \
	else \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $(APT_PACKAGES); \
	fi
	@touch $@

.venv/.installed: requirements.txt
	python3 -m venv .venv
	$(PYTHON) -m pip install -q --upgrade pip
	$(PYTHON) -m pip install -q -r requirements.txt
	@touch $@

run: setup
	$(PYTHON) -m orchestrate solve --model shell --h2 0.125 --E2 1 --out results/default
	$(PYTHON) -m orchestrate plot results/default

test: setup
	$(PYTHON) -m pytest -q tests

clean:
	rm -rf results/*/ .pytest_cache
