# Two entry points: `make demo` and `make test`. Both create .venv when it is missing.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
export NO_MKDOCS_2_WARNING := 1

.PHONY: demo test lint docs chromium postgresql linuxcnc clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(STAMP): $(BIN)/python pyproject.toml
	$(BIN)/python -m pip install --quiet -e '.[test,docs,dask,postgresql]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/axiscal demo --output axiscal-demo

# the layering contract of pyproject.toml (the computing core imports no CLI, plot or web library)
lint: $(STAMP)
	$(BIN)/lint-imports

# the documentation site, built strictly: a broken link or docstring reference fails
docs: $(STAMP)
	$(BIN)/mkdocs build --strict --quiet

# the browser tests drive Debian's chromium headless; install it when we are root, else say how
chromium:
	@command -v chromium >/dev/null 2>&1 || { \
	  if [ "$$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "installing Debian's chromium for the browser tests"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; \
	  else \
	    echo "make test: the browser tests need Debian's chromium: run 'sudo apt-get install chromium', or make test as root"; \
	    exit 1; \
	  fi; }

# the history's tests start a real PostgreSQL server (Debian's postgresql); install it when we are root, else say how
postgresql:
	@{ command -v pg_ctl >/dev/null 2>&1 || ls /usr/lib/postgresql/*/bin/pg_ctl >/dev/null 2>&1; } || { \
	  if [ "$$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "installing Debian's postgresql for the history tests"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq postgresql >/dev/null; \
	  else \
	    echo "make test: the history tests need Debian's postgresql: run 'sudo apt-get install postgresql', or make test as root"; \
	    exit 1; \
	  fi; }

# the devices' tests drive a real LinuxCNC (Debian's linuxcnc-uspace, a headless simulator, run as an ordinary
# user since LinuxCNC refuses root); install it and make that user when we are root, else say how
LINUXCNC_USER := axiscal-sim
linuxcnc:
	@command -v linuxcnc >/dev/null 2>&1 && command -v halsampler >/dev/null 2>&1 || { \
	  if [ "$$(id -u)" = "0" ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "installing Debian's linuxcnc-uspace for the devices tests"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends linuxcnc-uspace >/dev/null; \
	  else \
	    echo "make test: the devices tests need Debian's LinuxCNC: run 'sudo apt-get install --no-install-recommends linuxcnc-uspace', or make test as root"; \
	    exit 1; \
	  fi; }
	@if [ "$$(id -u)" = "0" ] && ! id -u $(LINUXCNC_USER) >/dev/null 2>&1; then \
	  useradd --system --create-home --shell /usr/sbin/nologin $(LINUXCNC_USER); fi

# two workers share the machine (the suite mostly waits on subprocesses, devices and browsers); the
# LinuxCNC tests then run alone, one after another, as a real machine's timing needs
# numba's kernels are compiled once beside the documentation's build (tests/warm_kernels.py; nothing to do when
# their caches are current), not by each worker and command line of the suite; should it fail, the suite compiles them
test: lint chromium postgresql linuxcnc
	@$(BIN)/python tests/warm_kernels.py & warm=$$!; \
	$(MAKE) --no-print-directory docs; docs=$$?; \
	wait $$warm || echo "tests/warm_kernels.py failed: the suite's processes compile numba's kernels themselves"; \
	test $$docs -eq 0
	$(BIN)/python -m pytest -q -n 2 --ignore=tests/devices/test_linuxcnc.py
	$(BIN)/python -m pytest -q tests/devices/test_linuxcnc.py

clean:
	rm -rf $(VENV) axiscal-demo build site src/*.egg-info
