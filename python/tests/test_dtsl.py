"""Tests of the dtsl Python module (python/dtsl_module.cpp). Run: PYTHONPATH=build/python python3 -m pytest python/tests"""
import os
import warnings

import numpy as np
import pytest

import dtsl

# A baseline that meshes a few hundred points in well under a second, for most tests; the paper's method
# runs once (test_dtsl_pipeline_closed_sphere).
FAST = "pcl_poisson"


def sphere_cloud(n=800, radius=1.0, center=(0.0, 0.0, 0.0), seed=3):
    """n points uniformly on a sphere (normalised Gaussian vectors)."""
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(n, 3))
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    return radius * p + np.asarray(center)


def radii(vertices, center):
    return np.linalg.norm(vertices - np.asarray(center), axis=1)


# ---- reconstruct ----------------------------------------------------------------------------------


def test_pipelines_and_version():
    names = dtsl.pipelines()
    assert "dtsl" in names and FAST in names
    assert names == sorted(names)
    assert isinstance(dtsl.__version__, str) and dtsl.__version__


def test_context_keywords_are_no_option_of_any_pipeline():
    # reconstruct(threads=, seed=) set the run context; an option of the same name could not be reached.
    for name in dtsl.pipelines():
        options = dtsl.pipeline_options(name)
        assert "threads" not in options and "seed" not in options, name


def test_mesh_follows_the_input_units():
    # Scaled by 100 and moved: the mesh must come back in the same frame, not in [-1, 1]^3.
    center = (250.0, -40.0, 7.0)
    cloud = sphere_cloud(radius=100.0, center=center)
    vertices, faces, summary = dtsl.reconstruct(cloud, FAST, depth=6)
    assert vertices.dtype == np.float64 and vertices.shape[1] == 3 and len(vertices) > 100
    assert faces.dtype == np.int64 and faces.shape[1] == 3 and len(faces) > 100
    assert faces.min() >= 0 and faces.max() < len(vertices)
    r = radii(vertices, center)
    assert abs(np.median(r) - 100.0) < 3.0
    assert r.min() > 80.0 and r.max() < 120.0
    assert summary["pipeline"] == FAST
    assert summary["points"] == len(cloud)
    assert summary["vertices"] == len(vertices) and summary["faces"] == len(faces)
    assert summary["seconds"] > 0.0
    assert summary["options"]["depth"] == 6


def test_non_contiguous_and_integer_input():
    cloud = sphere_cloud(n=600)
    wide = np.zeros((len(cloud), 6))
    wide[:, ::2] = cloud  # a strided view: every other column
    view = wide[:, ::2]
    assert not view.flags["C_CONTIGUOUS"]
    v1, f1, _ = dtsl.reconstruct(view, FAST, depth=5)
    v2, f2, _ = dtsl.reconstruct(np.ascontiguousarray(view), FAST, depth=5)
    assert np.array_equal(v1, v2) and np.array_equal(f1, f2)
    # Integer coordinates (and a list of lists) are numbers too.
    grid = np.round(cloud * 1000).astype(np.int32)
    v3, _, _ = dtsl.reconstruct(grid.tolist(), FAST, depth=5)
    assert abs(np.median(radii(v3, (0, 0, 0))) - 1000.0) < 40.0


# The paper's method, made fast for a test (about a second): a coarser T-mesh, one round, no final
# refinement or its topology guard, a direct solver for the few hundred control points.
FAST_DTSL = dict(evolution_tmesh_max_depth=4, evolution_fine_levels=0, evolution_final_refinement=False,
                 refinement_guard=False, evolution_solver="eigen_ldlt", flip_refinements=0)


def test_dtsl_pipeline_closed_sphere():
    center = (10.0, 20.0, 30.0)
    cloud = sphere_cloud(n=1000, radius=5.0, center=center)
    vertices, faces, summary = dtsl.reconstruct(cloud, "dtsl", **FAST_DTSL)
    stats = dtsl.evaluate((vertices, faces), (vertices, faces), samples=1000)
    assert stats["watertight"] and stats["components"] == 1 and stats["genus"] == 0
    deviation = np.abs(radii(vertices, center) - 5.0)
    assert np.median(deviation) < 0.05 and deviation.max() < 0.3  # 1% and 6% of the radius
    assert [s["name"] for s in summary["stages"]] == ["TL", "MT", "D-Map", "B-Evl"]
    for s in summary["stages"]:
        assert s["seconds"] >= 0.0 and isinstance(s["summary"], dict)
    assert summary["stages"][0]["summary"]["iterations"] > 0
    assert summary["stages"][-1]["vertices"] == len(vertices)


