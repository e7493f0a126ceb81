"""The per-dataset plots of `make evaluate` (scripts/evaluate.py): the trajectories over the BIM
plan, the localized pose coloured by its error, and the x-y and yaw error over time of the
localization and the two baselines."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from evaluation_common import draw_plan  # noqa: E402

COLOURS = {"odometry": "tab:orange", "sgraph": "tab:blue", "sgraph_online": "tab:purple",
           "isgraphs": "tab:green"}
LABELS = {"odometry": "odometry (true start pose)",
          "sgraph": "S-Graph alone, final keyframes (true start pose)",
          "sgraph_online": "S-Graph alone, online (true start pose)",
          "isgraphs": "iS-Graphs pose_bim"}


def trajectory_plot(name, truth, series, agraph_path, storey, out_png):
    """`series`: {method: (stamps, err_xy, err_yaw, ref, est)} as evaluation_common.ape gives;
    the localization (isgraphs) is drawn coloured by its x-y error, the baselines as lines."""
    fig, ax = plt.subplots(figsize=(10, 8), dpi=100)
    draw_plan(ax, agraph_path, storey)
    ax.plot(truth.positions_xyz[:, 0], truth.positions_xyz[:, 1], color="black", lw=1.0,
            label="ground truth")
    for method in ("odometry", "sgraph_online"):
        if method in series:
            est = series[method][4]
            ax.plot(est.positions_xyz[:, 0], est.positions_xyz[:, 1], color=COLOURS[method],
                    lw=0.8, alpha=0.8, label=LABELS[method])
    if "isgraphs" in series:
        _, err, _, _, est = series["isgraphs"]
        sc = ax.scatter(est.positions_xyz[:, 0], est.positions_xyz[:, 1], c=err, s=4,
                        cmap="viridis", vmin=0.0, vmax=max(0.1, float(err.max())),
                        label=LABELS["isgraphs"], zorder=3)
        fig.colorbar(sc, ax=ax, label="iS-Graphs x-y error [m]")
        ax.plot(*est.positions_xyz[0, :2], marker="*", ms=14, color="red", ls="none",
                label="first pose in the BIM", zorder=4)
        title = "localized"
    else:
        title = "NOT localized"
    ax.set_title(f"{name}: {title}", fontsize=10)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    fig.savefig(out_png)
    plt.close(fig)


def error_plot(name, t0, series, out_png):
    """x-y and yaw error against time since the bag's start, every method in `series`."""
    fig, (ax_xy, ax_yaw) = plt.subplots(2, 1, figsize=(10, 6), dpi=100, sharex=True)
    for method in ("odometry", "sgraph", "sgraph_online", "isgraphs"):
        if method not in series:
            continue
        stamps, err_xy, err_yaw = series[method][:3]
        style = {"color": COLOURS[method], "label": LABELS[method], "lw": 1.0}
        ax_xy.plot(stamps - t0, err_xy, **style)
        ax_yaw.plot(stamps - t0, err_yaw, **style)
    ax_xy.set_yscale("log")
    ax_xy.set_ylabel("x-y error [m]")
    ax_yaw.set_yscale("log")
    ax_yaw.set_ylabel("yaw error [deg]")
    ax_yaw.set_xlabel("time since the bag's start [s]")
    ax_xy.set_title(f"{name}: error against ground truth (no alignment)", fontsize=10)
    ax_xy.legend(loc="best", fontsize=8)
    for ax in (ax_xy, ax_yaw):
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out_png)
    plt.close(fig)
