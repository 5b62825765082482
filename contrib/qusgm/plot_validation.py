#!/usr/bin/python3
"""K and G of a QuSGM pack against the confining stress, with the effective
medium theory (Walton/Digby) for the same grains and the coordination and
solid fraction at the end of the runs given, averaged over them (give one
file for a pack's own); prints the fitted growth exponents.

Usage: plot_validation.py out.png mu=0.3:file.csv [mu=0.5:file.csv ...]
"""
import csv
import math
import sys

try:
    import matplotlib
except ImportError:
    raise SystemExit(f"{sys.argv[0]}: needs matplotlib, which {sys.executable} does not have "
                     "(Debian: apt-get install python3-matplotlib; run the script with /usr/bin/python3)")
matplotlib.use("Agg")
import matplotlib.pyplot as plt

E, NU = 70e9, 0.2
G_GRAIN = E / (2 * (1 + NU))


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = []
    for r in rows:
        try:  # an undefined modulus or sliding ratio is an empty field: skip the row
            k, g = float(r["bulk_modulus"]), float(r["shear_modulus"])
            sliding = float(r["sliding_ratio"])
        except ValueError:
            continue
        out.append(dict(stage=r["stage"], s=float(r["confining_stress"]), k=k, g=g,
                        z=float(r["coordination_number"]),
                        phi=float(r.get("solid_fraction", 0.64)),
                        sliding=sliding))
    return out


def emt_k(p, z, phi):
    return (z * z * phi * phi * G_GRAIN ** 2 * p / (18 * math.pi ** 2 * (1 - NU) ** 2)) ** (1 / 3)


def slope(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = len(lx)
    mx, my = sum(lx) / n, sum(ly) / n
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    out = sys.argv[1]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    colours = ["C0", "C1", "C2", "C3", "C4"]
    smin, smax = 1e9, 0
    zs, phis = [], []
    for index, spec in enumerate(sys.argv[2:]):
        label, path = spec.split(":", 1)
        rows = read(path)
        c = colours[index % len(colours)]
        for stage, marker, fill in (("activation", "o", "none"), ("test", "s", None)):
            sel = [r for r in rows if r["stage"] == stage and r["k"] > 0]
            if not sel:
                continue
            s = [r["s"] * 1e-6 for r in sel]
            kw = dict(color=c, marker=marker, ms=3, ls="none")
            if fill:
                kw["markerfacecolor"] = fill
            axes[0].plot(s, [r["k"] * 1e-9 for r in sel], label=f"{label} {stage}", **kw)
            axes[1].plot(s, [r["g"] * 1e-9 for r in sel], label=f"{label} {stage}", **kw)
            axes[2].plot(s, [r["sliding"] for r in sel], label=f"{label} {stage}", **kw)
            smin, smax = min(smin, min(s)), max(smax, max(s))
        test = [r for r in rows if r["stage"] == "test" and r["k"] > 0 and r["g"] > 0]
        if len(test) > 4:
            s = [r["s"] for r in test]
            half = len(test) // 2
            print(f"{label}: test stage sigma_c {min(s)*1e-6:.1f}-{max(s)*1e-6:.1f} MPa, "
                  f"K {test[0]['k']*1e-9:.3f}->{test[-1]['k']*1e-9:.3f} GPa, "
                  f"G {test[0]['g']*1e-9:.3f}->{test[-1]['g']*1e-9:.3f} GPa, "
                  f"exponent K {slope(s, [r['k'] for r in test]):.2f} "
                  f"(first half {slope(s[:half], [r['k'] for r in test[:half]]):.2f}, "
                  f"second {slope(s[half:], [r['k'] for r in test[half:]]):.2f}), "
                  f"G {slope(s, [r['g'] for r in test]):.2f}, "
                  f"Z {test[-1]['z']:.2f}, phi {test[-1]['phi']:.3f}, "
                  f"sliding {test[-1]['sliding']:.3f}")
            zs.append(test[-1]["z"])
            phis.append(test[-1]["phi"])
    if zs:
        z, phi = sum(zs) / len(zs), sum(phis) / len(phis)
        ps = [smin + (smax - smin) * i / 50 for i in range(51)]
        k = [emt_k(p * 1e6, z, phi) * 1e-9 for p in ps]
        axes[0].plot(ps, k, "k-", label=f"EMT (Z={z:.2f}, phi={phi:.3f})")
        axes[1].plot(ps, [x * 3 * (5 - 4 * NU) / (5 * (2 - NU)) for x in k], "k-",
                     label="EMT rough")
        axes[1].plot(ps, [x * 3 / 5 for x in k], "k--", label="EMT smooth")
        for p in (10, 20):
            kk = emt_k(p * 1e6, z, phi)
            print(f"EMT at {p} MPa (Z={z:.2f}, phi={phi:.3f}): K {kk*1e-9:.3f} GPa, "
                  f"G_rough {kk*3*(5-4*NU)/(5*(2-NU))*1e-9:.3f}, G_smooth {0.6*kk*1e-9:.3f} GPa")
    for ax, name in zip(axes, ("K [GPa]", "G [GPa]", "sliding ratio")):
        ax.set_xlabel("confining stress sigma_c [MPa]")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize=7)
    fig.suptitle("QuSGM G2740-like pack (2740 glass beads): moduli during friction "
                 "activation (open) and uniaxial-strain test (filled)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
