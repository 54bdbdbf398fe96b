"""A basin of attraction and a precision sweep from Python, drawn with matplotlib.

    PYTHONPATH=build/python python3 examples/python/basin_and_sweep.py [OUT.png]

Left: the basin of the constant-restitution bouncer at eps = 0.5, a = 24 (the paper's fig.
basin2, on a coarser grid): the class of the orbit from every start (theta, v). Right: the
precision sweep from the release state (1/2, 4) at eps = 0.5, a = 15: the step at which
each precision's orbit leaves the certified enclosure, against its bits (log2 axis). Both
are bouncer's own answers (the CLI's basin and sweep), as numpy arrays; the title of each
panel is its command line, which reruns it in a shell.
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.text
import matplotlib.ticker
import numpy as np
from matplotlib.colors import ListedColormap

import bouncer

out = sys.argv[1] if len(sys.argv) > 1 else "basin_and_sweep.png"

basin = bouncer.basin(eps="0.5", a="24", grid=(160, 120), v_range=("4", "16"), transient=2000, steps=300)
sweep = bouncer.sweep(eps="0.5", a="15", steps=3000)

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.4), gridspec_kw={"width_ratios": [1.25, 1]})

# The basin: one colour per class present (Okabe-Ito, colour-blind safe).
palette = ["#000000", "#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2", "#D55E00", "#CC79A7", "#999999"]
present = sorted(set(basin["class"].ravel().tolist()))
index = np.vectorize({code: i for i, code in enumerate(present)}.get)(basin["class"])
dt = basin["theta"][1] - basin["theta"][0]
dv = basin["v"][1] - basin["v"][0]
extent = (basin["theta"][0] - dt / 2, basin["theta"][-1] + dt / 2, basin["v"][0] - dv / 2, basin["v"][-1] + dv / 2)
left.imshow(index, origin="lower", extent=extent, aspect="auto", interpolation="nearest",
            cmap=ListedColormap(palette[: len(present)]), vmin=-0.5, vmax=len(present) - 0.5)
for i, code in enumerate(present):
    label = basin["classes"][code]
    share = (basin["class"] == code).mean()
    left.plot([], [], "s", color=palette[i], label=f"{label} ({100 * share:.1f}%)")
left.legend(loc="upper right", fontsize=8, framealpha=0.9)
left.set_xlabel(r"initial phase $\theta_0$")
left.set_ylabel(r"initial velocity $v_0$")
left.set_title("basin, constant restitution, eps = 0.5, a = 24", fontsize=10)

# The sweep: where each precision leaves the certified enclosure.
left_at = sweep["leaves_enclosure_at"]
bits = sweep["bits"]
stays = left_at < 0
right.plot(bits[~stays], left_at[~stays], "o", color="#0072B2", label="leaves the enclosure at step")
if stays.any():
    right.plot(bits[stays], np.full(stays.sum(), sweep["inputs"]["steps"]), "^", color="#009E73",
               label="stays inside through the last step")
right.set_xscale("log", base=2)
right.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
right.set_xlabel("significand bits")
right.set_ylabel("step")
right.set_title(f"precision sweep, eps = 0.5, a = 15 (slope {sweep['slope_steps_per_bit']:.2f} steps/bit)",
                fontsize=10)
right.legend(loc="upper left", fontsize=8)
right.grid(True, which="both", alpha=0.3)

fig.text(0.01, 0.01, f"{basin['command_line']}\n{sweep['command_line']}", fontsize=6, family="monospace",
         va="bottom", color="#555555")
fig.tight_layout(rect=(0, 0.06, 1, 1))
# After the layout: the named precisions' labels, horizontal above their points; where one
# would overlap a label already placed (dd and quad are 7 bits apart), it is lifted a line
# at a time and joined to its point by a thin leader.
placed = []
for name, x, y, inside in sorted(zip(sweep["precision"], bits, left_at, stays), key=lambda t: t[1]):
    if name.startswith("mpfr") or name.startswith("interval"):
        continue
    point = (x, sweep["inputs"]["steps"] if inside else y)
    for lift in range(12):
        dy = 6 + 9 * lift
        label = right.annotate(name, point, textcoords="offset points", xytext=(0, dy), fontsize=7, color="#333333",
                               ha="center", va="bottom",
                               arrowprops=dict(arrowstyle="-", color="#999999", lw=0.6, shrinkA=0, shrinkB=3)
                               if lift else None)
        fig.canvas.draw()
        box = matplotlib.text.Text.get_window_extent(label).expanded(1.1, 1.15)
        if not any(box.overlaps(other) for other in placed):
            placed.append(box)
            break
        label.remove()
fig.savefig(out, dpi=150, metadata={"Software": f"bouncer {bouncer.__version__}, matplotlib"})
print(f"wrote {out}: basin {basin['class'].shape[1]} x {basin['class'].shape[0]}, "
      f"sweep of {len(sweep['precision'])} precisions")
