"""Reconstruct a torus from a numpy point cloud with the dtsl Python module and save a picture of it.

    cmake --build build --target dtsl_python
    PYTHONPATH=build/python python3 docs/python_example.py [OUT.png]   (default /tmp/dtsl_example.png)
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import dtsl  # noqa: E402


def torus_cloud(n, major=3.0, minor=1.0, seed=1):
    """n points area-uniformly on a torus around the z axis (rejection sampling on the tube angle: the
    area element grows with the distance from the axis, major + minor cos v)."""
    rng = np.random.default_rng(seed)
    u, v = [], []
    while len(u) < n:
        cu = rng.uniform(0, 2 * np.pi, n)
        cv = rng.uniform(0, 2 * np.pi, n)
        keep = rng.uniform(0, major + minor, n) < major + minor * np.cos(cv)
        u.extend(cu[keep])
        v.extend(cv[keep])
    u, v = np.array(u[:n]), np.array(v[:n])
    ring = major + minor * np.cos(v)
    return np.column_stack([ring * np.cos(u), ring * np.sin(u), minor * np.sin(v)])


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "/tmp/dtsl_example.png"
    points = torus_cloud(4000)
    # The paper's method with its defaults; any option of `dtsl list reconstructor dtsl` can be given as a
    # keyword, e.g. sharpen=False.
    vertices, faces, summary = dtsl.reconstruct(points, "dtsl")
    stages = summary.pop("stages")
    summary.pop("options")
    print(json.dumps(summary, indent=2))
    for s in stages:
        print(f"  stage {s['name']:6s} {s['seconds']:6.2f} s")
    stats = dtsl.evaluate((vertices, faces), (vertices, faces), samples=1000)
    print(f"watertight {stats['watertight']}, components {stats['components']}, genus {stats['genus']:g}")

    fig = plt.figure(figsize=(8, 6))
    ax = fig.add_subplot(projection="3d")
    ax.plot_trisurf(vertices[:, 0], vertices[:, 1], vertices[:, 2], triangles=faces, cmap="viridis",
                    linewidth=0.05, edgecolor="k", antialiased=True)
    ax.set_box_aspect(np.ptp(vertices, axis=0))
    ax.view_init(elev=35, azim=30)
    ax.set_title(f"dtsl: {len(points)} points -> {len(faces)} triangles, genus {stats['genus']:g}")
    fig.savefig(out, dpi=120, bbox_inches="tight")
    print("wrote", out)


if __name__ == "__main__":
    main()