def test_options_of_every_type():
    cloud = sphere_cloud(n=500)
    _, _, summary = dtsl.reconstruct(cloud, FAST, depth=np.int64(5), point_weight=np.float32(2.0), manifold=False,
                                     normals="pca_mst", threads=1, seed=7)
    o = summary["options"]
    assert o["depth"] == 5 and o["point_weight"] == 2.0 and o["manifold"] is False and o["normals"] == "pca_mst"


# ---- bad input: each raises before any work, naming the problem ------------------------------------


@pytest.mark.parametrize(
    "points, message",
    [
        (np.zeros((10, 2)), r"points: expected an \(n, 3\) array, got shape \(10, 2\)"),
        (np.zeros(30), r"points: expected an \(n, 3\) array, got shape \(30,\)"),
        (np.zeros((2, 10, 3)), r"got shape \(2, 10, 3\)"),
        (np.full((10, 3), "a"), r"points: expected numbers, got dtype <U1"),
        (np.ones((10, 3), dtype=bool), r"points: expected numbers, got dtype bool"),
        (np.ones((10, 3), dtype=complex), r"points: expected numbers, got dtype complex128"),
        ([[0, 0, 0], [1, 1]], r"points: not convertible to an array"),
    ],
)
def test_bad_arrays(points, message):
    with pytest.raises(ValueError, match=message):
        dtsl.reconstruct(points, FAST)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_row_is_named(bad):
    cloud = sphere_cloud(n=100)
    cloud[42, 1] = bad
    with pytest.raises(ValueError, match=r"points: row 42 is not finite \("):
        dtsl.reconstruct(cloud, FAST)


@pytest.mark.parametrize("pipeline", ["dtsl", FAST])
def test_too_few_points(pipeline):
    # The pipeline's own minimum, as `dtsl reconstruct` reports it.
    with pytest.raises(dtsl.AlgorithmError, match=rf"{pipeline}: needs at least \d+ points, got 3"):
        dtsl.reconstruct(np.eye(3), pipeline)


def test_empty_and_coincident_points():
    with pytest.raises(dtsl.AlgorithmError, match="points: no points"):
        dtsl.reconstruct(np.zeros((0, 3)), FAST)
    with pytest.raises(dtsl.AlgorithmError, match="points: all points coincide"):
        dtsl.reconstruct(np.ones((20, 3)), FAST)


def test_unknown_option_and_pipeline():
    cloud = sphere_cloud(n=100)
    with pytest.raises(dtsl.ConfigError, match=r"options\.dpeth: unknown key.*'depth'.*known keys: .*depth"):
        dtsl.reconstruct(cloud, FAST, dpeth=6)
    with pytest.raises(ValueError):  # a ConfigError is a ValueError too
        dtsl.reconstruct(cloud, FAST, dpeth=6)
    with pytest.raises(dtsl.ConfigError, match=r"pipeline: unknown pipeline 'no_such'; known: .*dtsl"):
        dtsl.reconstruct(cloud, "no_such")


def test_presets():
    presets = dtsl.presets("dtsl")
    assert list(presets)[0] == "default" and presets["default"]["values"] == {}
    assert "paper" in presets and presets["paper"]["values"]["evolution_velocity"] == "paper"
    assert list(dtsl.presets(FAST)) == ["default"]  # every pipeline has default
    with pytest.raises(dtsl.ConfigError, match=r"pipeline: unknown pipeline 'no_such'"):
        dtsl.presets("no_such")
    cloud = sphere_cloud(n=100)
    with pytest.raises(dtsl.ConfigError, match=r"preset: unknown preset 'papr'.*'paper'.*known: default, paper"):
        dtsl.reconstruct(cloud, "dtsl", preset="papr")
    with pytest.raises(dtsl.ConfigError, match=r"unknown preset 'paper' of pipeline 'pcl_poisson'"):
        dtsl.reconstruct(cloud, FAST, preset="paper")


