# The package's Python modules (rigid_body_sim.testing; its messages and configs are generated beside them),
# installed by catkin_python_setup(): never run this file by hand.
from setuptools import setup

from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=["rigid_body_sim"], package_dir={"": "src"}))
