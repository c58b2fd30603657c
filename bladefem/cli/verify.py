"""``bladefem verify``: FE, Galerkin and closed-form references side by side; exit 1 when a bound is broken."""

from __future__ import annotations

import argparse


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    verify = subparsers.add_parser(
        "verify", help="self-check: FE, Galerkin and closed-form references (exit 1 on a broken bound)",
        description="Compare the finite elements, the Galerkin model and closed-form or published references on "
                    "uniform blades and on the NREL 5MW blade; print one table; exit 1 when a difference exceeds "
                    "its bound.")
    verify.add_argument("--nrel5mw", metavar="ELASTODYN.dat",
                        help="ElastoDyn main file of the NREL 5MW turbine (default: the copy installed with "
                             "bladefem)")
    verify.set_defaults(run=run_verify)


def run_verify(args: argparse.Namespace) -> int:
    from ..verify import NREL5MW_MAIN, format_table, verification_rows

    rows = verification_rows(nrel5mw=args.nrel5mw or NREL5MW_MAIN)
    print(format_table(rows))
    return 0 if all(row.ok for row in rows) else 1
