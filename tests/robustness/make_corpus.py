#!/usr/bin/env python3
"""Writes the robustness corpus (tests/robustness/corpus/) and its expectations file.

Each entry is a bad, hostile or degenerate input with the outcome `dtsl` must give it:
  error   exit code 1, the message contains the substring (which names the problem: file, key or value)
  either  degenerate but valid input: a clean success with a valid mesh, or a clean error containing
          the substring (empty: any "dtsl: error:" message)
robustness_test.cpp runs every point file through `dtsl reconstruct IN OUT` with --pipeline pcl_poisson
and --pipeline dtsl, and every config through `dtsl run CONFIG`. The files are committed; run this
script again only to change the corpus.
"""
import math
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")
entries = []  # (relative path, outcome, substring)


def put(rel, content, outcome, expect):
    path = os.path.join(CORPUS, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(content.encode() if isinstance(content, str) else content)
    entries.append((rel, outcome, expect))


def ply_header(fmt, nv, props=("x", "y", "z"), ptype="float", faces=None, ftype="int"):
    h = f"ply\nformat {fmt} 1.0\nelement vertex {nv}\n"
    h += "".join(f"property {ptype} {p}\n" for p in props)
    if faces is not None:
        h += f"element face {faces}\nproperty list uchar {ftype} vertex_indices\n"
    return h + "end_header\n"


def sphere(n, r=1.0, c=(0.0, 0.0, 0.0), seed=1):
    rnd = random.Random(seed)
    out = []
    for _ in range(n):
        z = rnd.uniform(-1, 1)
        t = rnd.uniform(0, 2 * math.pi)
        s = math.sqrt(1 - z * z)
        out.append((c[0] + r * s * math.cos(t), c[1] + r * s * math.sin(t), c[2] + r * z))
    return out


def xyz(points):
    return "".join(f"{p[0]!r} {p[1]!r} {p[2]!r}\n" for p in points)


tetra = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]

# ---- PLY ---------------------------------------------------------------------------------------------
put("points/ply_truncated_ascii.ply", ply_header("ascii", 3) + "0.000000000 0.000000000 0.000000000\n1.000000 0",
    "error", "the file ends inside vertex 1 (of 3)")
put("points/ply_truncated_ascii_short.ply", ply_header("ascii", 8) + "0 0 0\n1 0 0\n0 1",
    "error", "header promises 8 'vertex' elements")
body = b"".join(struct.pack("<3f", *p) for p in tetra)
put("points/ply_truncated_binary.ply", ply_header("binary_little_endian", 4).encode() + body[:40],
    "error", "truncated")
put("points/ply_truncated_binary_face.ply",
    ply_header("binary_little_endian", 4, faces=2).encode() + body + struct.pack("<B3i", 3, 0, 1, 2) + b"\x03\x00",
    "error", "face 1 (of 2)")
put("points/ply_truncated_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nprop",
    "error", "unexpected PLY header line starting with 'prop'")
put("points/ply_header_only.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "error",
    "no 'end_header' line")
put("points/ply_garbage.ply", bytes(random.Random(7).randrange(256) for _ in range(3000)),
    "error", "not a PLY file")
put("points/ply_garbage_body_ascii.ply", ply_header("ascii", 3) + "0 0 0\nfoo bar baz\n1 1 1\n",
    "error", "expected a number for x, got 'foo'")
put("points/ply_garbage_body_binary.ply",
    ply_header("binary_big_endian", 3, ptype="double").encode() + bytes([0xFF] * 72),
    "error", "NaN or infinite coordinate")
put("points/ply_10M_vertices_ascii.ply", ply_header("ascii", 10_000_000) + "0 0 0\n1 0 0\n0 1 0\n",
    "error", "header promises 10000000 'vertex' elements")
put("points/ply_10M_vertices_binary.ply", ply_header("binary_little_endian", 10_000_000).encode() + body[:36],
    "error", "header promises 10000000 'vertex' elements")
put("points/ply_huge_count.ply", ply_header("ascii", 99999999999999999999) + "0 0 0\n",
    "error", "out of range")
put("points/ply_negative_count.ply", ply_header("ascii", -3) + "0 0 0\n", "error", "negative element count")
put("points/ply_unknown_format.ply", ply_header("binary_middle_endian", 1) + "0 0 0\n",
    "error", "unknown PLY format 'binary_middle_endian'")
put("points/ply_unknown_type.ply", ply_header("ascii", 1, ptype="float128") + "0 0 0\n",
    "error", "unknown PLY type 'float128'")
put("points/ply_missing_z.ply", ply_header("ascii", 2, props=("x", "y")) + "0 0\n1 1\n",
    "error", "no property 'z'")
