from setuptools import find_packages, setup

package_name = 'ament_copyright'

setup(
    name=package_name,
    version='0.17.1',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Checks that source files carry a copyright notice and a known license.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': ['ament_copyright = ament_copyright.main:main'],
        'pytest11': ['ament_copyright = ament_copyright.pytest_marker'],
    },
)
