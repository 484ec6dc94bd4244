"""Journal figures of flexrock's results with matplotlib (``pip install flexrock[figures]``).

The figures the command line draws (``flexrock plot``), drawn onto your own matplotlib axes
with the same conventions, so that a paper's figure is three lines and stays fully editable:
text in points that stays legible at print size (7 pt ticks and legend, 8 pt labels, 9 pt
panel labels), panels labelled (a), (b), ... instead of titled, stacked time panels sharing
their x axis, events as a light rug, colours of the Okabe-Ito palette (kept apart by most
colour-blind readers) with dashes that survive greyscale, subscripts and minus signs, log
axes where the literature uses them.

Each ``plot_*`` function takes a result (a `flexrock.Result`, a `flexrock.SweepResult`, or
plain arrays) and optional axes; without axes it makes a figure one journal column wide
(`COLUMN_MM`, 85 mm; ``width="page"`` for two columns). It returns the axes it drew on.

Examples
--------
>>> import flexrock, flexrock.figures as ff
>>> result = flexrock.simulate(flexrock.Model.from_file("models/ichinose1986.toml"))
>>> axes = ff.plot_motion(result)                 # four panels, one column wide
>>> axes[0].figure.savefig("motion.pdf")          # vector PDF, fonts embedded by matplotlib

Every plot is listed in `PLOTS` by the kind of result it draws.
"""

from __future__ import annotations

import contextlib
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union

import math
import textwrap

import numpy as np

try:
    import matplotlib
    import matplotlib.figure
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
except ImportError as e:  # pragma: no cover - exercised only without the extra
    raise ImportError(
        "flexrock.figures needs matplotlib: pip install 'flexrock[figures]'"
    ) from e

__all__ = [
    "COLUMN_MM",
    "PAGE_MM",
    "PALETTE",
    "PLOTS",
    "STYLE",
    "IdaCurve",
    "figure",
    "panel_labels",
    "plot_capacities",
    "plot_energy",
    "plot_fragility",
    "plot_ida",
    "plot_map",
    "plot_motion",
    "plot_relations",
    "plot_row",
    "plot_spectrum",
    "style",
]

#: One journal column, mm.
COLUMN_MM = 85.0
#: Two journal columns (the text width), mm.
PAGE_MM = 180.0

#: Black, then Okabe and Ito's colours (vermillion, blue, bluish green, orange, reddish purple,
#: sky blue), then grey: the colours of the command line's figures, in the same order.
PALETTE = [
    "#000000",
    "#D55E00",
    "#0072B2",
    "#009E73",
    "#E69F00",
    "#CC79A7",
    "#56B4E9",
    "#787878",
]

#: matplotlib settings of the figures: sizes in points, the palette as the colour cycle,
#: fonts embedded as TrueType in PDF and PS.
STYLE: Dict[str, Any] = {
    "font.size": 8,
    "axes.labelsize": 8,
    "axes.titlesize": 9,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 7,
    "legend.frameon": False,
    "axes.linewidth": 0.5,
    "xtick.major.width": 0.5,
    "ytick.major.width": 0.5,
    "xtick.minor.width": 0.4,
    "ytick.minor.width": 0.4,
    "xtick.major.size": 2.5,
    "ytick.major.size": 2.5,
    "lines.linewidth": 0.9,
    "lines.markersize": 3.5,
    "axes.grid": True,
    "grid.color": "#E6E6E6",
    "grid.linewidth": 0.4,
    "axes.prop_cycle": matplotlib.cycler(color=PALETTE[1:] + PALETTE[:1]),
    "axes.unicode_minus": True,
    "pdf.fonttype": 42,
    "ps.fonttype": 42,
    "savefig.dpi": 300,
}

# Colour, marker and rug side of each kind of event, as the command line draws them.
_EVENTS = {
    "uplift": (PALETTE[4], "^", False),
    "landing": (PALETTE[3], "v", True),
    "overturn": (PALETTE[0], "x", False),
}


@contextlib.contextmanager
def style() -> Iterator[None]:
    """A context in which matplotlib draws with `STYLE`."""
    with matplotlib.rc_context(STYLE):
        yield


def _mm(value: Union[str, float]) -> float:
    if value == "column":
        return COLUMN_MM
    if value == "page":
        return PAGE_MM
    return float(value)


class _Figure(matplotlib.figure.Figure):
    """A figure that saves with `STYLE` in effect, whatever the settings at the time: its PDF
    keeps TrueType fonts and its PNG 300 dpi (matplotlib reads both when it saves)."""

    def savefig(self, *args: Any, **kwargs: Any) -> None:
        with style():
            super().savefig(*args, **kwargs)