put("points/ply_face_index_out_of_range.ply", ply_header("ascii", 3, faces=1) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
    "error", "vertex index 7 out of range")
put("points/ply_face_negative_index.ply", ply_header("ascii", 3, faces=1) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
    "error", "vertex index -1 out of range")
put("points/ply_nan_ascii.ply", ply_header("ascii", 3) + "0 0 0\nnan 0 0\n0 1 0\n", "error", "NaN or infinite")
put("points/ply_inf_binary.ply",
    ply_header("binary_little_endian", 3).encode() + struct.pack("<9f", 0, 0, 0, float("inf"), 0, 0, 0, 1, 0),
    "error", "vertex 1 (of 3) at byte")
put("points/ply_trailing_data.ply", ply_header("ascii", 2) + "0 0 0\n1 0 0\n2 0 0\n",
    "error", "unexpected data after the last element")
put("points/ply_zero_vertices.ply", ply_header("ascii", 0), "error", "contains no points")
# ---- OFF ---------------------------------------------------------------------------------------------
put("points/off_too_few_vertices.off", "OFF\n5 0 0\n" + "0.000000000 0.000000000 0.000000000\n" * 3,
    "error", "the file ends after 3 of the 5 vertices")
put("points/off_too_many_lines.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 0 1\n",
    "error", "unexpected data after the last face")
put("points/off_wrong_face_count.off", "OFF\n3 2 0\n" + "0.000000000 0.000000000 0.000000000\n" * 3 + "3 0 1 2\n",
    "error", "the file ends after 1 of the 2 faces")
put("points/off_bad_keyword.off", "OFFICE\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", "error", "not an OFF file")
put("points/off_negative_counts.off", "OFF\n-3 0 0\n", "error", "negative vertex or face count")
put("points/off_huge_counts.off", "OFF\n2000000000 2000000000 0\n0 0 0\n", "error", "header promises 2000000000 vertices")
put("points/off_face_index_out_of_range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
    "error", "vertex index 3 out of range")
put("points/off_face_too_short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n5 0 1 2\n",
    "error", "face 0 announces 5 vertices but lists 3")
# ---- OBJ ---------------------------------------------------------------------------------------------
put("points/obj_negative_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n",
    "error", "relative vertex index -5 out of range")
put("points/obj_index_out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n",
    "error", "vertex index 99 out of range (the file has 3 vertices)")
