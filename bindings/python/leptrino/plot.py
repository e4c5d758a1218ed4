"""Draw a Recording: forces and moments against time (needs matplotlib)."""

from __future__ import annotations

from typing import Any, Optional

from .values import Recording


def pyplot(path: Optional[str] = None) -> Any:
    """matplotlib.pyplot (the Agg backend when drawing to a file), or
    ImportError with an install hint: call it before recording anything."""
    try:
        import matplotlib

        if path is not None:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as exc:
        raise ImportError(
            "plotting needs matplotlib: pip install matplotlib"
        ) from exc
    return plt


def plot_recording(rec: Recording, path: Optional[str] = None, *, title: str = "") -> Any:
    """Two panels (Fx Fy Fz in N, Mx My Mz in N·m) against seconds since the
    first sample. Saves a PNG to path when given; returns the Figure.
    ImportError with an install hint when matplotlib is missing."""
    plt = pyplot(path)
    t = rec.elapsed
    fig, (ax_f, ax_m) = plt.subplots(2, 1, sharex=True, figsize=(10, 6), constrained_layout=True)
    for i, name in enumerate(("Fx", "Fy", "Fz")):
        ax_f.plot(t, rec.si[:, i], label=name, linewidth=0.8)
    for i, name in enumerate(("Mx", "My", "Mz")):
        ax_m.plot(t, rec.si[:, 3 + i], label=name, linewidth=0.8)
    ax_f.set_ylabel("force [N]")
    ax_m.set_ylabel("moment [N·m]")
    ax_m.set_xlabel("time [s]")
    for ax in (ax_f, ax_m):
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", ncol=3, fontsize="small")
    over = rec.overload
    if over.any():
        for ax in (ax_f, ax_m):
            ax.fill_between(t, 0, 1, where=over, transform=ax.get_xaxis_transform(),
                            color="red", alpha=0.12, label="overload")
    rate = rec.rate_hz
    head = title + ("  —  " if title else "") + f"{len(rec)} samples, {rate:.0f} Hz"
    fig.suptitle(head)
    if path is not None:
        fig.savefig(path, dpi=100)
        plt.close(fig)
    return fig
