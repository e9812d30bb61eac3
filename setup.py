"""The build behind pyproject.toml: CMake builds the module batchccd._batchccd
(python/CMakeLists.txt, for the interpreter running pip), setuptools packages
it with python/batchccd (the package, its stubs and py.typed).

BATCHCCD_CMAKE_BUILD_DIR=DIR takes the module from an existing CMake build
instead (building its target there if it is out of date), for an interpreter
of the same version as DIR's BATCHCCD_PYTHON_EXECUTABLE.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent
MODULE_TARGET = "batchccd_python"  # python/CMakeLists.txt


def project_version():
    text = (SOURCE / "CMakeLists.txt").read_text()
    return re.search(r"project\(batchccd VERSION (\S+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("BATCHCCD_CMAKE_BUILD_DIR")
        build_dir = pathlib.Path(given).resolve() if given else pathlib.Path(self.build_temp).resolve() / "cmake"
        if not given:
            self.configure(build_dir)
        elif not (build_dir / "CMakeCache.txt").exists():
            sys.exit(f"BATCHCCD_CMAKE_BUILD_DIR={given}: no configured CMake build there")
        # Ninja's own parallelism, or CMAKE_BUILD_PARALLEL_LEVEL's.
        subprocess.run(["cmake", "--build", str(build_dir), "--target", MODULE_TARGET], check=True)
        built = build_dir / "python" / "batchccd" / ("_batchccd" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.exists():
            sys.exit(f"CMake built no {built.name} in {built.parent}: the module is for another interpreter "
                     f"than {sys.executable} (BATCHCCD_PYTHON_EXECUTABLE)")
        destination = pathlib.Path(self.get_ext_fullpath(ext.name))
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, destination)

    def configure(self, build_dir):
        # The module alone: no tests, benchmarks, tool, MPI or install rules.
        arguments = ["cmake", "-S", str(SOURCE), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                     "-DBATCHCCD_BUILD_TESTS=OFF", "-DBATCHCCD_BUILD_BENCH=OFF", "-DBATCHCCD_BUILD_CLI=OFF",
                     "-DBATCHCCD_MPI=OFF", "-DBATCHCCD_INSTALL=OFF", "-DBATCHCCD_PYTHON=ON",
                     f"-DBATCHCCD_PYTHON_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja") and not (build_dir / "CMakeCache.txt").exists():
            arguments += ["-G", "Ninja"]
        subprocess.run(arguments, check=True)


setup(
    version=project_version(),
    package_dir={"": "python"},
    packages=["batchccd"],
    package_data={"batchccd": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("batchccd._batchccd", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # Not build/: that is the CMake build of README and ./dev.
    options={"build": {"build_base": "build-pip"}},
    zip_safe=False,
)
