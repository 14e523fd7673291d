"""The installed wheel, tested from Python: the `viewray` command it installs and the
`viewray` module, checked against the command and against the lecture's formulas.

`cargo xtask wheel --test` builds the wheel, installs it into a fresh virtual
environment with pytest and Pillow (an image decoder independent of viewray), and runs
this file there. It needs nothing else from the repository but the fixtures.
"""

import ast
import doctest
import json
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import viewray

ROOT = Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "fixtures"
SCENES = sorted(
    [FIXTURES / "default.ron"]
    + list((FIXTURES / "scenes").glob("*.ron"))
    + list((FIXTURES / "homework").glob("*.ron"))
    + list((FIXTURES / "animations").glob("*.ron"))
)
BAD_SCENES = sorted((FIXTURES / "bad").glob("*.ron"))


def viewray_command(*args, check=True):
    """Runs the `viewray` command the wheel installed."""
    return subprocess.run(
        [COMMAND, *map(str, args)], capture_output=True, text=True, check=check
    )


def json_lines(text):
    return [json.loads(line) for line in text.splitlines()]


def vector(value):
    """A JSON vector as the module gives it: None (no ray) is NaN."""
    return np.full(3, np.nan) if value is None else np.array(value, dtype=np.float64)


def same(a, b):
    """Equal numbers, NaN equal to NaN."""
    return np.array_equal(a, b, equal_nan=True)


COMMAND = shutil.which("viewray")


def test_the_wheel_installs_the_command_beside_the_module():
    assert COMMAND is not None, "no viewray command on PATH"
    # The command is the wheel's, in this environment's scripts folder (beside its
    # python, which may be a link to the interpreter it was made from).
    assert Path(COMMAND).parent == Path(sys.executable).parent
    version = viewray_command("--version").stdout
    assert version.startswith(f"viewray {viewray.__version__}"), version
    frame = json_lines(
        viewray_command("frame", FIXTURES / "homework" / "canonical_2x2.ron").stdout
    )
    assert frame == [
        {"e": [0.0, 0.0, 0.0], "u": [1.0, 0.0, 0.0], "v": [0.0, 1.0, 0.0], "w": [0.0, 0.0, 1.0]}
    ]


def test_rays_are_the_lectures_formula():
    # The canonical camera, 2 x 2: u = ((j - 1/2)/W - 1/2) vw, v = -((i - 1/2)/H - 1/2) vh,
    # direction (u, v, -d), worked out here with NumPy.
    scene = viewray.Scene.load(FIXTURES / "homework" / "canonical_2x2.ron")
    origins, directions = scene.rays()
    assert origins.shape == directions.shape == (2, 2, 3)
    assert origins.dtype == directions.dtype == np.float64
    i, j = np.meshgrid(np.arange(1, 3), np.arange(1, 3), indexing="ij")
    u = ((j - 0.5) / 2 - 0.5) * 1.0
    v = -((i - 0.5) / 2 - 0.5) * 1.0
    expected = np.stack([u, v, -np.ones_like(u)], axis=-1)
    assert same(directions, expected)
    assert same(origins, np.zeros((2, 2, 3)))

    # With a lens shift: (i, j) = (1, 3) has u = 1, v = 1/4 and direction
    # (u + sx, v + sy, -d) = (1.5, 0.5, -2) from the eye (1, 0, 0).
    scene = viewray.Scene.load(str(FIXTURES / "homework" / "shifted_3x2.ron"))
    origins, directions = scene.rays()
    assert same(directions[0, 2], [1.5, 0.5, -2.0])
    assert same(origins[0, 2], [1.0, 0.0, 0.0])


def lecture_rays(mistake=None):
    """The rays of `fixtures/scenes/perspective_general.ron`'s camera (240 x 180, d = 1,
    viewport 0.8 x 0.6, no shift, as the file says) as a student computes them with
    NumPy from the lecture's formulas, with `mistake` (a catalogue id) made: u, v from
    (i, j), then origin e and direction u U + v V - d W in the frame viewray prints."""
    scene = viewray.Scene.load(FIXTURES / "scenes" / "perspective_general.ron")
    frame = scene.frame()
    width, height, d, vw, vh = 240, 180, 1.0, 0.8, 0.6
    assert (scene.width, scene.height) == (width, height)
    i, j = np.meshgrid(np.arange(1, height + 1), np.arange(1, width + 1), indexing="ij")
    if mistake == "pixel-corner":
        u = ((j - 1) / width - 0.5) * vw
        v = -((i - 1) / height - 0.5) * vh
    else:
        u = ((j - 0.5) / width - 0.5) * vw
        v = -((i - 0.5) / height - 0.5) * vh
    if mistake == "v-sign":
        v = -v
    if mistake == "u-sign":
        u = -u
    directions = u[..., None] * frame["u"] + v[..., None] * frame["v"] - d * frame["w"]
    origins = np.broadcast_to(frame["e"], directions.shape).copy()
    return scene, origins, directions


