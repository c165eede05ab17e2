from setuptools import find_packages, setup

package_name = 'ament_pep257'

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
    description='Checks Python docstrings against PEP 257 as ament does, with ruff.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': ['ament_pep257 = ament_pep257.main:main'],
        'pytest11': ['ament_pep257 = ament_pep257.pytest_marker'],
    },
)
