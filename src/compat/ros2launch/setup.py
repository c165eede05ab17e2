from setuptools import find_packages, setup

package_name = 'ros2launch'

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
    description='The ros2 launch command.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'ros2cli.command': ['launch = ros2launch.command.launch:LaunchCommand'],
    },
)
