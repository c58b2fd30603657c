"""pytest plugin (entry point ``pytest11``): ``pytest --bladefem-spec SPEC.yaml`` adds one test per requirement of
the spec; the fixture ``bladefem_check`` evaluates a spec from a test of your own.

    def test_blade_design(bladefem_check):
        outcomes = bladefem_check("design/blade_check.yaml")
        assert all(o.passed for o in outcomes), [o for o in outcomes if not o.passed]

Loading the plugin costs nothing: bladefem's models are imported only when a spec is evaluated.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("bladefem", "bladefem modal design checks")
    group.addoption("--bladefem-spec", action="append", default=[], metavar="SPEC.yaml",
                    help="add one test per requirement of this bladefem check spec (may be repeated)")
    group.addoption("--bladefem-update-baseline", action="store_true",
                    help="rewrite the spec's baseline files from the present results")


class RequirementFailed(Exception):
    """A requirement of a spec is not met; carries the failing outcomes."""


class SpecFile(pytest.File):
    """The requirements of one spec, each a test item; the models are solved once for all of them."""

    def collect(self):
        from . import read_spec
        from .evaluate import model_runs
        spec = read_spec(self.path)
        runs = model_runs(spec)
        for req in spec.requirements:
            yield RequirementItem.from_parent(self, name=req.name, requirement=req, run=runs[req.model])


class RequirementItem(pytest.Item):
    def __init__(self, *, requirement: Any, run: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.requirement = requirement
        self.run = run

    def runtest(self) -> None:
        from .evaluate import evaluate_requirement
        from .report import table
        update = self.config.getoption("bladefem_update_baseline")
        outcomes = evaluate_requirement(self.run, self.requirement, update)
        if not all(o.passed for o in outcomes):
            raise RequirementFailed(table(outcomes))

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> str:
        if isinstance(excinfo.value, RequirementFailed):
            return f"requirement '{self.requirement.name}' not met:\n{excinfo.value}"
        return str(super().repr_failure(excinfo))

    def reportinfo(self) -> tuple[Path, int | None, str]:
        return self.path, self.requirement.line, f"bladefem requirement: {self.requirement.name}"


def pytest_collection_modifyitems(session: pytest.Session, config: pytest.Config, items: list) -> None:
    for spec in config.getoption("bladefem_spec"):
        path = Path(spec).resolve()
        if not path.is_file():
            raise pytest.UsageError(f"--bladefem-spec: no such file: {spec}")
        items.extend(SpecFile.from_parent(session, path=path).collect())


@pytest.fixture
def bladefem_check():
    """``bladefem_check(spec_path, update_baseline=False) -> list[Outcome]``: evaluate a spec."""
    from . import run_check
    return run_check
