#!/usr/bin/env python3
"""The speed bench's table and plot (docs/performance.md), from the result directories of repeated
`dtsl run configs/bench_speed.yaml` runs: per dataset and pipeline the best time of the repeats (and the
peak memory and stage times of that run), what the time bought (chamfer to the truth, closed, genus
against the truth's), then dtsl's time over each other pipeline's, and where dtsl's time goes.

    bench/speed_table.py DIR [DIR ...] [--plot FILE.png] [--json FILE.jsonl]

Markdown on stdout. A run that failed in every repeat shows its status (e.g. "skipped: ... not found").
"""
import argparse
import glob
import json
import os
import sys


def load(dirs):
    """{(dataset, pipeline): [record, ...]} over the repeats, in the config's order."""
    runs, order = {}, []
    for d in dirs:
        files = sorted(glob.glob(os.path.join(d, "runs", "*", "metrics.json")))
        if not files:
            sys.exit(f"speed_table: no runs/*/metrics.json under {d}")
        for f in files:
            with open(f) as fh:
                r = json.load(fh)
            key = (r["dataset"], r["pipeline"])
            if key not in runs:
                runs[key] = []
                order.append((r.get("order", 0), key))
            runs[key].append(r)
    return runs, [k for _, k in sorted(order, key=lambda x: x[0])]


def best(records):
    ok = [r for r in records if r.get("status") == "ok" and "time_total" in r]
    if not ok:
        return records[0], 0
    return min(ok, key=lambda r: r["time_total"]), len(ok)


def get(r, *path):
    for p in path:
        if not isinstance(r, dict) or p not in r:
            return None
        r = r[p]
    return r


def fmt(x, spec="{:.2f}"):
    return "–" if x is None else spec.format(x)


def stage_seconds(r, name):
    for s in r.get("stages", []):
        if s.get("name") == name:
            return s.get("seconds")
    return None


def inner_parts(r):
    """Where dtsl's time goes inside TL and D-Map, from the records the pipeline keeps."""
    parts = {}
    for s in r.get("stages", []):
        m = s.get("summary", {})
        if s.get("name") == "TL":
            for k, v in (m.get("evolution_timings") or {}).items():
                parts["evolution_" + k] = v
            if "final_refinement" in m and isinstance(m["final_refinement"], dict):
                parts["final_refinement"] = m["final_refinement"].get("seconds")
            if "refinement_guard" in m:
                parts["refinement_guard"] = m["refinement_guard"].get("seconds")
            parts["iterations"] = m.get("iterations")
        if s.get("name") == "D-Map" and "refinement_round_seconds" in m:
            parts["flip_rounds"] = sum(v for rnd in m["refinement_round_seconds"] for v in rnd.values())
    return parts


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--plot")
    ap.add_argument("--json")
    a = ap.parse_args()
    runs, keys = load(a.dirs)
    datasets = list(dict.fromkeys(k[0] for k in keys))
    pipelines = list(dict.fromkeys(k[1] for k in keys))
    bests = {k: best(v) for k, v in runs.items()}

    print(f"Best of {len(a.dirs)} runs each ({', '.join(a.dirs)}).\n")
    print("| dataset | points | pipeline | time (s) | peak (MiB) | chamfer (1e-3) | closed | genus (truth) | status |")
    print("| --- | ---: | --- | ---: | ---: | ---: | --- | --- | --- |")
    for d in datasets:
        for p in pipelines:
            if (d, p) not in bests:
                continue
            r, n_ok = bests[(d, p)]
            ok = r.get("status") == "ok"
            chamfer = get(r, "final", "surface", "chamfer")
            genus, truth = get(r, "final", "mesh", "genus"), get(r, "truth_mesh", "genus")
            closed = get(r, "final", "mesh", "watertight")
            status = "ok" if ok else (r.get("error") or r.get("status", "?")).split("\n")[0][:80]
            print(f"| {d} | {r.get('np', '–')} | {p} | {fmt(r.get('time_total') if ok else None)} | "
                  f"{fmt(r.get('peak_memory_mib') if ok else None, '{:.0f}')} | "
                  f"{fmt(None if chamfer is None else 1e3 * chamfer)} | "
                  f"{'–' if closed is None else ('yes' if closed else 'no')} | "
                  f"{'–' if genus is None else genus} ({'–' if truth is None else truth}) | {status} |")

    others = [p for p in pipelines if p != "dtsl"]
    print("\ndtsl's time over each pipeline's (below 1: dtsl is faster):\n")
    print("| dataset | points | " + " | ".join(f"dtsl / {p}" for p in others) + " |")
    print("| --- | ---: |" + " ---: |" * len(others))
    for d in datasets:
        if (d, "dtsl") not in bests:
            continue
        r, _ = bests[(d, "dtsl")]
        cells = []
        for p in others:
            o = bests.get((d, p), (None, 0))[0]
            ok = o and o.get("status") == "ok" and r.get("status") == "ok"
            cells.append(fmt(r["time_total"] / o["time_total"] if ok else None))
        print(f"| {d} | {r.get('np', '–')} | " + " | ".join(cells) + " |")

    for p in [p for p in pipelines if p.startswith("dtsl")]:
        print(f"\nWhere {p}'s time goes (s; evolution parts from the TL record, flip rounds from D-Map):\n")
        print("| dataset | TL | MT | D-Map | B-Evl | steps | solve | rows | zero-set sampling | final refinement | "
              "refinement guard | flip rounds |")
        print("| --- |" + " ---: |" * 11)
        for d in datasets:
            if (d, p) not in bests or bests[(d, p)][0].get("status") != "ok":
                continue
            r = bests[(d, p)][0]
            q = inner_parts(r)
            print(f"| {d} | " + " | ".join(fmt(stage_seconds(r, s)) for s in ("TL", "MT", "D-Map", "B-Evl")) +
                  f" | {fmt(q.get('iterations'), '{}')} | {fmt(q.get('evolution_solve'))} | "
                  f"{fmt(q.get('evolution_rows'))} | {fmt(q.get('evolution_zero_set_sampling'))} | "
                  f"{fmt(q.get('final_refinement'))} | {fmt(q.get('refinement_guard'))} | {fmt(q.get('flip_rounds'))} |")

    if a.json:
        with open(a.json, "w") as fh:
            for (d, p), (r, n_ok) in bests.items():
                fh.write(json.dumps({"dataset": d, "pipeline": p, "np": r.get("np"), "repeats_ok": n_ok,
                                     "status": r.get("status"), "error": r.get("error"),
                                     "seconds": r.get("time_total"), "peak_memory_mib": r.get("peak_memory_mib"),
                                     "chamfer": get(r, "final", "surface", "chamfer"),
                                     "stages": {s["name"]: s.get("seconds") for s in r.get("stages", [])}}) + "\n")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
        for p in pipelines:
            pts = sorted((bests[(d, p)][0]["np"], bests[(d, p)][0]["time_total"]) for d in datasets
                         if (d, p) in bests and bests[(d, p)][0].get("status") == "ok")
            if pts:
                ax.plot([x for x, _ in pts], [y for _, y in pts], marker="o", label=p,
                        linewidth=2.2 if p.startswith("dtsl") else 1.2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("points")
        ax.set_ylabel("whole job (s), best of %d" % len(a.dirs))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(a.plot)


if __name__ == "__main__":
    main()
