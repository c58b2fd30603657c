"""``bladefem batch-loads RESULTS``: the fatigue and extreme loads of a DLC 1.2 batch (``turbine_simulate`` cases
over wind speeds and turbulence boxes): per channel the box-averaged damage-equivalent load at each wind speed, the
Weibull-weighted lifetime DEL for the IEC class's mean speed, the extremes; a table and figures."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ..errors import InputError


def add_parser(subparsers: argparse._SubParsersAction) -> None:
    loads = subparsers.add_parser(
        "batch-loads", help="damage-equivalent and extreme loads of a DLC 1.2 batch (turbine_simulate results)",
        description="Per channel of a turbine_simulate batch: the damage-equivalent load at each wind speed "
                    "(rainflow, 1 Hz equivalent cycles over the statistics window, averaged over the turbulence "
                    "boxes with the channel's S-N slope), the lifetime DEL weighted by a Weibull (Rayleigh) "
                    "distribution of the IEC class's annual mean speed, and the extremes.")
    loads.add_argument("results", metavar="RESULTS", help="results folder of 'bladefem batch'")
    loads.add_argument("--iec-class", choices=("I", "II", "III"), default="I",
                       help="IEC wind turbine class: annual mean speed 10, 8.5 or 7.5 m/s at the hub (default I)")
    loads.add_argument("--mean-speed", type=float, default=None, metavar="M_PER_S",
                       help="the annual mean wind speed at the hub instead of the class's, m/s")
    loads.add_argument("--output", "-o", metavar="FILE.csv", help="write the table to FILE.csv")
    loads.add_argument("--plot", metavar="DIR", help="write del.png (DEL over wind speed) and extremes.png")
    loads.set_defaults(run=run_loads_command)


def run_loads_command(args: argparse.Namespace) -> int:
    from ..batch.loads import IEC_MEAN_SPEED, lifetime_loads
    from ..batch.store import ResultStore
    from ..files import write_atomic

    mean = IEC_MEAN_SPEED[args.iec_class] if args.mean_speed is None else args.mean_speed
    if not (math.isfinite(mean) and 0 < mean <= 50):
        raise InputError(f"must be a speed in (0, 50] m/s, got {mean}", field="--mean-speed")
    store = ResultStore(args.results)
    if not store.parts():
        raise InputError("no batch results here", file=str(Path(args.results)))
    table = store.table()
    if "del" not in table.column_names:
        raise InputError("no damage-equivalent loads in these results: a turbine_simulate batch has them",
                         file=str(Path(args.results)))
    rows = [r for r in table.to_pylist() if r.get("status", "ok") == "ok" and r.get("channel")]
    channels = lifetime_loads(rows, mean)
    text = loads_table(channels, mean)
    if args.output:
        write_atomic(args.output, text)
        print(f"# {len(channels)} channels written to {args.output}")
    else:
        print(text, end="")
    if args.plot:
        from ..plots.loads import plot_loads
        for path in plot_loads(channels, args.plot, mean, title=Path(args.results).name):
            print(f"# wrote {path}")
    return 0


def loads_table(channels, mean_speed: float) -> str:
    """CSV: per channel and wind speed the DEL and the Weibull weight; per channel a row ``lifetime`` with the
    lifetime DEL and the extremes."""
    lines = [f"# Weibull (shape 2) of mean {mean_speed:g} m/s at the hub; DEL at 1 Hz equivalent cycles",
             "channel,unit,wohler_m,wind_speed_m_s,weight,del,max,max_at_m_s,min,min_at_m_s"]
    for c in channels:
        for v, w, d in zip(c.speeds, c.weights, c.dels):
            lines.append(f"{c.channel},{c.unit},{c.wohler:g},{v:g},{w:.6g},{d:.6g},,,,")
        lines.append(f"{c.channel},{c.unit},{c.wohler:g},lifetime,1,{c.lifetime_del:.6g},{c.maximum:.6g},"
                     f"{c.maximum_speed:g},{c.minimum:.6g},{c.minimum_speed:g}")
    return "\n".join(lines) + "\n"