def test_paper_preset_then_options():
    # The preset's values, then the keywords over them; the summary says which preset ran.
    cloud = sphere_cloud(n=1000)
    options = dict(FAST_DTSL, bilateral_max_iterations=3)
    vertices, faces, summary = dtsl.reconstruct(cloud, "dtsl", preset="paper", **options)
    assert summary["preset"] == "paper"
    assert summary["options"]["evolution_velocity"] == "paper"
    assert summary["options"]["evolution_fine_levels"] == 0
    assert summary["options"]["bilateral_max_iterations"] == 3
    stats = dtsl.evaluate((vertices, faces), (vertices, faces), samples=1000)
    assert stats["watertight"] and stats["components"] == 1 and stats["genus"] == 0


@pytest.mark.parametrize(
    "options, message",
    [
        ({"depth": 4.5}, r"options\.depth: expected an integer, got '4\.5'"),
        ({"depth": "deep"}, r"options\.depth: expected an integer, got 'deep'"),
        ({"depth": True}, r"options\.depth: expected an integer, got 'true'"),
        ({"point_weight": float("nan")}, r"options\.point_weight: expected a finite number, got 'nan'"),
        ({"manifold": 3}, r"options\.manifold: expected true or false, got '3'"),
        ({"depth": None}, r"options\.depth: expected a value"),
        ({"depth": [1, 2]}, r"options\.depth: expected an integer, got a list"),
    ],
)
def test_bad_option_values(options, message):
    with pytest.raises(dtsl.ConfigError, match=message):
        dtsl.reconstruct(sphere_cloud(n=100), FAST, **options)


def test_option_of_no_option_type():
    with pytest.raises(TypeError, match="option 'depth': a dict cannot be an option value"):
        dtsl.reconstruct(sphere_cloud(n=100), FAST, depth={"a": 1})


def test_bad_context_keywords():
    with pytest.raises(ValueError, match="threads: expected at least 1, got 0"):
        dtsl.reconstruct(sphere_cloud(n=100), FAST, threads=0)
    with pytest.raises(ValueError, match="seed: expected a non-negative integer, got -1"):
        dtsl.reconstruct(sphere_cloud(n=100), FAST, seed=-1)


# ---- evaluate ---------------------------------------------------------------------------------------


def test_evaluate_mesh_against_itself_and_a_shifted_copy():
    vertices, faces, _ = dtsl.reconstruct(sphere_cloud(), FAST, depth=6)
    same = dtsl.evaluate((vertices, faces), (vertices, faces), samples=2000)
    assert same["chamfer"] < 1e-9 and same["hausdorff"] < 1e-9
    assert same["fscore"] == 1.0
    for key in ("accuracy", "completeness", "precision", "recall", "normal_consistency", "tau", "watertight",
                "components", "genus", "vertices", "faces", "boundary_edges", "min_angle_deg"):
        assert key in same, key
    shifted = dtsl.evaluate((vertices + [0.05, 0.0, 0.0], faces), (vertices, faces), samples=2000)
    assert 0.005 < shifted["chamfer"] < 0.05 and shifted["hausdorff"] >= shifted["chamfer"]
    assert shifted["fscore"] < 1.0


def test_evaluate_bad_input():
    v = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    f = np.array([[0, 1, 2]])
    with pytest.raises(ValueError, match=r"mesh faces: row 0 has index 3, outside \[0, 3\)"):
        dtsl.evaluate((v, f + 1), (v, f))
    with pytest.raises(ValueError, match="truth faces: expected integers, got dtype float64"):
        dtsl.evaluate((v, f), (v, f.astype(float)))
    with pytest.raises(ValueError, match=r"mesh: expected a \(vertices, faces\) pair"):
        dtsl.evaluate(v, (v, f))
    with pytest.raises(dtsl.ConfigError, match="samples"):
        dtsl.evaluate((v, f), (v, f), samples=0)


# ---- files ------------------------------------------------------------------------------------------


def test_read_points_round_trip(tmp_path):
    cloud = sphere_cloud(n=50)
    path = tmp_path / "cloud.xyz"
    np.savetxt(path, cloud, fmt="%.17g")
    back = dtsl.read_points(path)  # os.PathLike and str both work
    assert back.shape == (50, 3) and back.dtype == np.float64
    assert np.array_equal(back, cloud)
    assert np.array_equal(dtsl.read_points(str(path)), cloud)