def test_check_passes_right_arrays_and_names_planted_mistakes():
    scene, origins, directions = lecture_rays()
    report = viewray.check(scene, origins, directions)
    assert report.ok and report.wrong == 0 and report.mistakes == [], str(report)
    # Normalized directions are right too, unless asked to be exact.
    unit = directions / np.linalg.norm(directions, axis=-1, keepdims=True)
    assert viewray.check(scene, origins, unit).ok
    assert not viewray.check(scene, origins, unit, exact_direction=True).ok
    for mistake in ["v-sign", "u-sign", "pixel-corner"]:
        scene, origins, directions = lecture_rays(mistake)
        report = viewray.check(scene, origins=origins, directions=directions)
        assert not report.ok
        assert mistake in report.mistakes, str(report)
        assert [mistake] in report.alternatives
        # The same words as the command.
        assert "the catalogue explains them" in str(report)
        assert "you wrote:" in str(report)


def test_check_refuses_arrays_of_another_shape_or_dtype():
    scene, origins, directions = lecture_rays()
    with pytest.raises(ValueError, match=r"directions: expected a float64 array of shape"):
        viewray.check(scene, origins, directions[:, :-1])
    with pytest.raises(ValueError, match=r"origins: expected a float64 array"):
        viewray.check(scene, origins.astype(np.float32), directions)
    with pytest.raises(ValueError, match=r"tolerance"):
        viewray.check(scene, origins, directions, tolerance=-1.0)


