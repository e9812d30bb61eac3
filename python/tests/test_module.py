"""The module's face: version, docstrings, the stub beside it."""
import pathlib
import re

import batchccd

REPO = pathlib.Path(__file__).resolve().parents[2]


def test_version_is_the_projects():
    project = re.search(r"project\(batchccd VERSION (\S+)", (REPO / "CMakeLists.txt").read_text()).group(1)
    assert batchccd.__version__ == project


def test_every_function_has_a_docstring_like_the_header():
    for name in batchccd.__all__:
        item = getattr(batchccd, name)
        if callable(item):
            assert item.__doc__ and len(item.__doc__) > 40, name
    assert "Bad input" in batchccd.mesh_ccd.__doc__
    assert "Options (keyword-only" in batchccd.batch_ccd.__doc__
    assert "mode=\"conservative\"" in batchccd.vertex_face_ccd.__doc__


def test_stub_beside_the_module_names_everything():
    package = pathlib.Path(batchccd.__file__).parent
    stub = (package / "__init__.pyi").read_text()
    assert (package / "py.typed").exists()
    for name in batchccd.__all__:
        assert re.search(rf"\b{name}\b", stub), name
    for option in batchccd.default_options():
        assert f"    {option}:" in stub, option


def test_input_error_is_a_value_error(tmp_path):
    (tmp_path / "t0.ply").write_text("not a ply\n")
    (tmp_path / "t1.ply").write_text("not a ply\n")
    try:
        batchccd.read_scene(str(tmp_path))
    except batchccd.InputError as error:
        assert isinstance(error, ValueError) and "t0.ply" in str(error)
    else:
        raise AssertionError("read_scene accepted a malformed scene")
