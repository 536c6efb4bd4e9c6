"""pip route to the Python module: CMake builds the extension, setuptools packages it.

    python3 -m venv --system-site-packages venv
    venv/bin/pip install --no-build-isolation --no-deps .

works on Debian 12 without network (docs/python.md). NSBRIDGE_BUILD_DIR names a CMake build
folder to build in (default: one inside setuptools' temporary folder).
"""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    """Builds the CMake target _nsbridge and copies it where setuptools expects it."""

    def build_extension(self, ext):
        build = pathlib.Path(os.environ.get("NSBRIDGE_BUILD_DIR") or
                             pathlib.Path(self.build_temp).resolve() / "cmake")
        subprocess.check_call(["cmake", "-S", str(SOURCE), "-B", str(build),
                               "-DCMAKE_BUILD_TYPE=Release", "-DNSB_BUILD_BENCHMARKS=OFF",
                               f"-DPython_EXECUTABLE={sys.executable}"],
                              stdout=subprocess.DEVNULL)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_nsbridge",
                               "-j", str(os.cpu_count() or 2)])
        built = sorted((build / "python" / "nsbridge").glob("_nsbridge*.so"))
        if not built:
            raise RuntimeError(f"the CMake build in {build} made no _nsbridge module")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


def version():
    for line in (SOURCE / "CMakeLists.txt").read_text().splitlines():
        if line.startswith("project(nsbridge VERSION"):
            return line.split()[2]
    return "0"


setup(
    name="nsbridge",
    version=version(),
    description="Nonsmooth seismic response of bridges with deck-abutment pounding",
    packages=["nsbridge"],
    package_dir={"": "python"},
    ext_modules=[Extension("nsbridge._nsbridge", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.9",
    zip_safe=False,
)
