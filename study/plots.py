"""Error against run time, log scales, the Pareto front marked (matplotlib,
the optional extra ``plots``; importing this module fails without it)."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402

from .measure import pareto  # noqa: E402

FLOOR = 1e-3                 # zero misclassification is drawn here on the log axis
STYLE = {"planar": ("s", "tab:brown"), "shadow map": ("o", "tab:blue"),
         "volumes": ("^", "tab:green"), "soft": ("D", "tab:purple")}


def _panel(ax, rows, key, title, floor_value=None):
    pts = [(r["time_ms"], max(r[key], FLOOR)) for r in rows]
    for fam, (marker, colour) in STYLE.items():
        sel = [p for p, r in zip(pts, rows) if r["family"] == fam]
        if sel:
            ax.scatter(*zip(*sel), marker=marker, color=colour, s=22, alpha=0.75, label=fam)
    front = sorted(pareto(pts), key=lambda i: pts[i][0])
    if front:
        fx, fy = zip(*(pts[i] for i in front))
        ax.step(fx, fy, where="post", color="red", lw=1.2, label="Pareto front")
        ax.scatter(fx, fy, facecolors="none", edgecolors="red", s=70, lw=1.2)
        for i in front:
            ax.annotate(rows[i]["label"], pts[i], fontsize=6, xytext=(4, 3),
                        textcoords="offset points")
    if floor_value is not None:
        ax.axhline(floor_value, color="grey", ls="--", lw=1, label="floor (reference decision)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    xs, ys = zip(*pts)
    _ticks(ax.xaxis, xs)
    _ticks(ax.yaxis, ys)
    ax.set_xlabel("warm run time (ms, median)")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=6, loc="best")


def _ticks(axis, values):
    """Log-axis labels at 1, 2, 5 (or 1.5, 3, 7 too) per decade, fewer for wide ranges."""
    decades = math.log10(max(values) / min(values)) if min(values) > 0 else 9
    subs = (1.0,) if decades > 2.5 else (1.0, 2.0, 5.0) if decades > 0.7 else \
        (1.0, 1.5, 2.0, 3.0, 5.0, 7.0)
    axis.set_major_locator(ticker.LogLocator(base=10, subs=subs))
    axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(ticker.NullFormatter())


def write(results, out_dir):
    """One PNG per scene; returns {scene: file name}."""
    names = {}
    for name, sc in results["scenes"].items():
        rows = sc["rows"]
        timed = [r for r in rows if not math.isnan(r["time_ms"])]   # on the compared machine
        hard = [r for r in timed if r["family"] not in ("soft", "floor")]
        soft = [r for r in timed if r["family"] == "soft"]
        floor = next((r["rmse"] for r in rows if r["family"] == "floor"), None)
        panels = [(hard, "misclassified", "hard: misclassified % (0 drawn at 0.001)", None),
                  (hard, "rmse", "hard: image RMSE vs point-light reference", floor),
                  (soft, "rmse", "soft: image RMSE vs area-light reference", None)]
        panels = [p for p in panels if p[0]]
        if not panels:
            continue
        fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.4))
        axes = [axes] if len(panels) == 1 else list(axes)
        for ax, (rs, key, title, fl) in zip(axes, panels):
            _panel(ax, rs, key, title, fl)
        axes[0].set_ylabel("error")
        fig.suptitle(f"scene {name}: {sc['title']}", fontsize=10)
        fig.tight_layout()
        names[name] = f"scene{name}_error_vs_time.png"
        fig.savefig(out_dir / names[name], dpi=110)
        plt.close(fig)
    return names
