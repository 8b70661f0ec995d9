"""Plot of one run: the contact and bond stresses along the surface.

Reads only the run's CSV files, so a plot never recomputes anything."""

import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

from .errors import ParameterError  # noqa: E402


def finished_summary(run_dir):
    """The summary of the converged run in ``run_dir``; ParameterError, in one line, if
    there is none (no such folder, no summary.json: an unfinished run, a run that did
    not converge or failed)."""
    if not os.path.isdir(run_dir):
        raise ParameterError(f"{run_dir}: no such folder")
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            summary = json.load(f)
    except OSError:
        raise ParameterError(f"{run_dir} holds no finished run (no summary.json)") from None
    except ValueError:
        raise ParameterError(f"{run_dir}: its summary.json is not readable JSON") from None
    if not isinstance(summary, dict):
        raise ParameterError(f"{run_dir}: its summary.json is not a run's summary")
    if not summary.get("converged"):
        status = summary.get("status")
        reason = (str(summary.get("reason") or "").splitlines() or [""])[0]  # one line
        outcome = (f"failed: {reason}" if status == "error" else
                   f"did not converge ({status}{': ' + reason if reason else ''})")
        raise ParameterError(f"{run_dir}: the run {outcome}; there are no stresses to plot")
    return summary


def _read_stresses(run_dir, name):
    try:
        return pd.read_csv(os.path.join(run_dir, name))
    except (OSError, ValueError, pd.errors.EmptyDataError):
        raise ParameterError(f"{run_dir}: {name} is missing or unreadable") from None


def plot_run(run_dir, path=None):
    """Write ``run_dir/stresses.png``: the contact stress of every contact interface
    and the bond stresses (normal, shear) of every patch against x1, in the run's units."""
    summary = finished_summary(run_dir)
    contact = _read_stresses(run_dir, "contact.csv")
    interface = _read_stresses(run_dir, "interface.csv")
    units = summary.get("units", {"length": "b", "stress": "E"})    # older runs: b and E
    figure, axes = plt.subplots(figsize=(6.4, 4.0))
    for k, (name, part) in enumerate(contact.groupby("interface", sort=False)):
        axes.plot(part.x1, part.sigma_n, color="C0",
                  label=r"contact $\sigma_n$" if k == 0 else None)
    for k, (name, part) in enumerate(interface.groupby("interface", sort=False)):
        axes.plot(part.x1, part.sigma_n, "--", color="C1",
                  label=r"bond $\sigma_n$" if k == 0 else None)
        axes.plot(part.x1, part.sigma_t, ":", color="C2",
                  label=r"bond $\sigma_t$" if k == 0 else None)
    axes.axhline(0.0, color="0.7", linewidth=0.8)
    axes.set_xlabel(f"$x_1$ ({units['length']})")
    axes.set_ylabel(f"stress ({units['stress']})")
    models = sorted({c["model"] for c in summary["scene"]["coatings"]})
    axes.set_title(f"{len(summary['scene']['coatings'])} coating patch(es), "
                   f"{'/'.join(models) or 'uncoated'}: {summary['iterations']} iterations")
    axes.legend()
    figure.tight_layout()
    path = path or os.path.join(run_dir, "stresses.png")
    figure.savefig(path, dpi=150)
    plt.close(figure)
    return path
