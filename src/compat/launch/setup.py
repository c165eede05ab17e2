from setuptools import find_packages, setup

package_name = 'launch'

setup(
    name=package_name,
    version='0.1.0',
    # launch_xml and launch_yaml are upstream's frontend modules; here they ship with launch.
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    # The frontend finds its parsers through this group, as upstream's launch_xml and launch_yaml
    # declare them.
    entry_points={
        'launch.frontend.parser': [
            'xml = launch_xml:Parser',
            'yaml = launch_yaml:Parser',
        ],
    },
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='The ROS 2 launch system (Python, XML and YAML launch files).',
    license='Apache-2.0',
    tests_require=['pytest'],
)
