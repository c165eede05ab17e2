from setuptools import find_packages, setup

package_name = 'turtlesim_py'

setup(
    name=package_name,
    version='1.4.2',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description="turtlesim's Python nodes; the turtlesim package's executables start them.",
    license='Apache-2.0',
    tests_require=['pytest'],
)
