# Two entry points: `make demo` and `make test`. Both create .venv when it is missing.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
export NO_MKDOCS_2_WARNING := 1

.PHONY: demo test lint docs clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(STAMP): $(BIN)/python pyproject.toml
	$(BIN)/python -m pip install --quiet -e '.[test,docs,dask]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/axiscal demo --output axiscal-demo

# the layering contract of pyproject.toml (the computing core imports no CLI, plot or web library)
lint: $(STAMP)
	$(BIN)/lint-imports

# the documentation site, built strictly: a broken link or docstring reference fails
docs: $(STAMP)
	$(BIN)/mkdocs build --strict --quiet

test: lint docs
	$(BIN)/python -m pytest -q

clean:
	rm -rf $(VENV) axiscal-demo build site src/*.egg-info
