#!/usr/bin/python3
"""The sliding fraction of QuSGM against the paper (Holtzman et al. 2010,
Fig. 4: it saturates at 0.09-0.11 for G2740 with mu = 0.3): one difference
at a time, on one pack.

A pack is generated and compacted without friction (the paper's stage (a))
once; every variant then continues from that same state with friction and
uniaxial-strain increments (stage (b) and the test, one path as in the
paper's Fig. 4). Writes, in the work directory (default
output/sliding_study):
  pack/                        the frictionless pack (prepared_state/)
  <variant>/increments.csv     one run per variant
  sliding_study.csv            per variant: sliding ratio (mean over the last
                               fifth of the path, and its largest), K and G
                               at the confining stresses listed, exponents
  sliding_study.md             the same as a Markdown table
  sliding_study.png            sliding ratio, K and G against sigma_c with EMT

Usage: sliding_study.py [--sable build/sable] [--work output/sliding_study]
                        [--grains 400] [--increments 80] [--target 4e6]
                        [--compaction-strain 4e-3] [--variants name,name,...]
                        [--plot-only]
"""
import argparse
import csv
import math
import os
import subprocess
import sys

try:
    import matplotlib
except ImportError:
    raise SystemExit(f"{sys.argv[0]}: needs matplotlib (Debian: python3-matplotlib; "
                     "run the script with /usr/bin/python3)")
matplotlib.use("Agg")
import matplotlib.pyplot as plt

E, NU = 70e9, 0.2
G_GRAIN = E / (2 * (1 + NU))

# One difference from the baseline each (Contact/... entries), then the
# combination that reproduces the paper's count, also with mu = 0.5.
VARIANTS = {
    "baseline": {},
    "cap_current": {"Contact/Friction cap": "current"},
    "stick_slip_per_increment": {"Contact/Stick-slip decision": "per increment"},
    "stick_slip_per_increment_affine": {"Contact/Stick-slip decision": "per increment",
                                        "Minimizer/Initial guess": "affine"},
    "stick_slip_per_increment_10_sub": {"Contact/Stick-slip decision": "per increment",
                                        "Minimizer/Initial guess": "affine",
                                        "Minimizer/Wall sub-increments": "10"},
    "count_tolerance_1pct": {"Contact/Sliding tolerance": "0.01"},
    "count_eq7b": {"Contact/Sliding count": "eq. 7b"},
    "walls_frictionless": {"Contact/Wall friction coefficient": "0"},
    # the same total strain in increments five times larger and half as large
    "increments_5x": {"Load path/Strain increment": "5x", "Load path/Number of increments": "/5"},
    "increments_half": {"Load path/Strain increment": "0.5x",
                        "Load path/Number of increments": "*2"},
    "baseline_mu0.5": {"Contact/Friction coefficient": "0.5",
                       "Contact/Wall friction coefficient": "0.5"},
    "count_eq7b_mu0.5": {"Contact/Sliding count": "eq. 7b",
                         "Contact/Friction coefficient": "0.5",
                         "Contact/Wall friction coefficient": "0.5"},
}

# The paper (G2740, mu = 0.3): sliding ratio at saturation; growth exponent
# of the moduli from 0.45 (low sigma_c) to 0.33 (high).
PAPER_SLIDING = (0.09, 0.11)


def write_prm(path, entries):
    sections = {}
    top = []
    for key, value in entries.items():
        if "/" in key:
            section, entry = key.split("/", 1)
            sections.setdefault(section, []).append((entry, value))
        else:
            top.append((key, value))
    lines = [f"set {k} = {v}" for k, v in top]
    for section, items in sections.items():
        lines.append(f"subsection {section}")
        lines += [f"  set {k} = {v}" for k, v in items]
        lines.append("end")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


COMMON = {
    "Model": "qusgm",
    "Walls/Young's modulus": "7e12",
    "Walls/Poisson's ratio": "0.495",
    "Contact/Friction coefficient": "0.3",
    "Contact/Wall friction coefficient": "0.3",
    "Contact/Torsion": "true",
    "Minimizer/Method": "lbfgs",
    "Minimizer/Wall sub-increments": "1",
    "Minimizer/Initial guess": "previous increment",
    "Minimizer/Energy tolerance": "0",
    "Minimizer/Gradient tolerance": "0",
    "Minimizer/Force tolerance": "1e-5",
    "Output/VTU increments": "none",
}


def run_sable(sable, prm):
    result = subprocess.run([sable, prm], capture_output=True, text=True)
    if result.returncode != 0:
        raise SystemExit(f"{sable} {prm} failed:\n{result.stdout[-3000:]}{result.stderr[-3000:]}")