def test_read_mesh_and_file_errors(tmp_path):
    path = tmp_path / "tri.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    vertices, faces = dtsl.read_mesh(path)
    assert vertices.shape == (3, 3) and faces.tolist() == [[0, 1, 2]]
    missing = tmp_path / "missing.ply"
    with pytest.raises(dtsl.FileError, match="missing.ply"):
        dtsl.read_points(missing)
    with pytest.raises(OSError):  # a FileError is an OSError too
        dtsl.read_points(missing)
    bad = tmp_path / "bad.xyz"
    bad.write_text("0 0 0\n1 2 x\n")
    with pytest.raises(dtsl.FileError, match=r"bad\.xyz:2"):
        dtsl.read_points(bad)


# ---- run --------------------------------------------------------------------------------------------

CONFIG = """
experiment: pytest_tiny
seed: 1
metrics: {samples: 1000}
datasets:
  - name: sphere
    shape: sphere
    sampler: {type: area, count: 500}
pipelines:
  - name: poisson
    type: pcl_poisson
    options: {depth: 5}
"""


def test_run_creates_the_result_directory(tmp_path):
    config = tmp_path / "tiny.yaml"
    config.write_text(CONFIG)
    results = tmp_path / "results"
    directory = dtsl.run(config, results=results, run_id="t1", progress=False)
    assert os.path.samefile(directory, results / "pytest_tiny" / "t1")
    assert (results / "pytest_tiny" / "t1" / "table.md").is_file()
    run_dir = results / "pytest_tiny" / "t1" / "runs" / "sphere__poisson"
    assert (run_dir / "final.ply").is_file() and (run_dir / "metrics.json").is_file()
    # Started again, the finished run is skipped, not redone.
    mtime = (run_dir / "final.ply").stat().st_mtime_ns
    dtsl.run(config, results=results, run_id="t1", progress=False)
    assert (run_dir / "final.ply").stat().st_mtime_ns == mtime


def test_run_errors(tmp_path):
    config = tmp_path / "tiny.yaml"
    config.write_text(CONFIG)
    with pytest.raises(dtsl.ConfigError, match="depht"):
        dtsl.run(config, results=tmp_path / "r", overrides=["pipelines.poisson.options.depht=5"], progress=False)
    with pytest.raises(dtsl.FileError, match="nothere.yaml"):
        dtsl.run(tmp_path / "nothere.yaml", results=tmp_path / "r")
    with pytest.raises(ValueError, match="run_id: use letters"):
        dtsl.run(config, results=tmp_path / "r", run_id="a/b")
    with pytest.raises(ValueError, match="jobs: expected at least 1"):
        dtsl.run(config, results=tmp_path / "r", jobs=0)
    assert not (tmp_path / "r").exists()  # nothing written on a config error


def test_run_with_a_failing_pipeline_warns(tmp_path):
    config = tmp_path / "fail.yaml"
    # Two points per dataset: the pipeline refuses them; the run is recorded as failed, not raised.
    config.write_text(CONFIG.replace("count: 500", "count: 3"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        directory = dtsl.run(config, results=tmp_path / "r", progress=False)
    assert any("1 of 1 runs failed" in str(w.message) for w in caught)
    assert os.path.isdir(directory)


def test_run_after_parallel_work_in_the_same_process(tmp_path):
    # evaluate() runs OpenMP regions, so this process then has an OpenMP thread pool; a run forked from it
    # must not wait for the pool's threads, which a forked child does not have. In a fresh interpreter,
    # so that the order of the tests does not matter; a hang is a failure after the timeout.
    import subprocess
    import sys
    config = tmp_path / "tiny.yaml"
    config.write_text(CONFIG)
    script = f"""
import numpy as np, dtsl
rng = np.random.default_rng(3)
p = rng.normal(size=(800, 3)); p /= np.linalg.norm(p, axis=1, keepdims=True)
v, f, _ = dtsl.reconstruct(p, "pcl_poisson", depth=6)
dtsl.evaluate((v, f), (v, f), samples=20000)
print(dtsl.run({str(config)!r}, results={str(tmp_path / "results")!r}, progress=False))
"""
    env = {k: v for k, v in os.environ.items() if k != "OMP_NUM_THREADS"}
    done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    run_dir = tmp_path / "results" / "pytest_tiny"
    logs = list(run_dir.glob("*/runs/sphere__poisson/log.txt"))
    assert logs and (run_dir / logs[0].parts[-4] / "table.md").is_file()
    if (os.cpu_count() or 1) > 1:
        assert "one thread" in logs[0].read_text()
