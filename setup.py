"""The build's one step that pyproject.toml cannot state: docs/ ships inside the package
as ``beltmdsm.docs`` (its pages print installed: ``beltmdsm docs``), but its ``conf.py``
is the documentation site's Sphinx configuration, not a module of the package, and is
left out of the wheel (issue 37 item 5). Everything else is in pyproject.toml.
"""

from setuptools import setup
from setuptools.command.build_py import build_py

#: (package, module) pairs that stay out of the wheel.
LEFT_OUT = {("beltmdsm.docs", "conf")}


class BuildPy(build_py):
    def find_package_modules(self, package, package_dir):
        found = super().find_package_modules(package, package_dir)
        return [m for m in found if (m[0], m[1]) not in LEFT_OUT]


setup(cmdclass={"build_py": BuildPy})