def prepare_pack(args):
    directory = os.path.join(args.work, "pack")
    state = os.path.join(directory, "prepared_state")
    if os.path.isdir(state):
        return os.path.abspath(state)
    os.makedirs(args.work, exist_ok=True)
    entries = dict(COMMON)
    entries.update({
        "Output directory": os.path.abspath(directory),
        "Pack/Source": "generate",
        "Pack/Number of grains": str(args.grains),
        "Pack/Random seed": str(args.seed),
        "Preparation/Enabled": "true",
        "Preparation/Target confining stress": str(args.target),
        "Preparation/Friction activation": "false",
        "Load path/Number of increments": "0",
        "Preparation/Compaction strain increment": str(args.compaction_strain),
    })
    prm = os.path.join(args.work, "pack.prm")
    write_prm(prm, entries)
    run_sable(args.sable, prm)
    return os.path.abspath(state)


def run_variant(args, state, name):
    directory = os.path.join(args.work, name)
    table = os.path.join(directory, "increments.csv")
    if os.path.isfile(table):
        return table
    entries = dict(COMMON)
    entries.update({
        "Output directory": os.path.abspath(directory),
        "Pack/Source": "state",
        "Pack/File": state,
        "Preparation/Enabled": "false",
        "Load path/Type": "uniaxial strain",
        "Load path/Axis": "z",
        "Load path/Strain increment": str(args.strain),
        "Load path/Number of increments": str(args.increments),
    })
    for key, value in VARIANTS[name].items():
        if value.endswith("x"):  # a multiple of the strain increment
            value = str(float(value[:-1]) * args.strain)
        elif value[0] in "*/":  # of the number of increments
            n = args.increments
            value = str(n * int(value[1:]) if value[0] == "*" else n // int(value[1:]))
        entries[key] = value
    prm = os.path.join(args.work, name + ".prm")
    write_prm(prm, entries)
    run_sable(args.sable, prm)
    return table


def read(path):
    rows = []
    with open(path) as f:
        for r in csv.DictReader(f):
            def value(key):
                return float(r[key]) if r[key] not in ("", "nan") else math.nan
            rows.append(dict(s=value("confining_stress"), k=value("bulk_modulus"),
                             g=value("shear_modulus"), sliding=value("sliding_ratio"),
                             z=value("coordination_number"), phi=value("solid_fraction"),
                             it=value("iterations")))
    return rows


def emt_k(p, z, phi):
    return (z * z * phi * phi * G_GRAIN ** 2 * p / (18 * math.pi ** 2 * (1 - NU) ** 2)) ** (1 / 3)


def slope(xs, ys):
    pairs = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(pairs) < 3:
        return math.nan
    mx = sum(p[0] for p in pairs) / len(pairs)
    my = sum(p[1] for p in pairs) / len(pairs)
    return (sum((a - mx) * (b - my) for a, b in pairs) /
            sum((a - mx) ** 2 for a, _ in pairs))


def at_stress(rows, key, s):
    """Mean of `key` over the rows within 10% of sigma_c = s (the moduli of
    single increments scatter)."""
    values = [r[key] for r in rows if abs(r["s"] - s) <= 0.1 * s and math.isfinite(r[key])]
    return sum(values) / len(values) if values else math.nan


def summarise(args, tables):
    out = os.path.join(args.work, "sliding_study.csv")
    stresses = [float(s) for s in args.stresses.split(",")]
    header = (["variant", "sliding_saturated", "sliding_max"] +
              [f"K_{s/1e6:g}MPa" for s in stresses] + [f"G_{s/1e6:g}MPa" for s in stresses] +
              ["K_exponent", "G_exponent", "sigma_c_end", "mean_iterations"])
    summary = []
    for name, path in tables.items():
        rows = read(path)
        last = rows[-max(3, len(rows) // 5):]
        sliding = sum(r["sliding"] for r in last) / len(last)
        # exponents over the second half of the path (friction developed)
        half = rows[len(rows) // 2:]
        good = [r for r in half if r["k"] > 0 and r["g"] > 0]
        summary.append([name, sliding, max(r["sliding"] for r in rows)] +
                       [at_stress(rows, "k", s) for s in stresses] +
                       [at_stress(rows, "g", s) for s in stresses] +
                       [slope([r["s"] for r in good], [r["k"] for r in good]),
                        slope([r["s"] for r in good], [r["g"] for r in good]),
                        rows[-1]["s"], sum(r["it"] for r in rows) / len(rows)])
    with open(out, "w") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for line in summary:
            writer.writerow([line[0]] + [f"{x:.4g}" for x in line[1:]])
    print(open(out).read(), end="")
    # the same as a Markdown table (GPa)
    n = len(stresses)
    mpa = " / ".join(f"{s/1e6:g}" for s in stresses)
    with open(os.path.join(args.work, "sliding_study.md"), "w") as f:
        f.write(f"| variant | sliding ratio (end) | largest | K at {mpa} MPa [GPa] | "
                f"G at {mpa} MPa [GPa] | exponent K | exponent G |\n")
        f.write("|---|---|---|---|---|---|---|\n")
        for line in summary:
            k = " / ".join(f"{x*1e-9:.3f}" for x in line[3:3 + n])
            g = " / ".join(f"{x*1e-9:.3f}" for x in line[3 + n:3 + 2 * n])
            f.write(f"| {line[0]} | {line[1]:.4f} | {line[2]:.4f} | {k} | {g} | "
                    f"{line[3 + 2*n]:.2f} | {line[4 + 2*n]:.2f} |\n")
    return out


def plot(args, tables):
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    smin, smax, zs, phis = 1e99, 0, [], []
    for index, (name, path) in enumerate(tables.items()):
        rows = read(path)
        c = plt.cm.tab20(index % 20)
        s = [r["s"] * 1e-6 for r in rows]
        axes[0].plot(s, [r["sliding"] for r in rows], color=c, lw=1, label=name)
        good = [r for r in rows if r["k"] > 0]
        axes[1].plot([r["s"] * 1e-6 for r in good], [r["k"] * 1e-9 for r in good], ".",
                     color=c, ms=3)
        good = [r for r in rows if r["g"] > 0]
        axes[2].plot([r["s"] * 1e-6 for r in good], [r["g"] * 1e-9 for r in good], ".",
                     color=c, ms=3)
        smin, smax = min(smin, min(s)), max(smax, max(s))
        zs.append(rows[-1]["z"])
        phis.append(rows[-1]["phi"])
    axes[0].axhspan(*PAPER_SLIDING, color="k", alpha=0.15, label="paper, Fig. 4 (0.09-0.11)")
    z, phi = sum(zs) / len(zs), sum(phis) / len(phis)
    ps = [smin + (smax - smin) * i / 50 for i in range(51)]
    k = [emt_k(p * 1e6, z, phi) * 1e-9 for p in ps]
    axes[1].plot(ps, k, "k-", label=f"EMT (Z={z:.2f}, phi={phi:.3f})")
    axes[2].plot(ps, [x * 3 * (5 - 4 * NU) / (5 * (2 - NU)) for x in k], "k-", label="EMT rough")
    axes[2].plot(ps, [x * 3 / 5 for x in k], "k--", label="EMT smooth")
    # the paper's trend: K, G ~ sigma_c^0.45 at low stress, ^0.33 at high,
    # drawn through the first variant's K at the middle of the path
    first = read(next(iter(tables.values())))
    middle = first[len(first) // 2]
    for exponent, style in ((0.45, ":"), (0.33, "-.")):
        axes[1].plot(ps, [middle["k"] * 1e-9 * (p * 1e6 / middle["s"]) ** exponent for p in ps],
                     "k" + style, lw=0.8, label=f"sigma_c^{exponent} (paper's exponents)")
    for ax in axes[1:]:
        ax.set_xscale("log")
        ax.set_yscale("log")
    for ax, name in zip(axes, ("sliding ratio", "K [GPa]", "G [GPa]")):
        ax.set_xlabel("confining stress sigma_c [MPa]")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3, which="both")
    axes[0].legend(fontsize=7)
    axes[1].legend(fontsize=7, loc="upper left")
    axes[2].legend(fontsize=7, loc="upper left")
    fig.suptitle(f"QuSGM sliding fraction: {args.grains} grains, friction and uniaxial strain "
                 f"increments of {args.strain:g} from a frictionless pack at "
                 f"{args.target/1e6:g} MPa")
    fig.tight_layout()
    out = os.path.join(args.work, "sliding_study.png")
    fig.savefig(out, dpi=110)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sable", default="build/sable")
    parser.add_argument("--work", default="output/sliding_study")
    parser.add_argument("--grains", type=int, default=400)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--target", type=float, default=4e6)
    parser.add_argument("--strain", type=float, default=1e-4)
    parser.add_argument("--compaction-strain", type=float, default=4e-3,
                        help="largest isotropic step of the frictionless compaction")
    parser.add_argument("--increments", type=int, default=80)
    parser.add_argument("--stresses", default="8e6,12e6")
    parser.add_argument("--variants", default=",".join(VARIANTS))
    parser.add_argument("--plot-only", action="store_true")
    args = parser.parse_args()
    names = args.variants.split(",")
    for name in names:
        if name not in VARIANTS:
            raise SystemExit(f"unknown variant '{name}'; known: {', '.join(VARIANTS)}")
    tables = {}
    if not args.plot_only:
        state = prepare_pack(args)
    for name in names:
        tables[name] = (os.path.join(args.work, name, "increments.csv") if args.plot_only
                        else run_variant(args, state, name))
        print(f"{name}: {tables[name]}", flush=True)
    summarise(args, tables)
    print(plot(args, tables))


if __name__ == "__main__":
    main()
