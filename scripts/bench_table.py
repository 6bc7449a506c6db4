"""Prints a markdown table of Google Benchmark JSON results (scripts/bench table [DIR]).

DIR holds one <name>.json per benchmark program, as scripts/bench writes them; without DIR, the
newest directory under bench/results/. Where a program ran repetitions, the table gives the median
and the coefficient of variation of the repetitions; otherwise each run's own figures. Times are in
the unit the benchmark reports them in; the user counters (unit_frames_per_s, achieved_x, ...) follow
in the last column.
"""
import json
import pathlib
import sys

# Keys of a Google Benchmark result that are not user counters.
STANDARD_KEYS = {"name", "family_index", "per_family_instance_index", "run_name", "run_type",
                 "repetitions", "repetition_index", "threads", "iterations", "real_time",
                 "cpu_time", "time_unit", "aggregate_name", "aggregate_unit", "error_occurred",
                 "error_message", "label"}


def newest_results_dir(root):
    dirs = sorted(d for d in root.iterdir() if d.is_dir()) if root.is_dir() else []
    if not dirs:
        sys.exit(f"bench_table: no results under {root} (scripts/bench writes them)")
    return dirs[-1]


def rows_of(path):
    doc = json.loads(path.read_text())
    benchmarks = doc.get("benchmarks", [])
    aggregated = any(b.get("run_type") == "aggregate" for b in benchmarks)
    rows = []
    for b in benchmarks:
        if aggregated:
            if b.get("run_type") != "aggregate" or b.get("aggregate_name") != "median":
                continue
            cv = next((c for c in benchmarks if c.get("run_name") == b.get("run_name")
                       and c.get("aggregate_name") == "cv"), None)
            runs = f"median of {b.get('repetitions')}"
            spread = f"{100.0 * cv['cpu_time']:.1f} %" if cv else ""
        else:
            runs = f"{b.get('iterations')} iterations"
            spread = ""
        unit = b.get("time_unit", "ns")
        counters = ", ".join(f"{k} {v:.4g}" for k, v in sorted(b.items())
                             if k not in STANDARD_KEYS and isinstance(v, (int, float)))
        rows.append((path.stem, b.get("run_name", b["name"]), f"{b['cpu_time']:.4g} {unit}",
                     f"{b['real_time']:.4g} {unit}", runs, spread, counters))
    return doc.get("context", {}), rows


def main(argv):
    directory = pathlib.Path(argv[1]) if len(argv) > 1 else newest_results_dir(
        pathlib.Path("bench/results"))
    files = sorted(directory.glob("*.json"))
    if not files:
        sys.exit(f"bench_table: no *.json in {directory}")
    contexts = []
    print("| program | benchmark | CPU time | wall time | runs | cv (CPU) | counters |")
    print("|---|---|---|---|---|---|---|")
    for path in files:
        context, rows = rows_of(path)
        contexts.append((path.stem, context))
        for row in rows:
            print("| " + " | ".join(row) + " |")
    print()
    for name, c in contexts:
        load = ", ".join(f"{x:.2f}" for x in c.get("load_avg", []))
        print(f"- {name}: {c.get('date', '?')}, {c.get('host_name', '?')}, "
              f"{c.get('num_cpus', '?')} CPUs at {c.get('mhz_per_cpu', '?')} MHz, "
              f"load average {load or '?'}, Google Benchmark library built as {c.get('library_build_type', '?')}")


if __name__ == "__main__":
    main(sys.argv)
