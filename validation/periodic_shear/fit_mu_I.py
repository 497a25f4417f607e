#!/usr/bin/env python3
"""Fits the runs' (I, mu) of periodic_shear to the plane-shear trends and
writes them for `plab plot`.

    build/plab validate periodic_shear --report /tmp/shear
    python3 validation/periodic_shear/fit_mu_I.py /tmp/shear/report.md /tmp/shear

reads each run's line of the report ("phi 0.78: ...; mu M; I I; ..."), fits

  * mu = mu_min + b I (GDR MiDi 2004, da Cruz et al. 2005), least squares;
  * mu = mu_s + (mu_2 - mu_s) / (I_0 / I + 1) (Jop et al. 2006), least
    squares over a grid of (mu_s, mu_2, I_0),

prints the parameters and the rms deviation of each fit and of the
published linear trend (mu_min 0.25-0.3, b ~ 1; taken at its middle, 0.275
+ I), and writes OUT/mu_I.csv (the runs) and OUT/mu_I_trend.csv (the
published trend), then the plot command."""
import math
import re
import sys


def runs(report):
    out = []
    for line in open(report):
        m = re.match(r"\s*phi ([0-9.]+): .*?; mu ([-0-9.e]+); I ([-0-9.e]+);.*?mu_with_kinetic ([-0-9.e]+)", line)
        if m:
            out.append(tuple(float(v) for v in m.groups()))
    return sorted(set(out), key=lambda r: r[2])


def linear_fit(I, mu):
    n = len(I)
    mi, mm = sum(I) / n, sum(mu) / n
    b = sum((i - mi) * (m - mm) for i, m in zip(I, mu)) / sum((i - mi) ** 2 for i in I)
    return mm - b * mi, b


def rms(pred, mu):
    return math.sqrt(sum((p - m) ** 2 for p, m in zip(pred, mu)) / len(mu))


def jop(I, s, m2, i0):
    return s + (m2 - s) / (i0 / I + 1)


def jop_fit(I, mu):
    best = None
    for s in [0.15 + 0.005 * k for k in range(41)]:
        for m2 in [0.4 + 0.01 * k for k in range(61)]:
            for i0 in [0.02 * 1.1 ** k for k in range(50)]:
                e = rms([jop(i, s, m2, i0) for i in I], mu)
                if best is None or e < best[0]:
                    best = (e, s, m2, i0)
    return best


def main():
    report, out = sys.argv[1], sys.argv[2]
    rows = runs(report)
    if len(rows) < 3:
        raise SystemExit(f"{report}: fewer than three runs")
    I = [r[2] for r in rows]
    mu = [r[1] for r in rows]
    print("phi      I         mu      mu (with kinetic)")
    for phi, m, i, mk in sorted(rows):
        print(f"{phi:<8} {i:<9.4g} {m:<7.4f} {mk:.4f}")
    print(f"I from {min(I):.3g} to {max(I):.3g} ({math.log10(max(I) / min(I)):.2f} decades)")
    a, b = linear_fit(I, mu)
    print(f"mu_min + b I fitted: mu_min {a:.3f}, b {b:.3f}; rms deviation {rms([a + b * i for i in I], mu):.4f}")
    print(f"published trend 0.275 + I: rms deviation {rms([0.275 + i for i in I], mu):.4f}")
    e, s, m2, i0 = jop_fit(I, mu)
    print(f"Jop et al. form fitted: mu_s {s:.3f}, mu_2 {m2:.3f}, I_0 {i0:.3f}; rms deviation {e:.4f}")
    with open(f"{out}/mu_I.csv", "w") as f:
        f.write("# periodic_shear runs: time means in steady shear (fit_mu_I.py)\nI,mu,mu_with_kinetic,phi\n")
        for phi, m, i, mk in rows:
            f.write(f"{i},{m},{mk},{phi}\n")
    with open(f"{out}/mu_I_trend.csv", "w") as f:
        f.write("# mu = mu_min + b I, mu_min 0.275 (the middle of 0.25-0.3), b 1: GDR MiDi 2004, da Cruz et al. 2005, 2D discs\nI,mu\n")
        for k in range(41):  # (I up to 0.4: the published trend's range, ~0.3)
            i = 10 ** (-3 + math.log10(400) * k / 40)
            f.write(f"{i},{0.275 + i}\n")
    print(f"plab plot {out}/mu_I.csv --x I --y mu,mu_with_kinetic --ref {out}/mu_I_trend.csv --ref-y mu --band 0.2 --log x "
          f"--out docs/images/periodic_shear_mu_I.png")


if __name__ == "__main__":
    main()
