"""The house's rules that no single room can check: no two modules of one package import each other, and modules stay a size a reader can hold.

A split follows a seam: the part others build on below, the part that uses it above. The layers
contract in pyproject.toml orders the rooms; the ``acyclic_siblings`` contract forbids a circle
inside any package. These tests check the package itself and that the contract, as written,
refuses a new circle.
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import grimp

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "axiscal"
#: the most lines a module may have before it is split by meaning
MAX_LINES = 600
#: modules still over MAX_LINES, each with the reason it is not split yet
NOT_YET_SPLIT = {
    "instruments/optics.py": "ray tracing through prisms; grew past the limit after the last count",
}


def _circle_contract() -> dict:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    contracts = config["tool"]["importlinter"]["contracts"]
    found = [c for c in contracts if c["type"] == "acyclic_siblings"]
    assert len(found) == 1, "pyproject.toml must hold one acyclic_siblings contract"
    return found[0]


def test_no_two_modules_of_one_package_import_each_other():
    graph = grimp.build_graph("axiscal")
    packages = sorted(m for m in graph.modules if graph.find_children(m))
    circles = {p: sorted(graph.nominate_cycle_breakers(p)) for p in packages}
    assert {p: c for p, c in circles.items() if c} == {}


def test_the_contract_covers_every_package_of_axiscal():
    contract = _circle_contract()
    assert contract["ancestors"] == ["axiscal"]
    assert contract.get("depth", 10) >= max(len(p.relative_to(PACKAGE).parts) for p in PACKAGE.rglob("*.py"))


def test_the_contract_as_written_refuses_a_circle_inside_a_sub_package(tmp_path):
    room = tmp_path / "house" / "room"
    room.mkdir(parents=True)
    (tmp_path / "house" / "__init__.py").write_text("")
    (room / "__init__.py").write_text("")
    (room / "lower.py").write_text("from house.room import upper\n")
    (room / "upper.py").write_text("from house.room import lower\n")
    contract = _circle_contract()
    config = tmp_path / "contracts.toml"
    config.write_text(
        '[tool.importlinter]\nroot_package = "house"\n\n[[tool.importlinter.contracts]]\n'
        f'name = "circles"\ntype = "{contract["type"]}"\nancestors = ["house"]\n',
        encoding="utf-8",
    )
    lint = Path(sys.executable).parent / "lint-imports"
    run = subprocess.run([str(lint), str(config), "--no-cache"], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode != 0
    assert "No cycles are allowed in house.room" in run.stdout + run.stderr

    (room / "lower.py").write_text("")
    run = subprocess.run([str(lint), str(config), "--no-cache"], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr


def test_every_module_stays_under_the_size_limit():
    lines = {str(p.relative_to(PACKAGE)): p.read_text(encoding="utf-8").count("\n") for p in PACKAGE.rglob("*.py")}
    over = {module: n for module, n in sorted(lines.items()) if n > MAX_LINES and module not in NOT_YET_SPLIT}
    assert over == {}, "split these by meaning, along a seam"