put("points/obj_index_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "error", "vertex index 0 is invalid")
put("points/obj_huge_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n",
    "error", "vertex index is out of range")
put("points/obj_short_vertex.obj", "v 0 0 0\nv 1 0\n", "error", "a vertex needs 3 coordinates, got 2")
put("points/obj_inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\n", "error", "NaN or infinite")
put("points/obj_no_vertices.obj", "# nothing\ng group\nusemtl m\n", "error", "contains no points")
# ---- XYZ ---------------------------------------------------------------------------------------------
put("points/xyz_nan.xyz", xyz(sphere(50)) + "nan 0 0\n", "error", "NaN or infinite: 'nan'")
put("points/xyz_inf.xyz", xyz(sphere(50)) + "0 -inf 0\n", "error", "NaN or infinite: '-inf'")
put("points/xyz_overflow.xyz", xyz(sphere(50)) + "0 0 1e400\n", "error", "NaN or infinite: '1e400'")
put("points/xyz_mixed_columns.xyz", "0 0 0\n1 0 0 0 0 1\n", "error", "expected 3 numbers like line 1, got 6")
put("points/xyz_words.xyz", "0 0 0\none two three\n", "error", "expected a number for a coordinate, got 'one'")
put("points/xyz_empty.xyz", "", "error", "file is empty")
put("points/xyz_comments_only.xyz", "# x y z\n\n# nothing\n", "error", "contains no points")
put("points/xyz_binary_zeros.xyz", bytes(4096), "error", "xyz_binary_zeros.xyz:1")
# ---- degenerate but valid point sets -----------------------------------------------------------------
put("points/xyz_1_point.xyz", "0.5 0.25 1\n", "either", "")
put("points/xyz_2_points.xyz", "0 0 0\n1 1 1\n", "either", "")
put("points/xyz_3_points.xyz", "0 0 0\n1 0 0\n0 1 0\n", "either", "")
put("points/xyz_4_points.xyz", xyz(tetra), "either", "")
put("points/xyz_4_coplanar_points.xyz", "0 0 0\n1 0 0\n0 1 0\n1 1 0\n", "either", "")
put("points/xyz_duplicated_plus_one.xyz", "0.5 0.5 0.5\n" * 499 + "1 2 3\n", "either", "")
put("points/xyz_two_tiny_clusters.xyz", xyz(sphere(400, r=1e-6) + sphere(400, r=1e-6, c=(1.0, 1.0, 1.0), seed=2)),
    "either", "")
put("points/xyz_needle.xyz", "".join(f"{t / 500!r} {1e-9 * math.sin(t)!r} {1e-9 * math.cos(t)!r}\n" for t in range(500)),
    "either", "")
put("points/xyz_all_duplicated.xyz", "0.3 -2 7\n" * 500, "either", "")
put("points/xyz_collinear.xyz", "".join(f"{t / 100!r} {2 * t / 100!r} {-t / 100!r}\n" for t in range(300)),
    "either", "")
put("points/xyz_coplanar.xyz", "".join(f"{i / 20!r} {j / 20!r} 0.5\n" for i in range(25) for j in range(25)),
    "either", "")
put("points/xyz_near_1e30.xyz", xyz(sphere(1500, r=1e30, c=(3e30, -1e30, 0.0))), "either", "")
put("points/xyz_1e30_offset_tiny_spread.xyz", xyz(sphere(500, r=1.0, c=(1e30, 1e30, 1e30))), "either", "")
put("points/xyz_tiny_scale.xyz", xyz(sphere(1500, r=1e-300)), "either", "")
# ---- PCD and other files -----------------------------------------------------------------------------
put("points/pcd_truncated.pcd",
    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1000\nHEIGHT 1\nPOINTS 1000\nDATA binary\n"
    "\x00\x00\x00\x00", "error", "header promises 1000 points")
# Found by fuzz/fuzz_pcd: PCL 1.13 reads header lines after DATA, so this body overrides COUNT and PCL
# reads far past its buffer (SIGSEGV in pcl::PCDReader::readBodyBinary) unless our validation refuses it.
put("points/pcd_header_after_data.pcd",
    "VERSION 0.7\nFIELDS x y z _\nSIZE 8 8 8 1\nTYPE F F F U\nCOUNT 1 1 1 4\nWIDTH 1\nHEIGHT 1\nPOINTS 1\n"
    "DATA binary\n# .PVERSION 0.7\nFIELDS x y z _\nSIZE 8 8 8 1\nTYPE F F F U\nCOUNT 1 1 12222222222 5",
    "error", "the data after the DATA line begins with what PCL would read as a header line")
# Also found by fuzz/fuzz_pcd: a header line starting with a blank ends PCL's header there (SIGSEGV on a
# null pointer in pcl::PCDReader::read).
put("points/pcd_blank_header_line.pcd",
    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n POINTS 2\nDATA binary\n"
    + "\0" * 24, "error", "a PCD header line must not start with a blank")
# Found by fuzz/fuzz_pcd in our own validation: FIELDS repeated after SIZE made it read past its arrays.
put("points/pcd_fields_twice.pcd",
    "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nFIELDS 1\nPOINTS 2\nDATA binary\n" + "\0" * 24,
    "error", "FIELDS, SIZE, TYPE and COUNT must give one entry per field")
put("points/pcd_no_data.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n", "error", "the header has no DATA line")
put("points/unknown_extension.stl", "solid x\nendsolid x\n", "error", "unknown file extension '.stl'")

# ---- experiment configs (dtsl run CONFIG) --------------------------------------------------------------
GOOD = """experiment: robust
seed: 1
metrics: {samples: 1000}
datasets:
  - name: ball
    shape: {type: sphere}
    sampler: {type: area, count: 500}
pipelines:
  - name: poisson
    type: pcl_poisson
    options: {depth: 5}
"""


def config(name, text, expect):
    put("configs/" + name + ".yaml", text, "error", expect)


config("syntax_error", GOOD.replace("{type: sphere}", "{type: sphere"), "YAML syntax error")
config("tab_indent", GOOD.replace("  - name: ball", "\t- name: ball"), "YAML syntax error")
config("not_a_map", "- just\n- a list\n", "expected a YAML map")
config("empty", "", "expected a YAML map")
config("garbage_bytes", bytes(random.Random(3).randrange(1, 256) for _ in range(2000)).decode("latin-1"),
       "garbage_bytes.yaml")
config("unknown_top_key", GOOD + "colour: blue\n", "colour: unknown key")
config("unknown_option", GOOD.replace("{depth: 5}", "{depht: 5}"), "pipelines[0].options.depht: unknown key")
config("unknown_sampler_key", GOOD.replace("count: 500", "cuont: 500"), "cuont")
config("wrong_type_int", GOOD.replace("{depth: 5}", "{depth: deep}"), "pipelines[0].options.depth: expected an integer, got 'deep'")
config("wrong_type_fraction", GOOD.replace("{depth: 5}", "{depth: 5.5}"), "depth: expected an integer, got '5.5'")
config("wrong_type_map", GOOD.replace("{depth: 5}", "{depth: {a: 1}}"), "depth: expected an integer, got a map")
config("wrong_type_seed", GOOD.replace("seed: 1", "seed: [1, 2]"), "seed: expected a non-negative integer")
config("negative_seed", GOOD.replace("seed: 1", "seed: -4"), "seed: must not be negative")
config("huge_int", GOOD.replace("{depth: 5}", "{depth: 1e300}"), "depth: expected an integer, got '1e300'")
config("out_of_range_depth", GOOD.replace("{depth: 5}", "{depth: 99}"), "depth: must be in")
config("out_of_range_samples", GOOD.replace("{samples: 1000}", "{samples: 3}"), "metrics.samples: must be in")
config("nan_value", GOOD.replace("{samples: 1000}", "{samples: 1000, fscore_tau_ratio: .nan}"),
       "metrics.fscore_tau_ratio: expected a finite number")
config("negative_timeout", GOOD.replace("seed: 1", "seed: 1\ntimeout_seconds: -5"), "timeout_seconds: must not be negative")
config("unknown_pipeline", GOOD.replace("type: pcl_poisson", "type: pcl_magic"), "unknown pipeline 'pcl_magic'")
config("unknown_shape", GOOD.replace("{type: sphere}", "{type: dodecahedron}"), "dodecahedron")
config("unknown_sampler", GOOD.replace("type: area", "type: telepathy"), "telepathy")
config("unknown_corruption", GOOD.replace("count: 500}", "count: 500}\n    corruptions: [{type: gremlins}]"), "gremlins")
config("missing_datasets", "experiment: x\npipelines: [{type: pcl_poisson}]\n", "datasets: expected a non-empty list")
config("empty_pipelines", GOOD.split("pipelines:")[0] + "pipelines: []\n", "pipelines: expected a non-empty list")
config("bad_experiment_name", GOOD.replace("experiment: robust", "experiment: ../../etc"), "experiment: '../../etc' must be")
config("duplicate_names", GOOD + "  - {name: poisson, type: pcl_gp3}\n", "'poisson' used twice")
config("sweep_bad_key", GOOD + "sweep: [{key: pipelines.nosuch.options.depth, values: [4, 5]}]\n", "no entry named 'nosuch'")
config("sweep_no_values", GOOD + "sweep: [{key: seed, values: []}]\n", "sweep[0].values: expected a non-empty list")
config("sweep_bad_value", GOOD + "sweep: [{key: pipelines.poisson.options.depth, values: [5, 99]}]\n", "depth: must be in")
values = "[" + ", ".join(str(v) for v in range(1, 21)) + "]"
config("sweep_explosion", GOOD + "sweep:\n" + "".join(f"  - {{key: '{k}', values: {values}}}\n" for k in
       ["seed", "timeout_seconds", "description", "datasets[0].sampler.count", "metrics.fscore_tau_ratio"]),
       "sweep: more than 1000 combinations")
config("list_as_key", "[a, b]: 1\n" + GOOD, "the top level: a key is a list, not a name")
config("list_as_option_key", GOOD.replace("{depth: 5}", "{[depth]: 5}"), "pipelines[0].options: a key is a list")
config("sweep_whole_list", GOOD + "sweep: {key: datasets, values: [x]}\n", "sweep[0].key: 'datasets' replaces the datasets list")
config("missing_model_file", GOOD.replace("{type: sphere}", "{type: file, points: /nonexistent/model.ply}").replace(
           "{type: area, count: 500}", "{type: none}"),
       "/nonexistent/model.ply")
config("table_unknown_column", GOOD + "table: {columns: [dataset, flux_capacitance]}\n", "flux_capacitance")
config("deep_nesting", "experiment: deep\ndescription: " + "[" * 20000 + "]" * 20000 + "\n", "deep_nesting.yaml")
config("alias_bomb", "experiment: bomb\na: &a [x, x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
       "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\nd: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
       "e: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d, *d]\nf: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e, *e]\n",
       "unknown key")

with open(os.path.join(CORPUS, "expectations.txt"), "w") as f:
    f.write("# Written by make_corpus.py: <file> | <error|either> | <substring the error message must contain>\n")
    for rel, outcome, expect in entries:
        f.write(f"{rel} | {outcome} | {expect}\n")
print(len(entries), "entries")
