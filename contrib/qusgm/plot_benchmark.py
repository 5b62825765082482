#!/usr/bin/python3
"""Plots of the QuSGM benchmark (contrib/benchmarks/qusgm): cost of one
increment against N, and error of the increment's stress change against
wall time for the minimisers and stopping tests.

Usage: plot_benchmark.py scaling.csv accuracy.csv out.png
"""
import csv
import sys

try:
    import matplotlib
except ImportError:
    raise SystemExit(f"{sys.argv[0]}: needs matplotlib, which {sys.executable} does not have "
                     "(Debian: apt-get install python3-matplotlib; run the script with /usr/bin/python3)")
matplotlib.use("Agg")
import matplotlib.pyplot as plt


def rows(path):
    with open(path) as f:
        return [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]


def main():
    scaling, accuracy, out = sys.argv[1:4]
    fig, axes = plt.subplots(1, 4, figsize=(18, 4.4))
    s = rows(scaling)
    for name, style in (("nlcg paper 1e-11/1e-13", "o-"), ("lbfgs force 1e-4", "s-"),
                        ("reference lbfgs 1e-9", "^--")):
        sel = [r for r in s if r["method"] == name]
        if sel:
            axes[0].loglog([int(r["grains"]) for r in sel], [float(r["seconds"]) for r in sel],
                           style, label=name)
    ns = sorted({int(r["grains"]) for r in s})
    if ns:
        ref = [r for r in s if r["method"] == "lbfgs force 1e-4"]
        if ref:
            mid = ref[len(ref) // 2]
            t0, n0 = float(mid["seconds"]), int(mid["grains"])
            axes[0].loglog(ns, [t0 * n / n0 for n in ns], "k:", label="linear in N")
    axes[0].set_xlabel("grains N")
    axes[0].set_ylabel("wall time of one increment [s]")
    axes[0].set_title("uniaxial increment 1e-4")
    axes[0].legend(fontsize=7)
    a = rows(accuracy)
    families = (("nlcg paper", "o", "C0"), ("nlcg force", "v", "C1"),
                ("lbfgs force", "s", "C2"), ("lbfgs increment force", "D", "C3"))
    for ax, d_eps in zip(axes[1:], ("5e-05", "0.0001", "0.0005")):
        for prefix, marker, colour in families:
            sel = [r for r in a if r["strain_increment"] == d_eps and
                   r["method"].startswith(prefix) and
                   not (prefix == "lbfgs force" and "increment" in r["method"])]
            pts = [(float(r["seconds"]), max(float(r["stress_change_error"]), 1e-9), r["method"])
                   for r in sel]
            if pts:
                ax.loglog([p[0] for p in pts], [p[1] for p in pts], marker, color=colour,
                          label=prefix, ls="-")
                for t, e, m in pts:
                    ax.annotate(m.split()[-1], (t, e), fontsize=6)
        ax.axhline(1e-3, color="k", ls=":", lw=0.8)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("relative error of the stress change")
        ax.set_title(f"2740 grains, increment {d_eps}")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
