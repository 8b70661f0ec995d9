"""The paper's figures' scenes: every one listed once, in the sweep file that `make fig3
fig4 fig5` runs (studies/sweeps/figures.toml), and which runs each figure draws."""

from studies.paths import FIGURE_SWEEP
from orchestrate.sweeps import load_sweep

# Every scene the three figures need, (model, h2, E2) (its runs land in
# results/figures/runs/).
FIGURE_SCENES = sorted({(point["model"], point["h2"], point["E2"])
                        for point in load_sweep(FIGURE_SWEEP)[1]})
FIGURE_HEIGHTS = tuple(sorted({h2 for _, h2, _ in FIGURE_SCENES}, reverse=True))

# The runs each figure draws, by their values (studies/figures.py draws its panels
# and curves from these): fig. 3 panels h2, curves E2; fig. 4 panels E2, curves h2;
# fig. 5 columns E2, rows h2.
DRAWS = {
    "fig3": {"model": ("shell", "elastic"), "h2": (1.0, 0.125), "E2": (5.0, 1.0)},
    "fig4": {"model": ("shell", "elastic"), "h2": (1.0, 0.5, 0.25, 0.125, 0.0625),
             "E2": (5.0, 1.0)},
    "fig5": {"model": ("elastic",), "h2": (1.0, 0.5, 0.25, 0.125), "E2": (0.2, 1.0, 5.0)},
}
