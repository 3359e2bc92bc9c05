#!/usr/bin/env python3
"""Markdown table of benches/cholmod/run.sh's runs.jsonl (issue #11).

    python3 table.py runs.jsonl [export.jsonl]

Per matrix and ordering: nnz(L) and flops of both codes, the best
factorisation time over every round for CHOLMOD at 1 and 2 OpenBLAS threads
and for ecc under each thread policy, and the ratio of ecc's best time to
CHOLMOD's reference (METIS, 2 threads: issue #11's 'done when' is <= 0.7).
"""
import json
import os
import sys
from collections import defaultdict


def name(path):
    return os.path.splitext(os.path.basename(path))[0]


def read_runs(path):
    best = defaultdict(lambda: float("inf"))
    info, loads = {}, defaultdict(list)
    with open(path) as f:
        for line in f:
            r = json.loads(line)
            if "solver" not in r:
                continue
            m = name(r["matrix"])
            key = (m, r["solver"], r["ordering"], str(r["threads"]))
            best[key] = min(best[key], r["factor_best_s"])
            # nnz(L) and flops of the plain factor (split's differ: two halves + dense separator)
            if r["solver"] == "cholmod" or r["threads"] == "sequential":
                info[(m, r["solver"], r["ordering"])] = r
            if r.get("load1") is not None and r["load1"] >= 0:
                loads[m].append(r["load1"])
    return best, info, loads


def fmt_t(t):
    return "—" if t == float("inf") else f"{t:.4f}"


def main():
    best, info, loads = read_runs(sys.argv[1])
    elements = {}
    if len(sys.argv) > 2 and os.path.exists(sys.argv[2]):
        with open(sys.argv[2]) as f:
            for line in f:
                r = json.loads(line)
                elements[r["matrix"]] = r["elements"]
    order = ["metis", "amd", "block-amd"]
    known = ["sequential", "parallel", "auto", "split"]
    found = {k[3] for k in best if k[1] == "ecc-faer"}
    policies = [p for p in known if p in found] + sorted(found - set(known))
    print("| matrix | n | nnz(A) | ordering | nnz(L) CHOLMOD / ecc | flops CHOLMOD / ecc "
          "| CHOLMOD 1T s | CHOLMOD 2T s | " + " | ".join(f"ecc {p} s" for p in policies)
          + " | ecc best / CHOLMOD METIS 2T | ecc best / CHOLMOD best | load |")
    print("|" + "---|" * (11 + len(policies)))
    for m in sorted({k[0] for k in best}, key=lambda m: info.get((m, "ecc-faer", "amd"), {}).get("n", 0)):
        ref = best[(m, "cholmod", "metis", "2")]
        cbest = min(t for k, t in best.items() if k[0] == m and k[1] == "cholmod")
        first = True
        for o in order:
            c, e = info.get((m, "cholmod", o)), info.get((m, "ecc-faer", o))
            if not c and not e:
                continue
            any_r = c or e
            nnzl = f"{c['nnz_l']:.3g}" if c else "—"
            nnzl += f" / {e['nnz_l']:.3g}" if e else " / —"
            fl = f"{c['flops']:.3g}" if c else "—"
            fl += f" / {e['flops']:.3g}" if e else " / —"
            ecc = [best[(m, "ecc-faer", o, p)] for p in policies]
            ratio = min(ecc) / ref if e and ref < float("inf") else float("nan")
            ratio_best = min(ecc) / cbest if e else float("nan")
            ls = loads.get(m, [])
            load = f"{min(ls):.1f}–{max(ls):.1f}" if ls and first else ""
            label = f"{m} ({elements[m]} el.)" if first and m in elements else (m if first else "")
            cols = [label, str(any_r["n"]) if first else "", str(any_r["nnz_a"]) if first else "",
                    o, nnzl, fl, fmt_t(best[(m, "cholmod", o, "1")]),
                    fmt_t(best[(m, "cholmod", o, "2")])] + [fmt_t(t) for t in ecc]
            cols += ["—" if x != x else f"{x:.2f}" for x in (ratio, ratio_best)] + [load]
            print("| " + " | ".join(cols) + " |")
            first = False


if __name__ == "__main__":
    main()