def sampled_pixels(height, width, count=24, seed=44):
    """The four corners, the centre and `count` pixels drawn with a fixed seed."""
    rng = np.random.default_rng(seed)
    pixels = {(0, 0), (0, width - 1), (height - 1, 0), (height - 1, width - 1)}
    pixels.add((height // 2, width // 2))
    rows = rng.integers(0, height, count)
    cols = rng.integers(0, width, count)
    pixels.update(zip(rows.tolist(), cols.tolist()))
    return sorted(pixels)


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
def test_rays_equal_the_commands_at_sampled_pixels(path):
    scene = viewray.Scene.load(path)
    origins, directions = scene.rays()
    assert origins.shape == directions.shape == (scene.height, scene.width, 3)
    pixels = sampled_pixels(scene.height, scene.width)
    args = [arg for row, col in pixels for arg in ("--pixel", f"{row},{col}")]
    lines = json_lines(viewray_command("rays", path, *args).stdout)
    assert len(lines) == len(pixels)
    for (row, col), line in zip(pixels, lines):
        assert (line["row"], line["col"]) == (row, col)
        # The command prints each number's shortest round trip: parsed, it is the same
        # float64 (minus zero is printed 0, and 0.0 == -0.0).
        assert same(origins[row, col], vector(line["origin"])), (row, col)
        assert same(directions[row, col], vector(line["direction"])), (row, col)


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
def test_the_frame_and_projections_equal_the_commands(path):
    scene = viewray.Scene.load(path)
    frame = scene.frame()
    (line,) = json_lines(viewray_command("frame", path).stdout)
    assert sorted(frame) == ["e", "u", "v", "w"]
    for name in "euvw":
        assert frame[name].shape == (3,) and frame[name].dtype == np.float64
        assert same(frame[name], np.array(line[name])), name

    # Points in front of the eye, around it, behind it, and far away.
    e, w = frame["e"], frame["w"]
    rng = np.random.default_rng(7)
    points = np.vstack([e - 3 * w, e + 3 * w, e + rng.normal(scale=4.0, size=(12, 3))])
    xy = scene.project(points)
    assert xy.shape == (len(points), 2) and xy.dtype == np.float64
    args = [arg for p in points for arg in ("--point", ",".join(repr(float(c)) for c in p))]
    lines = json_lines(viewray_command("project", path, *args).stdout)
    for k, line in enumerate(lines):
        x = np.nan if line["x"] is None else line["x"]
        y = np.nan if line["y"] is None else line["y"]
        assert same(xy[k], [x, y]), (k, line)


def test_a_point_on_a_pixels_ray_projects_to_its_centre():
    # project(ray(row, col).at(t)) == (col + 1/2, row + 1/2) for any t > 0.
    scene = viewray.Scene.load(FIXTURES / "scenes" / "perspective_canonical.ron")
    origins, directions = scene.rays()
    rows, cols = np.array([0, 17, 199]), np.array([5, 100, 199])
    points = origins[rows, cols] + 2.5 * directions[rows, cols]
    xy = scene.project(points)
    assert np.allclose(xy, np.stack([cols + 0.5, rows + 0.5], axis=-1), rtol=0, atol=1e-9)
    # Behind the eye nothing is seen.
    assert np.isnan(scene.project(origins[rows, cols] - directions[rows, cols])).all()
    assert scene.project(np.zeros((0, 3))).shape == (0, 2)


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
def test_a_render_is_the_commands_png_byte_for_byte(path, tmp_path):
    scene = viewray.Scene.load(path)
    pixels = scene.render()
    assert pixels.dtype == np.uint8
    assert pixels.shape == (scene.height, scene.width, 3)
    png = tmp_path / "render.png"
    viewray_command("render", path, "-o", png)
    with Image.open(png) as decoded:
        assert decoded.mode == "RGB"
        assert np.array_equal(np.asarray(decoded), pixels)


def test_samples_replace_the_scenes_as_the_commands_option_does(tmp_path):
    path = FIXTURES / "scenes" / "distortion_tilted.ron"
    scene = viewray.Scene.load(path)
    png = tmp_path / "one.png"
    viewray_command("render", path, "--samples", "1", "-o", png)
    one = scene.render(samples=1)
    with Image.open(png) as decoded:
        assert np.array_equal(np.asarray(decoded), one)
    assert not np.array_equal(one, scene.render()), "the scene's own samples antialias"


def test_a_scene_parses_from_text():
    text = (FIXTURES / "homework" / "canonical_2x2.ron").read_text()
    scene = viewray.Scene.parse(text)
    assert (scene.width, scene.height) == (2, 2)
    assert same(scene.rays()[1], viewray.Scene.load(FIXTURES / "homework" / "canonical_2x2.ron").rays()[1])
    assert repr(scene) == "<viewray.Scene <string>: 2 x 2, 1 sample>"


def test_the_rays_of_a_full_hd_image_take_well_under_a_second():
    scene = viewray.Scene.parse(
        "(image: (width: 1920, height: 1080), camera: (eye: (0.0, 0.0, 0.0), "
        "view: (0.0, 0.0, -1.0), projection: Perspective(distance: 1.0, "
        "viewport: (1.7777777777777777, 1.0))))"
    )
    started = time.perf_counter()
    origins, directions = scene.rays()
    seconds = time.perf_counter() - started
    assert directions.shape == (1080, 1920, 3)
    assert seconds < 0.5, f"{seconds:.3f} s"
    # The last pixel's direction, by the formula.
    u = ((1920 - 0.5) / 1920 - 0.5) * (16 / 9)
    v = -((1080 - 0.5) / 1080 - 0.5)
    assert np.allclose(directions[-1, -1], [u, v, -1.0], rtol=0, atol=1e-15)


def test_rendering_releases_the_gil():
    # While one thread renders, another runs Python: its ticks fall inside the render.
    scene = viewray.Scene.load(FIXTURES / "default.ron")
    window = {}

    def render():
        window["start"] = time.perf_counter()
        scene.render(samples=4)
        window["end"] = time.perf_counter()

    worker = threading.Thread(target=render)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    inside = [t for t in ticks if window["start"] < t < window["end"]]
    assert window["end"] - window["start"] > 0.05, "the render is too quick to tell"
    assert len(inside) >= 10, f"{len(inside)} ticks during a {window['end'] - window['start']:.3f} s render"


@pytest.mark.parametrize("path", BAD_SCENES, ids=lambda p: p.stem)
def test_a_bad_scene_raises_scene_error_with_the_commands_words(path):
    with pytest.raises(viewray.SceneError) as raised:
        viewray.Scene.load(path)
    error = raised.value
    failed = viewray_command("frame", path, check=False)
    assert failed.returncode == 2
    assert failed.stderr.strip() == f"error: {error}"
    assert isinstance(error, Exception)
    assert error.path == str(path)
    assert isinstance(error.message, str) and error.message
    if error.line is None:
        assert error.column is None
        assert str(error) == f"{path}: {error.message}"
    else:
        assert isinstance(error.line, int) and isinstance(error.column, int)
        assert str(error) == f"{path}:{error.line}:{error.column}: {error.message}"


def test_a_scene_error_keeps_its_position():
    with pytest.raises(viewray.SceneError) as raised:
        viewray.Scene.parse("(\n    image: (width: 0, height: 2),\n    camera: Front(size: 1.0),\n)")
    error = raised.value
    assert (error.path, error.line, error.column) == ("<string>", 2, 12)
    assert str(error).startswith("<string>:2:12: image: ")
    with pytest.raises(viewray.SceneError) as raised:
        viewray.Scene.load("no/such/scene.ron")
    assert (raised.value.path, raised.value.line, raised.value.column) == ("no/such/scene.ron", None, None)
    assert str(raised.value) == "no/such/scene.ron: no such scene file"


@pytest.mark.parametrize(
    "points, found",
    [
        ([[0.0, 0.0, -1.0]], "found list"),
        (np.zeros(3), "found a float64 array of shape (3,)"),
        (np.zeros((2, 4)), "found a float64 array of shape (2, 4)"),
        (np.zeros((2, 3), dtype=np.int64), "found an int64 array of shape (2, 3)"),
        (np.zeros((2, 3), dtype=np.float32), "found a float32 array of shape (2, 3)"),
        (None, "found NoneType"),
    ],
)
def test_wrong_points_raise_value_error_naming_what_was_expected(points, found):
    scene = viewray.Scene.load(FIXTURES / "homework" / "canonical_2x2.ron")
    with pytest.raises(ValueError) as raised:
        scene.project(points)
    message = str(raised.value)
    assert message.startswith("points: expected a float64"), message
    assert "shape (N, 3)" in message and found in message, message


def test_strided_and_odd_points_project_without_failing():
    scene = viewray.Scene.load(FIXTURES / "homework" / "canonical_2x2.ron")
    points = np.zeros((4, 6))[:, ::2]  # a view with strides, not a contiguous array
    points[:, 2] = -1.0
    assert same(scene.project(points), np.ones((4, 2)))
    odd = np.array([[np.nan, 0.0, -1.0], [np.inf, 0.0, -1.0], [0.0, 0.0, 0.0], [1e308, 1e308, -1e-308]])
    xy = scene.project(odd)
    assert xy.shape == (4, 2)
    assert np.isnan(xy[0]).all()


@pytest.mark.parametrize("samples", [0, -1, 65537, 2**40])
def test_samples_out_of_range_raise_value_error(samples):
    scene = viewray.Scene.load(FIXTURES / "homework" / "canonical_2x2.ron")
    with pytest.raises(ValueError, match=r"^samples: expected a whole number of samples from 1 to 65536, found "):
        scene.render(samples=samples)


def test_wrong_argument_types_raise_type_error():
    with pytest.raises(TypeError):
        viewray.Scene.load(42)
    with pytest.raises(TypeError):
        viewray.Scene.parse(b"bytes")
    scene = viewray.Scene.load(FIXTURES / "homework" / "canonical_2x2.ron")
    with pytest.raises(TypeError):
        scene.render(samples="four")
    with pytest.raises(TypeError):
        scene.render(4, 5)


def test_the_type_stub_is_shipped_and_names_what_the_module_has():
    stub = Path(viewray.__file__).with_name("__init__.pyi")
    assert stub.is_file(), f"no type stub beside {viewray.__file__}"
    assert stub.with_name("py.typed").is_file()
    tree = ast.parse(stub.read_text())
    top = {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    top |= {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    public = {n for n in dir(viewray) if not n.startswith("_") and not isinstance(getattr(viewray, n), type(viewray))}
    assert top == public | {"__version__"}
    (scene_stub,) = [n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Scene"]
    members = {n.name for n in scene_stub.body if isinstance(n, ast.FunctionDef)}
    assert members == {n for n in dir(viewray.Scene) if not n.startswith("_")}


def test_the_readmes_notebook_example_prints_what_it_shows(monkeypatch):
    readme = (ROOT / "README.md").read_text()
    section = readme.split("\n## Install with pip\n", 1)[1]
    example = section.split("```pycon\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(ROOT)
    test = doctest.DocTestParser().get_doctest(example, {}, "README", "README.md", 0)
    assert len(test.examples) == 5, "the README promises five lines"
    report = []
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test, out=report.append)
    assert runner.failures == 0, "".join(report)
