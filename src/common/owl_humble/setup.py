from setuptools import find_packages, setup

package_name = 'owl_humble'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=False,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description=('ROS 2 Humble beside our Jazzy: the Humble discovery layout, a Humble-wire module '
                 'twin and the discovery bridge that shows Humble nodes to our tools.'),
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'humble_twin = owl_humble.twin:main',
            'discovery_bridge = owl_humble.bridge:main',
        ],
    },
)
