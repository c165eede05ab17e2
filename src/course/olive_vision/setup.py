from glob import glob

from setuptools import find_packages, setup

package_name = 'olive_vision'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
        ('share/' + package_name + '/launch', glob('launch/*.launch.py')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Sections 4.6 and 4.7 of the Owl Kit course: object tracking and gesture control.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'track_object = olive_vision.track_object:main',
            'gesture_control = olive_vision.gesture_control:main',
        ],
    },
)