def figure(
    nrows: int = 1,
    ncols: int = 1,
    width: Union[str, float] = "column",
    height: Optional[float] = None,
    sharex: bool = False,
    panel_height: float = 30.0,
) -> Tuple[Any, np.ndarray]:
    """A figure of ``nrows`` by ``ncols`` axes, ``width`` mm wide ("column", "page" or mm).

    Its height is ``height`` mm, or ``panel_height`` mm per row and room for the legend and the
    x axis. Returns ``(fig, axes)``, axes a 1-D array. ``fig.savefig`` saves with `STYLE`
    (fonts embedded as TrueType in a PDF); a figure of your own saves so inside `style()`.
    """
    w = _mm(width)
    h = height if height is not None else nrows * panel_height + 22.0
    with style():
        fig, axes = plt.subplots(
            nrows,
            ncols,
            figsize=(w / 25.4, h / 25.4),
            sharex=sharex,
            squeeze=False,
            layout="constrained",
            FigureClass=_Figure,
        )
    return fig, axes.ravel()


def panel_labels(axes: Sequence[Any], start: int = 0) -> None:
    """Labels the axes (a), (b), ... at their upper left, above the frame."""
    for i, ax in enumerate(axes):
        ax.set_title(f"({chr(ord('a') + start + i)})", loc="left", fontsize=9, pad=3)


