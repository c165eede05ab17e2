import os
from glob import glob

from setuptools import find_packages, setup

package_name = 'olive_launch'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        # As in the course: every launch file (.py, .xml, .yaml) goes to share/<package>/launch.
        (os.path.join('share', package_name, 'launch'),
         glob(os.path.join('launch', '*launch.[pxy][yma]*'))),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Section 3.9 of the Owl Kit course: launch files for two turtlesim nodes.',
    license='Apache-2.0',
    tests_require=['pytest'],
)
