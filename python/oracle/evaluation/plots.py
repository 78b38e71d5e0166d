"""PNG plots of an evaluation: per-user box plots, learning curves, paired differences, ablations."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from oracle.evaluation.curves import half_window, learning_curves as curves_of  # noqa: E402
from oracle.evaluation.replay import KS, ReplayResult  # noqa: E402


def _save(fig: Any, path: Path) -> Path:  # a matplotlib Figure (matplotlib is untyped here)
    """The figure as a private file (0600: a plot is a person's routine)."""
    import io

    from oracle.files import write_private_bytes

    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=110, format=path.suffix.lstrip(".") or "png")
    plt.close(fig)
    write_private_bytes(path, buffer.getvalue())
    return path


def box_plots(summary: dict[str, Any], out: Path) -> Path:
    """Per-user Top-1/3/5 of every method, one row per k, chance dashed."""
    methods = list(summary["methods"])
    fig, axes = plt.subplots(len(KS), 1, figsize=(max(8.0, 0.55 * len(methods) + 2), 3 * len(KS)), sharex=True)
    for ax, k in zip(axes, KS):
        data = [[u[f"top{k}"] for u in summary["methods"][m]["per_user"].values()] for m in methods]
        ax.boxplot(data, tick_labels=methods)
        ax.axhline(summary["chance"][f"top{k}"], color="grey", linestyle="--", linewidth=1, label="chance")
        ax.set_ylabel(f"Top-{k} per user")
        ax.set_ylim(0, 1)
    axes[0].set_title("Accuracy per user")
    axes[0].legend(loc="lower left")
    axes[-1].tick_params(axis="x", rotation=60, labelsize=8)
    fig.tight_layout()
    return _save(fig, out / "per_user_box.png")


def learning_curves(result: ReplayResult, out: Path, reference: str | None = None, *,
                    ks: tuple[int, ...] = (1, 3)) -> Path:
    """Smoothed accuracy against position over the whole history, every method and chance, one panel per k.

    ``reference`` (default: the first method, the one every other is compared with) is drawn thick;
    the grey area is the number of users that reach each position (right axis).
    """
    methods = result.methods()
    if reference is not None and reference in methods:
        methods = [reference] + [m for m in methods if m != reference]
    colours = plt.get_cmap("tab20")
    fig, axes = plt.subplots(1, len(ks), figsize=(7 * len(ks), 5.5), sharey=True)
    axes = list(axes) if len(ks) > 1 else [axes]
    for ax, k in zip(axes, ks):
        curves, chance = curves_of(result.outcomes, methods, k)
        users = ax.twinx()
        users.fill_between(chance.positions, chance.users, color="0.9", step="mid", zorder=0)
        users.set_ylabel("users reaching this position", color="0.5")
        users.set_ylim(0, max(1, chance.users.max()) * 1.05)
        ax.set_zorder(users.get_zorder() + 1)
        ax.patch.set_visible(False)
        for i, name in enumerate(methods):
            ax.plot(curves[name].positions, curves[name].accuracy, color=colours(i % 20),
                    linewidth=2.6 if i == 0 else 1.1, label=name)
        ax.plot(chance.positions, chance.accuracy, color="black", linestyle="--", linewidth=1.2, label="chance")
        ax.set_xlabel("position of the prediction in the user's history")
        ax.set_title(f"Top-{k}, smoothed over ±{half_window(len(chance.positions))} positions")
        ax.set_ylim(0, 1)
    axes[0].set_ylabel("accuracy across users")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", fontsize=8, ncol=min(9, len(labels)), frameon=False)
    fig.tight_layout(rect=(0, 0.06 + 0.03 * (len(labels) // 9), 1, 1))
    return _save(fig, out / "learning_curve.png")


def differences(summary: dict[str, Any], out: Path) -> Path:
    """Paired Top-k difference of every method against the reference, with 95 % bootstrap intervals."""
    paired = summary["comparisons"]
    names = list(paired["methods"])
    fig, ax = plt.subplots(figsize=(8, 0.35 * len(names) + 1.6))
    offsets = {k: (i - 1) * 0.25 for i, k in enumerate(KS)}
    for k, colour in zip(KS, ("tab:blue", "tab:orange", "tab:green")):
        rows = [paired["methods"][n][f"top{k}"] for n in names]
        ys = [i + offsets[k] for i in range(len(names))]
        xs = [100 * r["difference"] for r in rows]
        err = [[100 * (r["difference"] - r["low"]) for r in rows], [100 * (r["high"] - r["difference"]) for r in rows]]
        ax.errorbar(xs, ys, xerr=err, fmt="o", color=colour, markersize=4, capsize=2, label=f"Top-{k}")
    ax.axvline(0, color="grey", linewidth=1)
    ax.set_yticks(range(len(names)), names)
    ax.invert_yaxis()
    ax.set_xlabel(f"accuracy minus {paired['reference']} (percentage points, 95 % bootstrap interval)")
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return _save(fig, out / "differences.png")


def ablation_plot(ablations: dict[str, Any], out: Path) -> Path:
    """Top-1/3/5 of every Fig. 5.5 setting (bars) and its paired difference to A with 95 % intervals."""
    rows = ablations["settings"]
    letters = list(rows)
    base = rows["A"]["settings"]
    labels = [letter + "\n" + ("\n".join(f"{k.split('_')[0]}={v:g}" for k, v in rows[letter]["settings"].items()
                                         if v != base[k]) or "recommended") for letter in letters]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(13, 8), sharex=True)
    width = 0.27
    colours = ("tab:blue", "tab:orange", "tab:green")
    for i, (k, colour) in enumerate(zip(KS, colours)):
        xs = [j + (i - 1) * width for j in range(len(letters))]
        top.bar(xs, [rows[x][f"top{k}"] for x in letters], width, color=colour, label=f"Top-{k}")
        diffs = [rows[x]["vs_A"][f"top{k}"] if x != "A" else None for x in letters]
        points = [(x, d) for x, d in zip(xs, diffs) if d is not None]
        bottom.errorbar([x for x, _ in points], [100 * d["difference"] for _, d in points],
                        yerr=[[100 * (d["difference"] - d["low"]) for _, d in points],
                              [100 * (d["high"] - d["difference"]) for _, d in points]],
                        fmt="o", color=colour, markersize=4, capsize=2, label=f"Top-{k} minus A")
        for x, d in points:
            if d["p_holm"] < 0.05:
                bottom.annotate("*", (x, 100 * d["high"]), ha="center", va="bottom", fontsize=9)
    top.set_ylabel("accuracy")
    top.set_ylim(0, 1)
    top.set_title("Thesis Fig. 5.5 settings (A = recommended, Table 4.2)")
    top.legend(loc="upper right", fontsize=8)
    bottom.axhline(0, color="grey", linewidth=1)
    bottom.set_ylabel("difference to A (points)")
    bottom.set_title(f"Paired difference to A, 95 % bootstrap interval over {ablations['units']} units; "
                     "* Holm-corrected Wilcoxon p < 0.05", fontsize=9)
    bottom.legend(loc="lower right", fontsize=8)
    bottom.set_xticks(range(len(letters)), labels, fontsize=7)
    fig.tight_layout()
    return _save(fig, out / "ablations.png")
