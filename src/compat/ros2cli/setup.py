from setuptools import find_packages, setup

package_name = 'ros2cli'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='The ros2 command line tool, compatible with upstream ros2cli.',
    license='Apache-2.0',
    tests_require=['pytest'],
    # `ros2` goes to <prefix>/bin, which the workspace setup puts on PATH.
    entry_points={
        'console_scripts': [
            'ros2 = ros2cli.cli:main',
        ],
    },
)
