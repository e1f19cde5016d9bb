#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Beverloo's law fitted to the silo's flow rates (studies/beverloo/run.py).

    W = C rho_b sqrt(g) (D0 - k d)^(5/2)

so that y = (W / (rho_b sqrt(g)))^(2/5) = C^(2/5) (D0 - k d) is a straight
line in D0: slope a = C^(2/5), intercept -a k d. Each run's own rho_b (the
settled column's solid fraction times the grains' density) enters its y.

Intervals, both at 95 %:
  - per seed: the line fitted to each seed's orifices, then the mean of C
    and of k over the seeds with Student's t interval (n_seeds - 1 degrees
    of freedom): the seeds are the independent samples;
  - pooled: the line fitted to all runs, with a bootstrap that resamples
    the runs within each orifice (percentile interval).
Also the pooled fit without the smallest and without the largest orifice
(how much the answer rests on the ends of the range), and C at the
textbook k = 1.5.

    python3 studies/beverloo/analyze.py                  # results.json, results.md, beverloo.png
    python3 studies/beverloo/analyze.py --check 0.5 0.7 1.0 2.0   # exit 1 unless C, k (per-seed means) lie in these ranges
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
G = 9.81
D = 4.0e-3                                   # grain diameter, m (run.py)
# Student's t, two-sided 95 %, by degrees of freedom.
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228}
PUBLISHED = {"C": [0.55, 0.65], "k": [1.3, 1.6]}


def load(path):
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            rows.append({"d0": float(r["d0_m"]), "d0_over_d": float(r["d0_over_d"]), "seed": int(r["seed"]),
                         "w": float(r["w_kg_s"]), "rho_b": float(r["rho_b"]), "phi": float(r["phi"]),
                         "jammed": r["jammed"] == "True", "ratio": float(r["second_half_over_first"]),
                         "wall_s": float(r["wall_s"]) if r.get("wall_s") not in (None, "", "nan") else float("nan")})
    return rows


def y_of(rows):
    return np.array([(r["w"] / (r["rho_b"] * math.sqrt(G))) ** 0.4 for r in rows])


def fit(rows):
    """C and k from a straight line through (D0, y)."""
    x = np.array([r["d0"] for r in rows])
    a, b = np.polyfit(x, y_of(rows), 1)
    return a ** 2.5, -b / (a * D), a, b


