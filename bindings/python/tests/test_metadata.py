"""The package's metadata: one version everywhere (include/horopter/version.h,
horopter.__version__, `horopter --version`, pyproject.toml), and the
Apache-2.0 licence in LICENSE and pyproject.toml."""
import os
import re
import subprocess

import pytest

import horopter


def header_version(source_dir):
    path = os.path.join(source_dir, "include", "horopter", "version.h")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        text = f.read()
    parts = [re.search(rf"#define HOROPTER_VERSION_{p} (\d+)", text).group(1)
             for p in ("MAJOR", "MINOR", "PATCH")]
    assert f'#define HOROPTER_VERSION_STRING "{".".join(parts)}"' in text
    return ".".join(parts)


def test_module_version_is_the_headers(source_dir):
    assert re.fullmatch(r"\d+\.\d+\.\d+", horopter.__version__)
    expected = header_version(source_dir)
    if expected is not None:  # an installed module may run without the sources
        assert horopter.__version__ == expected


def test_pyproject_version_is_the_headers(source_dir):
    expected = header_version(source_dir)
    pyproject = os.path.join(source_dir, "bindings", "python", "pyproject.toml")
    if expected is None or not os.path.exists(pyproject):
        return
    with open(pyproject) as f:
        match = re.search(r'^version = "([^"]+)"', f.read(), re.MULTILINE)
    assert match and match.group(1) == expected


def test_cli_version_is_the_modules(cli):
    for flag in ("--version", "-V"):
        out = subprocess.run([cli, flag], check=True, capture_output=True, text=True).stdout
        assert out == f"horopter {horopter.__version__}\n"


def test_license_is_apache_2(source_dir):
    license_file = os.path.join(source_dir, "LICENSE")
    pyproject = os.path.join(source_dir, "bindings", "python", "pyproject.toml")
    if not os.path.exists(license_file) or not os.path.exists(pyproject):
        return  # an installed module may run without the sources
    with open(license_file) as f:
        text = f.read()
    assert "Apache License" in text and "Version 2.0, January 2004" in text
    assert "END OF TERMS AND CONDITIONS" in text
    with open(pyproject) as f:
        assert 'license = {text = "Apache-2.0"}' in f.read()


def read_toml(path):
    tomllib = pytest.importorskip("tomllib", reason="tomllib needs Python 3.11+")
    with open(path, "rb") as f:
        return tomllib.load(f)


def test_root_pyproject_builds_this_package(source_dir):
    """`pip install .` at the root: the same package as bindings/python's
    (name, version = version.h, licence, dependencies), the module's target
    only, the tests and bench off. Checked without running pip (minutes)."""
    expected = header_version(source_dir)
    root = os.path.join(source_dir, "pyproject.toml")
    if expected is None or not os.path.exists(root):
        pytest.skip("an installed module without the sources")
    top = read_toml(root)
    bindings = read_toml(os.path.join(source_dir, "bindings", "python", "pyproject.toml"))
    assert top["project"]["name"] == "horopter"
    assert top["project"]["version"] == expected
    for key in ("name", "version", "license", "dependencies", "requires-python"):
        assert top["project"][key] == bindings["project"][key], key
    assert top["build-system"]["build-backend"] == "scikit_build_core.build"
    build = top["tool"]["scikit-build"]
    assert build["build"]["targets"] == ["horopter_python"]
    defines = build["cmake"]["define"]
    assert defines["HOROPTER_BUILD_PYTHON"] == "ON"
    for off in ("HOROPTER_BUILD_TESTS", "HOROPTER_BUILD_BENCH", "HOROPTER_INSTALL"):
        assert defines[off] == "OFF", off
    assert os.path.exists(os.path.join(source_dir, top["project"]["readme"]))
