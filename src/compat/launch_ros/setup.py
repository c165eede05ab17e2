from setuptools import find_packages, setup

package_name = 'launch_ros'

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
    description='ROS-specific launch actions: Node, PushRosNamespace, SetParameter, SetRemap...',
    license='Apache-2.0',
    tests_require=['pytest'],
    # launch's frontend imports every module of this group, as upstream's launch does, so that the
    # XML/YAML tags and `$(...)` names launch_ros exposes are known (importing launch_ros registers them).
    entry_points={
        'launch.frontend.launch_extension': [
            'launch_ros = launch_ros',
        ],
    },
)
