"""PNG plots of an evaluation: per-user box plots, learning curve, ablations."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from oracle.evaluation.replay import KS, ReplayResult, learning_curve  # noqa: E402


def box_plots(summary: dict, out: Path) -> Path:
    methods = list(summary["methods"])
    fig, axes = plt.subplots(1, len(KS), figsize=(4 * len(KS), 4), sharey=True)
    for ax, k in zip(axes, KS):
        data = [[u[f"top{k}"] for u in summary["methods"][m]["per_user"].values()] for m in methods]
        ax.boxplot(data, tick_labels=methods)
        ax.axhline(summary["chance"][f"top{k}"], color="grey", linestyle="--", linewidth=1, label="chance")
        ax.set_title(f"Top-{k} per user")
        ax.tick_params(axis="x", rotation=30)
    axes[0].set_ylabel("accuracy")
    axes[0].legend(loc="lower left")
    fig.tight_layout()
    path = out / "per_user_box.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def learning_curves(result: ReplayResult, out: Path, method: str = "oracle", max_index: int = 75) -> Path:
    fig, ax = plt.subplots(figsize=(7, 4))
    for k, color in zip(KS, ("tab:blue", "tab:orange", "tab:green")):
        acc, chance, _ = learning_curve(result, method, k, max_index)
        ax.plot(range(1, len(acc) + 1), acc, color=color, label=f"Top-{k}")
        ax.plot(range(1, len(chance) + 1), chance, color=color, linestyle=":", label=f"chance Top-{k}")
    ax.set_xlabel("action index (per user)")
    ax.set_ylabel("accuracy across users")
    ax.set_title(f"Learning curve of {method}")
    ax.set_ylim(0, 1)
    ax.legend(ncol=2, fontsize=8)
    fig.tight_layout()
    path = out / "learning_curve.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def ablation_plot(ablations: dict, out: Path, k: int = 5) -> Path:
    letters = list(ablations)
    data = [list(u[f"top{k}"] for u in ablations[x]["per_user"].values()) for x in letters]
    fig, ax = plt.subplots(figsize=(9, 4))
    ax.boxplot(data, tick_labels=letters)
    ax.set_title(f"Top-{k} per user for the thesis Fig. 5.5 settings (A = recommended)")
    ax.set_ylabel("accuracy")
    fig.tight_layout()
    path = out / f"ablations_top{k}.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
