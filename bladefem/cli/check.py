"""``bladefem check``: modal design requirements of a spec file, PASS/FAIL per requirement; exit 0 when all pass,
1 when any fails, 2 on bad input. JUnit XML (``--junit``) for CI systems, JSON (``--json``) for scripts."""

from __future__ import annotations

import argparse


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    check = subparsers.add_parser(
        "check", help="design checks for CI: frequency windows, resonance margins, soft-stiff band, baselines",
        description="Evaluate the modal requirements of a spec (YAML; see --schema) on the models it names; print a "
                    "table with the measured value, limit, margin and PASS/FAIL of each; exit 0 when all pass, 1 "
                    "when any fails, 2 on bad input.")
    check.add_argument("spec", metavar="SPEC.yaml", nargs="?", help="the spec file")
    check.add_argument("--junit", metavar="FILE.xml", help="also write JUnit XML (one testcase per check)")
    check.add_argument("--json", action="store_true", help="print JSON instead of the table")
    check.add_argument("--update-baseline", action="store_true",
                       help="rewrite the baseline files of the spec from the present results (atomically)")
    check.add_argument("--schema", action="store_true", help="print the spec's JSON Schema and exit")
    check.set_defaults(run=run_check_command)


def run_check_command(args: argparse.Namespace) -> int:
    import os
    import sys

    from ..errors import InputError
    if args.schema:
        from ..check.schema import schema_json
        sys.stdout.write(schema_json())
        return 0
    if args.spec is None:
        raise InputError("give a spec file (or --schema)", field="SPEC.yaml")
    from pathlib import Path

    from ..check import evaluate, read_spec
    from ..check.baseline import read_entries
    from ..check.report import dumps, junit_xml, table
    from ..files import check_writable, note_input, recorded_input, write_atomic
    spec = read_spec(args.spec)
    for model in spec.models.values():           # the files the spec names are inputs: never an output
        for path in (model.input, model.elastodyn_main):
            if path is not None:
                note_input(path)
    baselines: dict[str, Path] = {}                  # one per file, however spelled
    for requirement in spec.requirements:
        if "file" in requirement.parameters:
            baselines.setdefault(os.path.realpath(requirement.parameters["file"]), requirement.parameters["file"])
    for requirement in spec.requirements:
        if "file" in requirement.parameters and recorded_input(requirement.parameters["file"]) is not None:
            raise requirement.error("the baseline file is the spec or a model's input: name a file of its own",
                                    "file")
    for baseline in baselines.values():
        note_input(baseline)
        read_entries(baseline)                       # checked as the input it is, before anything is computed
    if args.junit:
        check_writable(args.junit, field="--junit")
        if os.path.realpath(args.junit) in baselines:   # a baseline not yet written is no input yet, but will be
            raise InputError("is a baseline file of the spec: write the JUnit XML elsewhere", file=args.junit,
                             field="--junit")
    outcomes = evaluate(spec, update_baseline=args.update_baseline)
    if args.junit:
        write_atomic(args.junit, junit_xml(outcomes))
    print(dumps(outcomes) if args.json else table(outcomes), end="" if args.json else "\n")
    return 0 if all(outcome.passed for outcome in outcomes) else 1
