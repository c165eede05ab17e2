from setuptools import find_packages, setup

package_name = 'owl_rosdep'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    package_data={package_name: ['ros_wheels.tsv']},
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='rosdep install/check backed by the installed packages and the pinned ROS wheels.',
    license='Apache-2.0',
    tests_require=['pytest'],
    # `rosdep` goes to <prefix>/bin, which the workspace setup puts on PATH.
    entry_points={
        'console_scripts': [
            'rosdep = owl_rosdep.cli:main',
        ],
    },
)