def mean_t(values):
    v = np.asarray(values, float)
    n = len(v)
    m = float(v.mean())
    if n < 2:
        return m, float("nan"), [float("nan"), float("nan")]
    se = float(v.std(ddof=1) / math.sqrt(n))
    h = T95.get(n - 1, 1.96) * se
    return m, se, [m - h, m + h]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", default=os.path.join(HERE, "flow_rates.csv"))
    ap.add_argument("--out-dir", default=HERE, help="where results.json, results.md and beverloo.png go")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--bootstrap", type=int, default=4000)
    ap.add_argument("--check", type=float, nargs=4, metavar=("C_LO", "C_HI", "K_LO", "K_HI"),
                    help="exit 1 unless the seeds' mean C and k lie in [C_LO, C_HI] and [K_LO, K_HI]")
    args = ap.parse_args()
    rows = [r for r in load(args.csv)]
    jammed = [r for r in rows if r["jammed"]]
    rows = [r for r in rows if not r["jammed"]]
    seeds = sorted({r["seed"] for r in rows})
    orifices = sorted({r["d0_over_d"] for r in rows})

    per_seed = {}
    for s in seeds:
        rs = [r for r in rows if r["seed"] == s]
        if len({r["d0"] for r in rs}) >= 3:
            c, k, a, b = fit(rs)
            per_seed[s] = {"C": c, "k": k}
    c_mean, c_se, c_ci = mean_t([v["C"] for v in per_seed.values()])
    k_mean, k_se, k_ci = mean_t([v["k"] for v in per_seed.values()])

    c_all, k_all, a_all, b_all = fit(rows)
    rng = np.random.default_rng(12345)
    by_orifice = [[r for r in rows if r["d0_over_d"] == o] for o in orifices]
    boot = []
    for _ in range(args.bootstrap):
        sample = [grp[i] for grp in by_orifice for i in rng.integers(0, len(grp), len(grp))]
        c, k, _, _ = fit(sample)
        boot.append((c, k))
    boot = np.array(boot)
    c_boot = np.percentile(boot[:, 0], [2.5, 97.5]).tolist()
    k_boot = np.percentile(boot[:, 1], [2.5, 97.5]).tolist()

    def fit_without(o):
        rs = [r for r in rows if r["d0_over_d"] != o]
        c, k, _, _ = fit(rs)
        return {"C": c, "k": k}

    # C at the textbook k = 1.5: mean over runs of W / (rho_b sqrt(g) (D0 - 1.5 d)^2.5).
    c_at_15 = [r["w"] / (r["rho_b"] * math.sqrt(G) * (r["d0"] - 1.5 * D) ** 2.5) for r in rows]
    x = np.array([r["d0"] for r in rows])
    resid = y_of(rows) - (a_all * x + b_all)
    table = []
    for o in orifices:
        rs = [r for r in rows if r["d0_over_d"] == o]
        w = np.array([r["w"] for r in rs])
        table.append({"d0_over_d": o, "runs": len(rs), "w_mean_g_s": float(w.mean() * 1e3),
                      "w_sd_g_s": float(w.std(ddof=1) * 1e3) if len(w) > 1 else float("nan"),
                      "phi_mean": float(np.mean([r["phi"] for r in rs])),
                      "second_half_over_first": float(np.mean([r["ratio"] for r in rs])),
                      "w_fit_g_s": float(c_all * np.mean([r["rho_b"] for r in rs]) * math.sqrt(G)
                                         * max(o * D - k_all * D, 0) ** 2.5 * 1e3)})
    res = {
        "law": "W = C rho_b sqrt(g) (D0 - k d)^2.5",
        "d_m": D, "orifices_d0_over_d": orifices, "seeds": seeds, "runs": len(rows),
        "jammed_runs_left_out": [f"D{r['d0_over_d']:g}_s{r['seed']}" for r in jammed],
        "phi_mean": float(np.mean([r["phi"] for r in rows])),
        "rho_b_mean": float(np.mean([r["rho_b"] for r in rows])),
        "per_seed": {str(s): v for s, v in per_seed.items()},
        "C": {"mean_over_seeds": c_mean, "se": c_se, "t95": c_ci, "pooled": c_all, "bootstrap95": c_boot},
        "k": {"mean_over_seeds": k_mean, "se": k_se, "t95": k_ci, "pooled": k_all, "bootstrap95": k_boot},
        "corr_C_k_bootstrap": (float(np.corrcoef(boot[:, 0], boot[:, 1])[0, 1])
                               if boot[:, 0].std() > 0 and boot[:, 1].std() > 0 else None),
        "without_smallest": fit_without(orifices[0]), "without_largest": fit_without(orifices[-1]),
        "C_at_k_1.5": {"mean": float(np.mean(c_at_15)), "sd": float(np.std(c_at_15, ddof=1)),
                       "min": float(min(c_at_15)), "max": float(max(c_at_15))},
        # The scatter about the pooled line, as a spread in D0 / d.
        "rms_residual_in_d0_over_d": float(np.sqrt(np.mean(resid ** 2)) / a_all / D),
        "published": PUBLISHED,
        "table": table,
        "cost_wall_s": float(np.nansum([r["wall_s"] for r in rows + jammed])),
    }
    os.makedirs(args.out_dir, exist_ok=True)
    with open(os.path.join(args.out_dir, "results.json"), "w") as f:
        json.dump(res, f, indent=1)

    lines = ["| D0/d | runs | W (g/s) mean | sd over seeds | phi | 2nd half / 1st half | Beverloo fit (g/s) |",
             "|---:|---:|---:|---:|---:|---:|---:|"]
    for t in table:
        lines.append(f"| {t['d0_over_d']:g} | {t['runs']} | {t['w_mean_g_s']:.2f} | {t['w_sd_g_s']:.2f} | "
                     f"{t['phi_mean']:.3f} | {t['second_half_over_first']:.3f} | {t['w_fit_g_s']:.2f} |")
    lines += ["",
              f"C = {c_mean:.3f} (95 % t over {len(per_seed)} seeds: {c_ci[0]:.3f} to {c_ci[1]:.3f}); "
              f"pooled {c_all:.3f} (bootstrap {c_boot[0]:.3f} to {c_boot[1]:.3f})",
              f"k = {k_mean:.2f} (95 % t over {len(per_seed)} seeds: {k_ci[0]:.2f} to {k_ci[1]:.2f}); "
              f"pooled {k_all:.2f} (bootstrap {k_boot[0]:.2f} to {k_boot[1]:.2f})",
              "per seed: " + ", ".join(f"seed {s}: C = {v['C']:.3f}, k = {v['k']:.2f}" for s, v in per_seed.items()),
              f"without D0 = {orifices[0]:g} d: C = {res['without_smallest']['C']:.3f}, k = {res['without_smallest']['k']:.2f}; "
              f"without D0 = {orifices[-1]:g} d: C = {res['without_largest']['C']:.3f}, k = {res['without_largest']['k']:.2f}",
              f"C at k = 1.5: {res['C_at_k_1.5']['mean']:.3f} (runs from {res['C_at_k_1.5']['min']:.3f} to {res['C_at_k_1.5']['max']:.3f})",
              f"bulk solid fraction {res['phi_mean']:.3f} (rho_b = {res['rho_b_mean']:.0f} kg/m^3); "
              f"jammed runs left out: {res['jammed_runs_left_out'] or 'none'}"]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out_dir, "results.md"), "w") as f:
        f.write(text)
    print(text, end="")

    if not args.no_plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.2))
        y = y_of(rows)
        for s, mk in zip(seeds, "osd^v<>"):
            sel = [i for i, r in enumerate(rows) if r["seed"] == s]
            ax.plot(x[sel] / D, y[sel] / D, mk, mfc="none", label=f"seed {s}")
        xs = np.linspace(0, max(orifices) + 0.5, 50)
        ax.plot(xs, (a_all * xs * D + b_all) / D, "k-", lw=1,
                label=f"fit: C = {c_all:.3f}, k = {k_all:.2f}")
        for c, k, st in [(0.55, 1.3, ":"), (0.65, 1.6, "--")]:
            ax.plot(xs, c ** 0.4 * (xs - k), "C3" + st, lw=1, label=f"C = {c}, k = {k}")
        ax.axhline(0, color="0.6", lw=0.5)
        ax.set_xlim(0, max(orifices) + 0.5)
        ax.set_ylim(-0.3, None)
        ax.set_xlabel("orifice diameter D0 / d")
        ax.set_ylabel(r"$(W / \rho_b \sqrt{g})^{2/5}$ / d")
        ax.set_title("Beverloo: a line with intercept k d")
        ax.legend(fontsize=8)
        w = np.array([r["w"] for r in rows])
        rb = np.mean([r["rho_b"] for r in rows])
        for s, mk in zip(seeds, "osd^v<>"):
            sel = [i for i, r in enumerate(rows) if r["seed"] == s]
            bx.loglog(x[sel] / D, w[sel] * 1e3, mk, mfc="none", label=f"seed {s}")
        xs = np.linspace(min(orifices) - 0.3, max(orifices) + 0.3, 50)
        bx.loglog(xs, c_all * rb * math.sqrt(G) * ((xs - k_all) * D) ** 2.5 * 1e3, "k-", lw=1, label="fit")
        from matplotlib.ticker import NullFormatter, ScalarFormatter
        bx.xaxis.set_major_formatter(ScalarFormatter())
        bx.xaxis.set_minor_formatter(NullFormatter())
        bx.set_xticks(orifices)
        bx.yaxis.set_major_formatter(ScalarFormatter())
        bx.yaxis.set_minor_formatter(NullFormatter())
        bx.set_yticks([t for t in (10, 20, 30, 50, 100, 200, 300, 500, 1000)
                       if 0.8 * w.min() * 1e3 <= t <= 1.25 * w.max() * 1e3])
        bx.set_xlabel("orifice diameter D0 / d")
        bx.set_ylabel("mass flow rate W (g/s)")
        bx.set_title(f"{len(rows)} runs, d = {D*1e3:g} mm glass beads")
        bx.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(args.out_dir, "beverloo.png"), dpi=110)

    if args.check:
        c_lo, c_hi, k_lo, k_hi = args.check
        ok = c_lo <= c_mean <= c_hi and k_lo <= k_mean <= k_hi and not jammed
        print(f"check: C = {c_mean:.3f} in [{c_lo}, {c_hi}], k = {k_mean:.2f} in [{k_lo}, {k_hi}], "
              f"no jam: {'pass' if ok else 'FAIL'}")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
