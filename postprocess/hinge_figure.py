#!/usr/bin/python3
"""The compliant needle turning in tissue (`needlefem run` of a compliant-tip case,
solver/run/hinge_coupling.hpp): one PNG from RUN_DIR/hinge.csv and summary.json.

Left: the head angle against time, the FEM's beside paper 000's Eq. 2.7 in air (no tissue term)
and with the tissue spring constant mu_t fitted to the FEM. Middle: the same against the flux
density B at the head, the paper's Fig. 7 quantity. Right: the FEM's angle and the fitted Eq. 2.7
relative to Eq. 2.7 in air, where the tissue's effect (about 1 %) shows. The title gives the fitted mu_t and the hinge
coupling's passes and residual.

usage: /usr/bin/python3 postprocess/hinge_figure.py RUN_DIR [--png OUT.png]
(default OUT.png: RUN_DIR/hinge.png)
"""
import argparse
import csv
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from sweep_figures import finish  # noqa: E402


def read(run_dir):
    hinge_csv = run_dir / "hinge.csv"
    if not hinge_csv.is_file():
        raise SystemExit(f"{hinge_csv}: missing (not a run of a compliant-tip case in frictional contact)")
    with open(hinge_csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{hinge_csv}: no rows")
    columns = {key: [float(row[key]) for row in rows] for key in rows[0]}
    summary = json.loads((run_dir / "summary.json").read_text())
    return columns, summary["hinge"]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", type=pathlib.Path)
    parser.add_argument("--png", type=pathlib.Path)
    args = parser.parse_args(argv)
    data, hinge = read(args.run_dir)
    fitted = hinge["fitted_tissue_spring_constant_n_per_m2"]
    series = [("head_angle_deg", "FEM (head in frictional contact with the tissue)", dict(color="k", lw=2)),
              ("head_angle_eq27_air_deg", "Eq. 2.7 in air (μ_t = 0)", dict(color="#1f77b4", ls="--")),
              ("head_angle_eq27_fitted_deg", f"Eq. 2.7, μ_t = {fitted:.4g} N/m² fitted to the FEM",
               dict(color="#d62728", ls=":"))]
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.5), constrained_layout=True)
    for key, label, style in series:
        axes[0].plot(data["time_s"], data[key], label=label, **style)
        axes[1].plot(data["flux_density_t"], data[key], label=label, **style)
    # The tissue's effect is about 1 %: its own panel, relative to Eq. 2.7 in air where the head has turned.
    turned = [i for i, a in enumerate(data["head_angle_eq27_air_deg"]) if a > 0.5]
    for key, label, style in series[::2]:
        axes[2].plot([data["flux_density_t"][i] for i in turned],
                     [100 * (data[key][i] / data["head_angle_eq27_air_deg"][i] - 1) for i in turned], label=label, **style)
    axes[0].set_xlabel("time [s]")
    for ax in axes[1:]:
        ax.set_xlabel("flux density B at the head [T]")
    for ax in axes[:2]:
        ax.set_ylabel("head turning angle θ [deg]")
    axes[2].set_ylabel("θ against Eq. 2.7 in air [%] (θ > 0.5°)")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="upper left")
    fig.suptitle(f"Compliant needle turning in tissue: K = {hinge['hinge_stiffness_n_m_per_rad']:.4g} N·m/rad, "
                 f"tissue {hinge['tissue_rotational_stiffness_n_m_per_rad']:.3g} N·m/rad; "
                 f"{hinge['passes']} coupling passes, balance within {hinge['balance_residual_rad']:.2g} rad",
                 fontsize=10)
    finish(fig, args.png or args.run_dir / "hinge.png")


if __name__ == "__main__":
    main(sys.argv[1:])