def _legend(axes: Sequence[Any], handles: List[Any], labels: List[str]) -> None:
    """One legend for the figure of `axes`, above its panels, each label once."""
    seen: Dict[str, Any] = {}
    for h, lab in zip(handles, labels):
        if lab and not lab.startswith("_") and lab not in seen:
            seen[lab] = h
    if not seen:
        return
    fig = axes[0].figure
    # As many columns as fit across the figure: an entry is its text (about 0.55 em a
    # character at 7 pt) and its handle and gap (about 5 em).
    width_pt = fig.get_size_inches()[0] * 72.0
    entry_pt = 7.0 * (0.55 * max(len(lab) for lab in seen) + 5.0)
    fig.legend(
        list(seen.values()),
        list(seen.keys()),
        loc="outside upper center",
        ncols=max(1, min(3, len(seen), int(width_pt // entry_pt))),
        fontsize=7,
        frameon=False,
    )


def _axes(axes: Optional[Sequence[Any]], n: int, **kw: Any) -> Tuple[np.ndarray, bool]:
    """The user's axes (checked to be ``n``), or a new figure's; True when new."""
    if axes is None:
        _, made = figure(**kw)
        return made, True
    flat = np.asarray(axes, dtype=object).ravel()
    if len(flat) != n:
        raise ValueError(f"axes: this figure draws {n} panels, got {len(flat)} axes")
    return flat, False


def _constant(result: Any, key: str) -> Optional[float]:
    constants = (getattr(result, "summary", None) or {}).get("constants", {})
    value = constants.get(key)
    return float(value) if value is not None else None


def _rug(ax: Any, events: Sequence[Dict[str, Any]]) -> None:
    """Short ticks at the events' times: uplifts along the bottom edge, landings the top."""
    for kind, (colour, _, top) in _EVENTS.items():
        times = [e["t"] for e in events if e.get("kind") == kind]
        if times:
            y = (0.97, 1.0) if top else (0.0, 0.03)
            for t in times:
                ax.axvline(t, ymin=y[0], ymax=y[1], color=colour, lw=0.8)


def plot_motion(result: Any, axes: Optional[Sequence[Any]] = None, width: Union[str, float] = "column") -> np.ndarray:
    """The motion of a run: floor acceleration a, top displacement q with ±sₙ and ±B, the
    flexural and rocking parts s and r, and the top velocity q̇ with the events marked.

    Parameters
    ----------
    result : flexrock.Result
        A run (``flexrock.simulate``).
    axes : four matplotlib axes, optional
        Drawn onto; otherwise a new figure ``width`` wide with a shared time axis.
    """
    ax, new = _axes(axes, 4, nrows=4, width=width, sharex=True, panel_height=26.0)
    with style():
        t = np.asarray(result.t)
        ax[0].plot(t, result.floor_acc, color=PALETTE[0])
        ax[0].set_ylabel("a (m/s²)")
        ax[1].plot(t, result.q, color=PALETTE[0])
        ax[1].set_ylabel("q (m)")
        s_n, b = _constant(result, "uplift_displacement"), _constant(result, "width")
        if s_n is not None:
            for sign in (1, -1):
                for a in (ax[1], ax[2]):
                    a.axhline(sign * s_n, color="#969696", lw=0.6,
                              label=f"±sₙ = {s_n:.4g} m (uplift)" if sign > 0 else None)
        if b is not None:
            for sign in (1, -1):
                ax[1].axhline(sign * b, color="#464646", lw=0.6, ls="--",
                              label=f"±B = {b:.4g} m (overturning)" if sign > 0 else None)
        ax[2].plot(t, result.s, color=PALETTE[2], label="s, flexural part")
        ax[2].plot(t, result.r, color=PALETTE[1], ls="--", label="r, rocking part")
        ax[2].set_ylabel("s, r (m)")
        ax[3].plot(t, result.qdot, color=PALETTE[0])
        ax[3].set_ylabel("q\u0307 (m/s)")
        for kind, (colour, marker, _) in _EVENTS.items():
            chosen = [e for e in result.events if e.get("kind") == kind]
            if chosen:
                ax[3].plot([e["t"] for e in chosen], [e["qdot_before"] for e in chosen],
                           ls="none", marker=marker, color=colour, label=f"{kind} ({len(chosen)})")
        for a in ax[:3]:
            _rug(a, result.events)
        ax[3].set_xlabel("t (s)")
        for a in ax[:3]:
            a.label_outer()
        panel_labels(ax)
        if new:
            handles, labels = [], []
            for a in ax:
                h, lab = a.get_legend_handles_labels()
                handles += h
                labels += lab
            _legend(ax, handles, labels)
    return ax


def plot_relations(result: Any, axes: Optional[Sequence[Any]] = None, width: Union[str, float] = "column") -> np.ndarray:
    """q against r and s against r (the paper's Figs. 12 and 13), side by side."""
    ax, _ = _axes(axes, 2, ncols=2, width=width, panel_height=40.0)
    with style():
        ax[0].plot(result.r, result.q, color=PALETTE[0])
        ax[0].set_xlabel("r (m)")
        ax[0].set_ylabel("q (m)")
        ax[1].plot(result.r, result.s, color=PALETTE[0])
        ax[1].set_xlabel("r (m)")
        ax[1].set_ylabel("s (m)")
        panel_labels(ax)
    return ax


def plot_energy(result: Any, ax: Optional[Any] = None, width: Union[str, float] = "column") -> Any:
    """The energy residual ΔE over the run's energy scale Eₛ, against t."""
    if ax is None:
        _, made = figure(width=width, panel_height=35.0)
        ax = made[0]
    with style():
        scale = (result.summary or {}).get("energy_scale") or 1.0
        ax.plot(result.t, np.asarray(result.energy_residual) / scale, color=PALETTE[0])
        ax.set_xlabel("t (s)")
        ax.set_ylabel(f"ΔE/Eₛ, Eₛ = {scale:.3g} J")
    return ax


_LABELS = {
    "excitation.amplitude": "aₚ (m/s²)",
    "excitation.period": "Tₚ (s)",
    "excitation.scale": "scale factor",
    "body.height": "H (m)",
    "body.width": "B (m)",
    "body.period": "T (s)",
    "body.damping_ratio": "h",
    "body.youngs_modulus": "E (Pa)",
}
_DIMENSIONLESS = {
    "excitation.amplitude": ("amplitude_over_g_tan_alpha", "aₚ/(g tan α)"),
    "excitation.scale": ("amplitude_over_g_tan_alpha", "PFA/(g tan α)"),
    "excitation.period": ("omega_p_over_p", "ωₚ/p"),
}


def _label(key: str) -> str:
    return _LABELS.get(key, key)


def _numeric_axis(sweep: Any) -> Tuple[str, np.ndarray]:
    key = sweep.axes[0][0]
    return key, np.asarray(sweep[key], dtype=float)


def _log_spaced(values: np.ndarray) -> bool:
    """The cells are more even in log10 than as they are (see the command line's map)."""
    v = np.sort(np.asarray(values, dtype=float))
    if len(v) < 3 or np.any(v <= 0):
        return False

    def spread(x: np.ndarray) -> float:
        d = np.diff(x)
        return float(np.std(d) / np.mean(d))

    return spread(np.log10(v)) < spread(v)


def plot_spectrum(sweep: Any, axes: Optional[Sequence[Any]] = None, width: Union[str, float] = "column") -> np.ndarray:
    """The spectrum of a minimum search (``flexrock.sweep(..., find_min=...)``): the smallest
    overturning value against the axis, physical and (where the axis has one) dimensionless,
    beside Housner's block (wide, grey) and the model's rigid limit (dashed); the periods where
    the body stands are open triangles at the search's top, not joined to the curve.
    """
    key, x = _numeric_axis(sweep)
    dimensionless = _DIMENSIONLESS.get(key)
    n = 2 if dimensionless and dimensionless[0] in sweep else 1
    ax, new = _axes(axes, n, ncols=n, width=width, panel_height=45.0)
    found = np.asarray(sweep["min_overturning"], dtype=float)
    status = np.asarray(sweep["status"])
    stands = np.isnan(found) & (status == "ok")
    top = np.nanmax(found) if np.any(~np.isnan(found)) else 1.0
    with style():
        views = [(x, "min_overturning", "rigid_min_overturning", "rigid_limit_min_overturning", _label(key))]
        if n == 2:
            column, xlabel = dimensionless
            views.append((np.asarray(sweep[column], dtype=float), "amplitude_over_g_tan_alpha",
                          "rigid_amplitude_over_g_tan_alpha",
                          "rigid_limit_amplitude_over_g_tan_alpha", xlabel))
        for a, (xs, y, rigid, limit, xlabel) in zip(ax, views):
            order = np.argsort(xs)
            a.plot(xs[order], np.asarray(sweep[rigid], dtype=float)[order], color=PALETTE[7], lw=2.4,
                   label="Housner block, small-angle eq.")
            a.plot(xs[order], np.asarray(sweep[limit], dtype=float)[order], color=PALETTE[0], lw=0.8, ls="--",
                   label="model's rigid limit")
            ys = np.asarray(sweep[y], dtype=float)[order]
            a.plot(xs[order], ys, color=PALETTE[2], marker="o", lw=1.1, label="elastic body (this model)")
            if np.any(stands):
                level = top if y == "min_overturning" else np.nanmax(ys)
                a.plot(xs[stands], np.full(stands.sum(), level), ls="none", marker="^",
                       mfc="white", color=PALETTE[2], label="stands (no overturning found)")
            if np.all(xs > 0) and xs.max() / xs.min() >= 3:
                a.set_xscale("log")
            a.set_xlabel(xlabel)
        ax[0].set_ylabel("smallest overturning value")
        if n == 2:
            ax[1].set_ylabel("aₚ/(g tan α)")
        if n > 1:
            panel_labels(ax)
        if new:
            h, lab = ax[0].get_legend_handles_labels()
            _legend(ax, h, lab)
    return ax


def plot_map(sweep: Any, ax: Optional[Any] = None, width: Union[str, float] = "column") -> Any:
    """The map of a sweep over two numeric axes: max |q|/B in five classes, overturned black,
    unsolved white, the boundary of overturning in vermillion."""
    (kx, vx), (ky, vy) = sweep.axes[0], sweep.axes[1]
    xs, ys = np.asarray(vx, dtype=float), np.asarray(vy, dtype=float)
    grid = np.asarray(sweep["max_abs_q_over_B"], dtype=float).reshape(len(xs), len(ys))
    over = np.asarray(sweep["overturned"], dtype=bool).reshape(len(xs), len(ys))
    if ax is None:
        _, made = figure(width=width, panel_height=50.0)
        ax = made[0]
    colours = ["#FDE725", "#5EC962", "#21918C", "#3B528B", "#440154"]
    with style():
        classes = np.clip(np.floor(np.nan_to_num(grid, nan=-1) / 0.2), -1, 4).astype(int)
        rgb = np.ones(grid.shape + (3,))
        for k, c in enumerate(colours):
            rgb[classes == k] = matplotlib.colors.to_rgb(c)
        rgb[over] = 0.0
        ox, oy = np.argsort(xs), np.argsort(ys)

        def edges(v: np.ndarray) -> np.ndarray:
            log = _log_spaced(v)
            w = np.log10(v) if log else v
            mid = 0.5 * (w[1:] + w[:-1])
            e = np.concatenate([[w[0] - (mid[0] - w[0])], mid, [w[-1] + (w[-1] - mid[-1])]])
            return 10 ** e if log else e

        ex, ey = edges(xs[ox]), edges(ys[oy])
        ax.pcolormesh(ex, ey, rgb[np.ix_(ox, oy)].transpose(1, 0, 2), shading="flat")
        if _log_spaced(xs):
            ax.set_xscale("log")
        if _log_spaced(ys):
            ax.set_yscale("log")
        ax.contour(xs[ox], ys[oy], over[np.ix_(ox, oy)].T.astype(float), levels=[0.5],
                   colors=[PALETTE[1]], linewidths=1.3)
        ax.set_xlabel(_label(kx))
        ax.set_ylabel(_label(ky))
        ax.grid(False)
        handles = [matplotlib.patches.Patch(color=c) for c in colours] + [
            matplotlib.patches.Patch(color="black"),
            Line2D([], [], color=PALETTE[1], lw=1.3),
        ]
        labels = ["max |q|/B: 0–0.2", "0.2–0.4", "0.4–0.6", "0.6–0.8", "0.8–1", "overturned",
                  "boundary of overturning"]
        ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7,
                  frameon=False)
    return ax


class IdaCurve:
    """One record's curve of an incremental dynamic analysis, as plain data.

    Parameters
    ----------
    label : str
        The legend text (a record's name).
    x : sequence of float
        The intensity at each point (a scale factor, or an intensity measure).
    y : sequence of float
        max |q|/B at each point (not used where overturned).
    overturned : sequence of bool
        Whether the body overturned at each point.
    """

    def __init__(self, label: str, x: Sequence[float], y: Sequence[float], overturned: Sequence[bool]):
        self.label = label
        self.x = np.asarray(x, dtype=float)
        self.y = np.asarray(y, dtype=float)
        self.overturned = np.asarray(overturned, dtype=bool)

    @staticmethod
    def of_sweep(sweep: Any) -> List["IdaCurve"]:
        """The curves of a sweep over ``excitation.path`` and a scale (or over a scale alone),
        one per record labelled by its file stem, x the scale."""
        keys = [k for k, _ in sweep.axes]
        x_key = next(k for k in keys if k in ("excitation.scale", "excitation.amplitude"))
        x = np.asarray(sweep[x_key], dtype=float)
        y = np.asarray(sweep["max_abs_q_over_B"], dtype=float)
        over = np.asarray(sweep["overturned"], dtype=bool)
        if "excitation.path" not in keys:
            return [IdaCurve("max |q|/B", x, y, over)]
        paths = np.asarray(sweep["excitation.path"])
        curves = []
        for path in dict.fromkeys(paths):
            chosen = paths == path
            stem = str(path).replace("\\", "/").rsplit("/", 1)[-1].rsplit(".", 1)[0]
            curves.append(IdaCurve(stem, x[chosen], y[chosen], over[chosen]))
        return curves


def _quantile(sorted_values: np.ndarray, p: float) -> float:
    """As the command line: linear between order statistics, +inf (overturned) above all."""
    h = p * (len(sorted_values) - 1)
    lo, hi = int(np.floor(h)), int(np.ceil(h))
    if np.isinf(sorted_values[hi]):
        return float("inf")
    return float(sorted_values[lo] + (h - lo) * (sorted_values[hi] - sorted_values[lo]))


def plot_ida(
    result: Any = None,
    ax: Optional[Any] = None,
    *,
    curves: Optional[Sequence[IdaCurve]] = None,
    x_label: str = "scale factor",
    width: Union[str, float] = "column",
) -> Any:
    """An incremental dynamic analysis: max |q|/B against the intensity, a line per record up
    to its first overturning (crosses stacked above |q| = B), and with three records or more
    the median and the 16 % and 84 % fractiles over the records at each intensity.

    Give a `flexrock.SweepResult` (records against ``excitation.scale``), or ``curves`` (a list
    of `IdaCurve`) with their ``x_label`` to draw against another intensity measure or with
    other labels.
    """
    if curves is None:
        if result is None:
            raise ValueError("plot_ida needs a SweepResult or curves=[IdaCurve, ...]")
        curves = IdaCurve.of_sweep(result)
    if ax is None:
        _, made = figure(width=width, panel_height=45.0)
        ax = made[0]
    firsts: Dict[float, int] = {}
    stacked = 0
    with style():
        for g, c in enumerate(curves):
            order = np.argsort(c.x)
            x, y, over = c.x[order], c.y[order], c.overturned[order]
            first = int(np.argmax(over)) if over.any() else len(x)
            line_x = list(x[:first]) + ([x[first]] if first < len(x) else [])
            line_y = list(y[:first]) + ([1.0] if first < len(x) else [])
            colour = PALETTE[1 + g % 7]
            ax.plot(line_x, line_y, color=colour, lw=0.7 if len(curves) > 1 else 0.9,
                    ls=["-", "--", "-."][(g // 7) % 3], marker="o" if len(curves) <= 7 else None,
                    label=c.label)
            if first < len(x):
                j = firsts.get(float(x[first]), 0) + 1
                firsts[float(x[first])] = j
                stacked = max(stacked, j)
                ax.plot([x[first]], [1.0 + 0.06 * j], ls="none", marker="x", color=colour)
        if len(curves) >= 3:
            xs = sorted(set(np.concatenate([c.x for c in curves]).tolist()))
            stats: List[List[Tuple[float, float]]] = [[], [], []]
            for xv in xs:
                at = []
                for c in curves:
                    hit = np.flatnonzero(c.x == xv)
                    if len(hit):
                        k = hit[0]
                        at.append(np.inf if c.overturned[k] else c.y[k])
                if len(at) < len(curves):
                    continue
                at_sorted = np.sort(np.asarray(at))
                for s, p in zip(stats, (0.5, 0.16, 0.84)):
                    v = _quantile(at_sorted, p)
                    if np.isfinite(v):
                        s.append((xv, v))
            for s, lab, lw, ls in zip(stats, ("median", "16 % and 84 % fractiles", None),
                                      (1.8, 0.9, 0.9), ("-", "--", "--")):
                if s:
                    ax.plot(*zip(*s), color=PALETTE[0], lw=lw, ls=ls, label=lab)
        ax.axhline(1.0, color="#464646", lw=0.6, ls="--", label="|q| = B (overturning)")
        if stacked:
            ax.plot([], [], ls="none", marker="x", color=PALETTE[0],
                    label="first overturning of a record")
            ax.set_ylim(top=1.0 + 0.06 * (stacked + 1))
        ax.set_xlabel(x_label)
        ax.set_ylabel("max |q|/B")
        ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7, frameon=False)
    return ax


def _single_legend(ax: Any, new: bool) -> None:
    """The legend of a one-panel figure outside its data: above it in a figure of its own,
    to the right of the user's axes (which may share a figure with others)."""
    handles, labels = ax.get_legend_handles_labels()
    if new:
        _legend([ax], handles, labels)
        return
    seen: Dict[str, Any] = {}
    for h, lab in zip(handles, labels):
        if lab and not lab.startswith("_") and lab not in seen:
            seen[lab] = h
    if seen:
        ax.legend(list(seen.values()), list(seen.keys()), loc="upper left",
                  bbox_to_anchor=(1.02, 1.0), fontsize=7, frameon=False)


def _fits(result: Any, caller: str) -> List[Tuple[str, float, float]]:
    """The fits of `result` as (damage state, theta, beta), each checked to draw a curve."""
    summary = getattr(result, "summary", None)
    if isinstance(summary, dict) and "fits" in summary:
        raw = [(f.get("state", "damage state"), f.get("theta"), f.get("beta"))
               for f in summary["fits"]]
    elif isinstance(result, dict) and "fits" in result:
        raw = [(f.get("state", "damage state"), f.get("theta"), f.get("beta"))
               for f in result["fits"]]
    elif isinstance(result, dict) and "theta" in result and "beta" in result:
        raw = [(result.get("state", "damage state"), result["theta"], result["beta"])]
    else:
        raw = []
    if not raw:
        raise ValueError(
            f"{caller}: {type(result).__name__} holds no fit (theta and beta): give a "
            "FragilityResult of flexrock.fragility, or the dict of flexrock.fit_capacities "
            "or flexrock.fit_stripes"
        )
    fits = []
    for state, theta, beta in raw:
        for name, value in (("theta", theta), ("beta", beta)):
            if value is None or not math.isfinite(float(value)) or float(value) <= 0:
                raise ValueError(
                    f"{caller}: the fit of {state!r} has {name} = {value}: "
                    "a lognormal curve needs a finite theta > 0 and beta > 0"
                )
        fits.append((str(state), float(theta), float(beta)))
    return fits


def _im_label(result: Any) -> Optional[str]:
    """The intensity measure of a fragility study with its unit, e.g. "PGA (g)"."""
    summary = getattr(result, "summary", None)
    if not isinstance(summary, dict) or "im" not in summary:
        return None
    unit = summary.get("im_unit", "")
    period = summary.get("sa_period_s")
    name = f"Sa({period:g} s, 5 %)" if period is not None else str(summary["im"]).upper()
    return f"{name} ({unit})" if unit else name


def _lognormal_cdf(x: Any, theta: float, beta: float) -> np.ndarray:
    """Φ(ln(x/θ)/β), 0 at x ≤ 0: the core's lognormal fragility curve, evaluated for drawing."""
    x = np.asarray(x, dtype=float)
    with np.errstate(divide="ignore"):
        z = np.log(np.where(x > 0, x, np.nan) / theta) / beta
    p = 0.5 * np.array([math.erfc(-v / math.sqrt(2.0)) if np.isfinite(v) else np.nan
                        for v in np.ravel(z)]).reshape(np.shape(z))
    return np.where(x > 0, p, 0.0)


def plot_fragility(
    result: Any,
    ax: Optional[Any] = None,
    *,
    capacity: Optional[Sequence[float]] = None,
    censored: Optional[Sequence[bool]] = None,
    stripes: Optional[Tuple[Sequence[float], Sequence[int], Sequence[int]]] = None,
    x_label: Optional[str] = None,
    log: bool = False,
    width: Union[str, float] = "column",
) -> Any:
    """Fragility curves: the fitted lognormal CDF Φ(ln(IM/θ)/β) of each damage state, with
    its median θ and dispersion β in the legend, and what was observed as markers.

    Parameters
    ----------
    result : FragilityResult or dict
        A study of `flexrock.fragility` (a curve per damage state of its ``fits``, the
        records' capacities as the observed fractions: the i-th smallest capacity at i/n,
        censored records as a rug along the top, their capacity above its mark), or the dict
        of `flexrock.fit_capacities` or `flexrock.fit_stripes` (its ``"state"`` names the
        curve if given).
    capacity, censored : sequences, optional
        With a dict of `fit_capacities`: the capacities it was fitted to, drawn as a study's.
    stripes : (levels, records, damaged), optional
        With a dict of `fit_stripes`: the counts it was fitted to, drawn as the fraction
        damaged/records at each level.
    x_label : str, optional
        The intensity axis's label [default: a study's measure and unit, else "IM"].
    log : bool
        A log intensity axis [default: linear from 0, as the command line draws it].

    Raises
    ------
    ValueError
        A result without a fit (theta and beta), or a fit whose theta or beta is not a
        positive number.
    """
    fits = _fits(result, "plot_fragility")
    new = ax is None
    if ax is None:
        _, made = figure(width=width, panel_height=50.0)
        ax = made[0]
    values: List[float] = []
    with style():
        observed: Optional[np.ndarray] = None
        above = np.zeros(0)
        if hasattr(result, "summary") and "records" in result.summary and capacity is None:
            capacity, censored = result["capacity"], result["censored"]
        if capacity is not None:
            c = np.asarray(capacity, dtype=float)
            flags = (np.zeros(c.shape, dtype=bool) if censored is None
                     else np.asarray(censored, dtype=bool))
            observed, above = np.sort(c[~flags]), c[flags]
            values += list(c)
            n = len(c)
            ax.plot(observed, np.arange(1, len(observed) + 1) / n, ls="none", marker="o",
                    mfc="white", color=PALETTE[0], label=f"records, i/n (n = {n})")
            for x in above:
                ax.axvline(x, ymin=0.97, ymax=1.0, color=PALETTE[7], lw=0.8)
            if len(above):
                ax.plot([], [], color=PALETTE[7], lw=0.8,
                        label=f"censored ({len(above)}), capacity above")
        if stripes is not None:
            levels, records, damaged = (np.asarray(v, dtype=float) for v in stripes)
            values += list(levels)
            ax.plot(levels, damaged / records, ls="none", marker="s", mfc="white",
                    color=PALETTE[0], label="observed fraction damaged")
        unit = getattr(result, "im_unit", None) or ""
        top = max([t * math.exp(2.0 * b) for _, t, b in fits] + values)
        low = min([t * math.exp(-2.5 * b) for _, t, b in fits] + values)
        x = np.geomspace(low / 1.1, top * 1.1, 300) if log else np.linspace(0.0, top * 1.05, 300)
        for k, (state, theta, beta) in enumerate(fits):
            ax.plot(x, _lognormal_cdf(x, theta, beta), color=PALETTE[1 + k % 7],
                    ls=["-", "--", "-.", ":"][k % 4], lw=1.2,
                    label=f"{state}: θ = {theta:.3g}{' ' + unit if unit else ''}, β = {beta:.2f}")
        if log:
            ax.set_xscale("log")
        else:
            ax.set_xlim(left=0.0)
        ax.set_ylim(0.0, 1.0)
        ax.set_xlabel(x_label or _im_label(result) or "IM")
        states = [s for s, _, _ in fits]
        ax.set_ylabel(f"P({states[0]} | IM)" if len(states) == 1 else "P(state reached | IM)")
        _single_legend(ax, new)
    return ax


def plot_capacities(result: Any, ax: Optional[Any] = None, width: Union[str, float] = "column") -> Any:
    """The records' capacities on the intensity axis, one row per record named by its label,
    censored records as open circles (the capacity lies above), with the fit's median θ and
    its 16 % and 84 % fractiles θ exp(∓β).

    Parameters
    ----------
    result : FragilityResult
        A study of `flexrock.fragility` (its first damage state's fit).

    Raises
    ------
    ValueError
        A result without the records' capacities, or without a fit.
    """
    if not hasattr(result, "summary") or "records" not in getattr(result, "summary", {}):
        raise ValueError(
            f"plot_capacities: {type(result).__name__} holds no records' capacities: give a "
            "FragilityResult of flexrock.fragility"
        )
    state, theta, beta = _fits(result, "plot_capacities")[0]
    c = np.asarray(result["capacity"], dtype=float)
    flags = np.asarray(result["censored"], dtype=bool)
    # Long names (event, station, component) wrapped to keep the panel wide.
    labels = [textwrap.fill(str(v), 24) for v in result["label"]]
    lines = max([lab.count("\n") + 1 for lab in labels] + [1])
    n = len(c)
    new = ax is None
    if ax is None:
        _, made = figure(width=width, height=max(45.0, n * (3.0 * lines + 1.5) + 32.0))
        ax = made[0]
    rows = np.arange(n, 0, -1, dtype=float)
    with style():
        ax.plot(c[~flags], rows[~flags], ls="none", marker="o", color=PALETTE[2],
                label=f"capacity ({state})")
        if flags.any():
            ax.plot(c[flags], rows[flags], ls="none", marker="o", mfc="white", color=PALETTE[2],
                    label="censored (capacity above)")
        unit = f" {result.im_unit}" if getattr(result, "im_unit", "") else ""
        ax.axvline(theta, color=PALETTE[0], lw=1.0, label=f"median θ = {theta:.3g}{unit}")
        for k, f in enumerate((theta * math.exp(-beta), theta * math.exp(beta))):
            ax.axvline(f, color=PALETTE[0], lw=0.7, ls="--",
                       label=f"16 % and 84 % fractiles, β = {beta:.2f}" if k == 0 else None)
        ax.set_yticks(rows, labels)
        ax.set_ylim(0.4, n + 0.6)
        ax.tick_params(axis="y", length=0)
        ax.grid(axis="y", visible=False)
        ax.set_xlim(0.0, 1.05 * max(float(np.max(c)), theta * math.exp(beta)))
        ax.set_xlabel(_im_label(result) or "IM")
        _single_legend(ax, new)
    return ax


def plot_row(row: Any, axes: Optional[Sequence[Any]] = None, width: Union[str, float] = "column") -> np.ndarray:
    """The motion of a row of columns (``flexrock.simulate_row``), as ``flexrock row`` draws
    it: the floor acceleration a, each column's top displacement q, and each contact's clear
    gap, which falls to zero at an impact; the impacts as a rug along every panel's bottom.

    Parameters
    ----------
    row : flexrock.RowResult
        The row's run.
    axes : three matplotlib axes, optional
        Drawn onto; otherwise a new figure ``width`` wide with a shared time axis.
    """
    ax, new = _axes(axes, 3, nrows=3, width=width, sharex=True, panel_height=26.0)
    dashes = ["-", "--", "-.", ":"]
    with style():
        first = row.columns[0]
        ax[0].plot(first.t, first.floor_acc, color=PALETTE[0])
        ax[0].set_ylabel("a (m/s²)")
        for i, column in enumerate(row.columns):
            body = (column.summary or {}).get("body") or {}
            size = (f": H × B = {body['height']:.4g} × {body['width']:.4g} m"
                    if "height" in body and "width" in body else "")
            ax[1].plot(column.t, column.q, color=PALETTE[1 + i % 7], ls=dashes[i % 4],
                       label=f"column {i}{size}")
        ax[1].set_ylabel("q (m)")
        contacts = row.contacts
        if len(contacts):
            t, which = np.asarray(contacts["t"], float), np.asarray(contacts["contact"], int)
            gap = np.asarray(contacts["gap"], float) * 1e3
            for k in sorted(set(which.tolist())):
                chosen = which == k
                ax[2].plot(t[chosen], gap[chosen], color=PALETTE[0], ls=dashes[k % 4],
                           label=f"contact {k}: columns {k} and {k + 1}")
        ax[2].axhline(0.0, color="#464646", lw=0.5)
        ax[2].set_ylabel("clear gap (mm)")
        ax[2].set_xlabel("t (s)")
        times = [i["t"] for i in row.impacts]
        for a in ax:
            for ti in times:
                a.axvline(ti, ymin=0.0, ymax=0.04, color=PALETTE[0], lw=0.6)
        if times:
            ax[2].plot([], [], ls="none", marker="|", markersize=5, color=PALETTE[0],
                       label=f"impact ({len(times)})")
        for a in ax[:2]:
            a.label_outer()
        panel_labels(ax)
        if new:
            handles, labels = [], []
            for a in ax:
                h, lab = a.get_legend_handles_labels()
                handles += h
                labels += lab
            _legend(ax, handles, labels)
    return ax


#: The plots by the kind of result they draw.
PLOTS = {
    "run": (plot_motion, plot_relations, plot_energy),
    "spectrum": (plot_spectrum,),
    "map": (plot_map,),
    "ida": (plot_ida,),
    "fragility": (plot_fragility, plot_capacities),
    "row": (plot_row,),
}
