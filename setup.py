"""pip route to the Python module: CMake builds the extension, setuptools packages it.

    python3 -m venv --system-site-packages venv
    venv/bin/pip install --no-build-isolation --no-deps .

works on Debian 12 without network (docs/python.md). The CMake build folder is
NSBRIDGE_BUILD_DIR when set (setuptools' own files go there too, so the source tree is left
alone), else build/pip/ of the source tree (beside, not inside, the folders of a CMake build).
A folder is reused by the next install: CMake rebuilds what changed. Nothing stale is
packaged: the configuration is given again on every install (build type, this interpreter),
and the module copied is the one named for this interpreter (its EXT_SUFFIX), never a module
left in the folder for another Python. CMAKE_CXX_COMPILER_LAUNCHER (e.g. ccache) in the
environment is passed to CMake.
"""
import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent
BUILD = pathlib.Path(os.environ.get("NSBRIDGE_BUILD_DIR") or SOURCE / "build" / "pip").resolve()


class CMakeBuild(build_ext):
    """Builds the CMake target _nsbridge and copies it where setuptools expects it."""

    def build_extension(self, ext):
        cmake = BUILD / "cmake"
        subprocess.check_call(["cmake", "-S", str(SOURCE), "-B", str(cmake),
                               "-DCMAKE_BUILD_TYPE=Release", "-DNSB_BUILD_BENCHMARKS=OFF",
                               f"-DPython_EXECUTABLE={sys.executable}"],
                              stdout=subprocess.DEVNULL)
        subprocess.check_call(["cmake", "--build", str(cmake), "--target", "_nsbridge",
                               "-j", str(os.cpu_count() or 2)])
        built = cmake / "python" / "nsbridge" / ("_nsbridge" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.exists():
            raise RuntimeError(f"the CMake build in {cmake} made no {built.name} for {sys.executable}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


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
    options={"build": {"build_base": str(BUILD / "setuptools")},
             "egg_info": {"egg_base": str(BUILD)}},
    python_requires=">=3.9",
    zip_safe=False,
)
